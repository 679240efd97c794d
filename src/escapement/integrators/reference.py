"""Reference solver: numerical integration by SciPy's ``solve_ivp`` (or SUNDIALS CVODE) with terminal events,
sharing the automaton but none of the closed forms.

The motion is integrated segment by segment, each ending at an event or a turning point, so that ``x`` is monotone
inside it: a step that spans the crossing of a zone's end and the turning point just beyond shows no sign change,
so a watched surface between a segment's start and end is located on that monotone stretch afterwards.
"""

from __future__ import annotations

import math

import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.arguments import Numeric, ParameterError, check_choice, real_number
from ..model.events import EventKind
from ..model.limits import check_flag, run_spec
from ..model.parameters import Parameters
from ..solvers.result import Solution
from .driver import HORIZON, NO_EVENT, Step, drive
from .segments import CvodeIntegrator, DenseSegments, Hit, SciPyIntegrator, Segment, Watch

__all__ = ["METHODS", "DenseSegments", "IvpStepper", "solve_reference"]

#: free half-swings in a row without an event after which the escapement has stopped (more than one revolution)
HALF_SWINGS_TO_STOP = 3
#: the integrators a reference run may use: SciPy's solve_ivp methods and SUNDIALS CVODE's two
METHODS = ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA", "CVODE-Adams", "CVODE-BDF")
DENSE_MAX_EVENTS = 100_000  #: the event bound of a run to ``t_end`` alone that keeps its dense output (7 kB each)


def _heading(centre: float, x: float, v: float) -> int:
    """The direction of motion: that of ``v``, or at rest that of the spring's pull (0 at the centre)."""
    return 1 if v > 0 else -1 if v < 0 else (1 if centre > x else -1 if centre < x else 0)


class IvpStepper:
    """The next event by numerical integration, segment by segment (turning points end segments)."""

    def __init__(self, params: Parameters, integrator: SciPyIntegrator | CvodeIntegrator,
                 record_trajectory: bool) -> None:
        self.omega, self.omega2, self.period = params.omega, params.omega2, params.natural_period
        self.name, self.integrator, self.record = integrator.name, integrator, record_trajectory
        self.surfaces = {kind: Watch(automaton.position(kind, params), s.direction)
                         for kind, s in automaton.SURFACES.items()}
        #: bytes besides the loop's: each segment's dense output per event (measured 6_400), SciPy's work arrays
        self.trajectory_bytes_per_event, self.fixed_bytes = (7_000 if record_trajectory else 0), 256_000
        self.seg_t, self.seg_sol, self.seg_c = [], [], []  # each segment's start, dense output and centre

    def next_event(self, mode: Mode, centre: Numeric, t: Numeric, x: Numeric, v: Numeric,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step:
        """As :meth:`Stepper.next_event <escapement.integrators.driver.Stepper.next_event>`."""
        t_start, largest = t, x
        # each pass ends in a return or a turning point; a free run stops after HALF_SWINGS_TO_STOP of them
        for rests in range(1, HALF_SWINGS_TO_STOP + 2):
            heading = _heading(centre, x, v)
            # x is monotone inside a segment: only the surfaces ahead can be crossed, and not one it starts on
            # (SciPy would report a spurious event at the start; the release is the state at t0+, after any jump)
            kinds = [k for k in watched
                     if self.surfaces[k].direction == heading and self.surfaces[k].value((x, v)) != 0.0]
            horizon = min(t + 0.75 * self.period, t_stop)
            watches = [self.surfaces[k] for k in kinds] + ([Watch(None, heading)] if heading else [])
            seg = Segment(self.omega2, centre, t, (x, v), horizon, tuple(watches))
            hit, dense = self.integrator.segment(seg)
            if self.record:
                self.seg_t.append(t), self.seg_sol.append(dense), self.seg_c.append(centre)
            if hit is None:
                if horizon >= t_stop:
                    return Step(HORIZON, math.inf, 0.0, largest)
                if mode == Mode.FREE:  # at rest at the centre (an equilibrium): no surface is ever reached
                    return Step(NO_EVENT, math.inf, 0.0, abs(x))
                return Step(NO_EVENT, t - t_start, 0.0, x)
            hit = self._first_crossing(seg, hit, dense, heading)
            t = hit.t
            if hit.index == len(kinds):  # the velocity vanished: a turning point
                x, v = hit.y[0], 0.0
                if mode != Mode.FREE:
                    return Step(NO_EVENT, t - t_start, 0.0, x)
                largest = max(largest, x)
                if rests >= HALF_SWINGS_TO_STOP and not self._ahead(watched, centre, x):
                    break
                continue
            kind = kinds[hit.index]
            surface = self.surfaces[kind]
            # near grazing the integrated velocity is within the tolerance of zero and may have the wrong sign
            v_hit = surface.direction * max(surface.direction * hit.y[1], 0.0)
            return Step(kind, t - t_start, v_hit, max(largest, surface.position), t_abs=t)
        return Step(NO_EVENT, math.inf, 0.0, abs(x))  # HALF_SWINGS_TO_STOP without an event: it has stopped

    def _first_crossing(self, seg: Segment, hit: Hit, dense, heading: int) -> Hit:
        """``hit``, or the crossing the integrator missed of a watched surface between the start and ``hit``."""
        x0, x1 = seg.y0[0], hit.y[0]
        passed = [i for i, w in enumerate(seg.watches)
                  if i != hit.index and w.position is not None
                  and (w.position - x0) * heading > 0.0 and (x1 - w.position) * heading > 0.0]
        nearest = min(passed, key=lambda i: (seg.watches[i].position - x0) * heading, default=None)
        return hit if nearest is None else self.integrator.crossing(seg, dense, hit, nearest)

    def _ahead(self, watched, centre: float, x: float) -> bool:
        """True if, from a turning point at ``x``, a watched surface lies ahead in the motion that follows."""
        heading = _heading(centre, x, 0.0)
        return any(self.surfaces[k].direction == heading and (self.surfaces[k].position - x) * heading > 0.0
                   for k in watched)

    def trajectory(self, t_final: float) -> DenseSegments | None:
        """The dense output of every segment up to ``t_final``, if the run keeps its trajectory."""
        return DenseSegments(np.array(self.seg_t), tuple(self.seg_sol), np.array(self.seg_c), self.omega,
                             t_final) if self.record else None


def solve_reference(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                    t_end: float | None = None, max_events: int | None = None, method: str = "DOP853",
                    rtol: float = 1e-12, atol: float | None = None, record_trajectory: bool = True) -> Solution:
    """Integrate the escapement model numerically; the limits and outcomes are those of ``solve_exact``.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run; at least one of ``n_cycles`` and ``t_end`` is given.
    t_end : float, optional
        End time, s.
    max_events : int, optional
        Bound on the number of events (:data:`DENSE_MAX_EVENTS` for a run to ``t_end`` that keeps its dense output).
    method : str, default "DOP853"
        A ``solve_ivp`` method or "CVODE-Adams" / "CVODE-BDF" (SUNDIALS, no dense output): :data:`METHODS`.
    rtol : float, default 1e-12
        Relative tolerance, dimensionless, in ``(0, 1)``.
    atol : float, optional
        Absolute tolerance on ``x``, m (``omega`` times it on ``v``); default ``rtol`` times the run's length scale.
    record_trajectory : bool, default True
        Keep the dense output, for :meth:`Solution.sample <escapement.Solution.sample>` (not with CVODE).

    Returns
    -------
    Solution
        The run (times in s, positions in m, velocities in m/s); :class:`RuntimeError` if the integrator fails.

    Examples
    --------
    >>> from escapement import Parameters, solve_exact, solve_reference
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> ivp = solve_reference(p, x0=1.0, n_cycles=1, rtol=1e-10, record_trajectory=False)
    >>> ivp.method, bool(abs(ivp.cycles.period[0] - solve_exact(p, x0=1.0, n_cycles=1).cycles.period[0]) < 1e-8)
    ('solve_ivp DOP853 rtol=1e-10', True)
    """
    record_trajectory = check_flag("record_trajectory", record_trajectory)
    if max_events is None and n_cycles is None and record_trajectory:
        max_events = DENSE_MAX_EVENTS
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    method = check_choice("method", method, METHODS)
    rtol = real_number("rtol", rtol, lambda r: 0 < r < 1, "in the open interval (0, 1), dimensionless")
    if atol is not None:
        atol = real_number("atol", atol, lambda a: a > 0, "> 0 (m), or None for rtol times the run's length scale")
    p, omega = spec.params, spec.params.omega
    length = max(abs(spec.x0), abs(p.a1), abs(p.a2), abs(p.a3), abs(p.a4), p.zone_offset, abs(spec.v0) / omega)
    atol_x = rtol * length if atol is None else atol
    atol_vec = np.array([atol_x, atol_x * omega])
    if method.startswith("CVODE-"):
        if record_trajectory:
            raise ParameterError("record_trajectory", record_trajectory, f"False with method = {method!r}, "
                                 "which keeps no dense output")
        integrator = CvodeIntegrator(method.removeprefix("CVODE-"), rtol, atol_vec)
    else:
        integrator = SciPyIntegrator(method, rtol, atol_vec, record_trajectory)
    return drive(spec, IvpStepper(p, integrator, record_trajectory))
