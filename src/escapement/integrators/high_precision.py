"""A high-precision reference in mpmath (50 significant digits by default), hand-written because no library
integrates an impulsive system with events in arbitrary precision. Each arc's time comes from the phase angles of
its start and end taken separately, independently of the exact solver's kinematics.
"""

from __future__ import annotations

import mpmath

from ..model import automaton
from ..model.arguments import Numeric
from ..model.automaton import Mode
from ..model.events import EventKind
from ..model.kinematics import time_to_rest
from ..model.limits import MAX_DIGITS, MIN_DIGITS, check_count, run_spec
from ..model.parameters import Parameters
from ..solvers.result import Solution
from .driver import NO_EVENT, Step, drive

__all__ = ["MpmathStepper", "solve_high_precision"]


class MpmathStepper:
    """Each arc in ``dps``-digit arithmetic, from the phase angles of its ends."""

    def __init__(self, params: Parameters, dps: int) -> None:
        self.name, self.two_pi = f"mpmath {dps} digits", 2 * mpmath.pi
        self.w = mpmath.sqrt(mpmath.mpf(params.K) / mpmath.mpf(params.M))
        self.offset = mpmath.mpf(params.F) / mpmath.mpf(params.K)
        self.targets = {kind: (mpmath.mpf(automaton.position(kind, params)), s.direction)
                        for kind, s in automaton.SURFACES.items()}

    def next_event(self, mode: Mode, centre: Numeric, t: Numeric, x: Numeric, v: Numeric,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step:
        """As :meth:`Stepper.next_event <escapement.integrators.driver.Stepper.next_event>`."""
        w, c = self.w, automaton.CENTRE_SIGN[int(mode)] * self.offset
        x = mpmath.mpf(x)
        start = mpmath.atan2(v / w, x - c)
        radius = mpmath.sqrt((x - c) ** 2 + (v / w) ** 2)
        best = None
        for kind in watched:
            target, direction = self.targets[kind]
            v_sq = v**2 + w**2 * ((x - c) ** 2 - (target - c) ** 2)
            if v_sq <= 0:
                continue
            v_end = direction * mpmath.sqrt(v_sq)
            end = mpmath.atan2(v_end / w, target - c)
            angle = (start - end) % self.two_pi or self.two_pi  # the phase point turns clockwise: in (0, 2 pi]
            if best is None or angle < best[3]:
                best = (kind, angle / w, v_end, angle, target)
        if best is None:
            if mode == automaton.Mode.FREE:
                return Step(NO_EVENT, mpmath.inf, 0, radius)
            dt, turning = time_to_rest(c, x, v, w, mpmath)  # the next rest, in the zone
            return Step(NO_EVENT, dt, 0, turning)
        kind, dt, v_end, angle, target = best
        x_max = c + radius if start % self.two_pi <= angle else max(x, target)  # the top of the circle, if passed
        return Step(kind, dt, v_end, x_max)


def solve_high_precision(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = 50,
                         t_end: float | None = None, max_events: int | None = None, dps: int = 50) -> Solution:
    """Run the model in ``dps``-digit arithmetic from ``(x0, v0)`` at ``t = 0+``; the limits and outcomes are
    those of :func:`escapement.solvers.exact.solve_exact`.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int or None, default 50
        Complete cycles to run (None: run to ``t_end``).
    t_end : float, optional
        End time, s.
    max_events : int, optional
        Bound on the number of events.
    dps : int, default 50
        Significant decimal digits of the arithmetic, 17 to 1000.

    Returns
    -------
    Solution
        The run, without a trajectory; its event log and cycles hold mpmath numbers (times in s, positions in m,
        velocities in m/s).

    Examples
    --------
    >>> from escapement import Parameters, solve_exact, solve_high_precision
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> ref = solve_high_precision(p, x0=1.0, n_cycles=2, dps=30)
    >>> period = ref.cycles.period[-1]  # s, an mpmath number
    >>> ref.method, bool(abs(float(period) - solve_exact(p, x0=1.0, n_cycles=2).cycles.period[-1]) < 1e-13)
    ('mpmath 30 digits', True)
    """
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    dps = check_count("dps", dps, MAX_DIGITS, MIN_DIGITS)
    with mpmath.workdps(dps + 10):
        return drive(spec, MpmathStepper(spec.params, dps), mpmath.mpf)
