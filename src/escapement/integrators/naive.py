"""A naive fixed-step RK4, to show what not locating events costs: an event is applied at the end of the step that
passes its surface, so the errors are O(h) (hand-written: a library's RK4 locates its events or is not this simple).
"""

from __future__ import annotations

import math

from ..model import automaton
from ..model.automaton import Mode
from ..model.arguments import Numeric, real_number
from ..model.events import EventKind
from ..model.limits import run_spec
from ..model.parameters import Parameters
from ..model.printing import exact
from ..solvers.result import Solution
from .driver import NO_EVENT, Step, drive

__all__ = ["STEPS_PER_PERIOD", "NaiveStepper", "solve_naive"]

STEPS_PER_PERIOD = 20  #: the fewest steps per natural period a run may take
PERIODS_TO_STOP = 2.0  #: free flight of this many natural periods without an event: the escapement has stopped


class NaiveStepper:
    """RK4 steps of ``h`` until a watched surface lies behind the state."""

    def __init__(self, params: Parameters, step: float) -> None:
        self.name, self.w2, self.h, self.t = f"naive RK4 h={step:g}", params.omega2, step, 0.0
        self.surfaces = {kind: (automaton.position(kind, params), s.direction)
                         for kind, s in automaton.SURFACES.items()}
        self.max_steps = int(math.ceil(PERIODS_TO_STOP * params.natural_period / step)) + 1

    def next_event(self, mode: Mode, centre: Numeric, t: Numeric, x: Numeric, v: Numeric,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step:
        """As :meth:`Stepper.next_event <escapement.integrators.driver.Stepper.next_event>`."""
        w2, h, h2, h6 = self.w2, self.h, self.h / 2.0, self.h / 6.0
        t_start, largest = self.t, x
        for _ in range(self.max_steps):
            k1x, k1v = v, -w2 * (x - centre)
            k2x, k2v = v + h2 * k1v, -w2 * (x + h2 * k1x - centre)
            k3x, k3v = v + h2 * k2v, -w2 * (x + h2 * k2x - centre)
            k4x, k4v = v + h * k3v, -w2 * (x + h * k3x - centre)
            x_new = x + h6 * (k1x + 2 * k2x + 2 * k3x + k4x)
            v_new = v + h6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            self.t += h
            for kind in watched:
                target, direction = self.surfaces[kind]
                if mode == Mode.FREE:
                    passed = (x < target <= x_new if direction > 0 else x > target >= x_new) and v_new * direction > 0
                else:
                    passed = x_new * direction >= target * direction
                if passed:
                    return Step(kind, self.t - t_start, v_new, max(largest, x_new), t_abs=self.t, x_at=x_new)
            if mode != Mode.FREE and v_new * automaton.SURFACES[watched[0]].direction <= 0:
                return Step(NO_EVENT, self.t - t_start, 0.0, x_new)  # turned back inside the zone
            x, v = x_new, v_new
            largest = max(largest, x)
        return Step(NO_EVENT, math.inf, 0.0, math.hypot(x, v / math.sqrt(w2)))


def solve_naive(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int, step: float) -> Solution:
    """Run ``n_cycles`` cycles with fixed RK4 steps of ``step`` seconds, each event applied at the end of the step
    that passes it (an error of the order of ``step``), for comparison with the exact solver only.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles to run.
    step : float
        The fixed step, s: > 0 and at most 1/20 of the natural period (:data:`STEPS_PER_PERIOD`).

    Returns
    -------
    Solution
        The run (times in s, positions in m, velocities in m/s); no trajectory is kept.

    Examples
    --------
    >>> from escapement import Parameters, solve_exact, solve_naive
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> rough = solve_naive(p, x0=1.0, n_cycles=2, step=1e-3)
    >>> error = abs(rough.cycles.period[-1] - solve_exact(p, x0=1.0, n_cycles=2).cycles.period[-1])  # s
    >>> rough.method, bool(error < 2e-3)  # of the order of the step
    ('naive RK4 h=0.001', True)
    """
    spec = run_spec(params, x0, v0, n_cycles=n_cycles)
    largest = spec.params.natural_period / STEPS_PER_PERIOD
    step = real_number("step", step, lambda h: 0 < h <= largest,
                       f"> 0 and at most {exact(largest)} s, 1/{STEPS_PER_PERIOD} of the natural period "
                       "2 pi / omega: a larger step passes events without seeing them, and from omega step = 2.8 on "
                       "the RK4 step is unstable")
    return drive(spec, NaiveStepper(spec.params, step))
