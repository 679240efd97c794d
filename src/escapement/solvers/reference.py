"""Reference solver: numerical integration with scipy's ``solve_ivp`` and terminal events.

It checks the exact solver independently and measures what a general-purpose integrator costs (SciPy's
methods and SUNDIALS CVODE): it shares the automaton (through the loop of :mod:`escapement.solvers.driver`)
but none of the closed forms. The motion is integrated segment by segment, a segment ending at every event
and every turning point, so that ``x`` is monotone inside it and a surface is crossed at most once; it
watches the surfaces ahead in the direction of motion, and rest; after each event the state is put exactly
on the surface (SciPy reports a spurious event when a segment starts on a surface it watches).

Grazing.  An integrator locates an event only where the event function has opposite signs
at the two ends of a step.  A step that spans the crossing of a surface and the turning point
just beyond it (a zone's end a2 or a4 passed slowly, an arc that turns a hair past it) can end
where ``x`` has come back across the surface: the turning point is found, the crossing is not.
So at the end of every segment the state there is checked against every surface the segment
watches: one that lies between the start and the end in the direction of motion was crossed,
and its crossing is located on the monotone stretch before the end (on the segment's dense
output with SciPy, by integrating back from the end with CVODE).  The velocity has a single zero
in any step (steps are kept below half a period, the spacing of its zeros), so no turning point
is missed; an impact position (a1, a3) is reached moving towards the free centre, so it is
grazed only just after a turning point, where a segment starts: one sign change, which the
integrator finds.  An escapement that stops is declared so only at a turning point from which
no watched surface lies ahead, so that the turning point it reports lies short of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state
from .driver import HORIZON, NO_EVENT, Step, drive
from .result import Solution

__all__ = ["DenseSegments", "IvpStepper", "solve_reference"]

#: free half-swings in a row without an event after which the escapement has stopped
#: (three turning points cover more than one whole revolution from any start)
HALF_SWINGS_TO_STOP = 3
#: the longest step, in half periods: the velocity's zeros are half a period apart, so a step
#: shorter than that holds at most one of them and changes the velocity's sign across it
MAX_STEP_HALF_PERIODS = 0.9
#: the event bound of a run to an end time alone that keeps its dense output (about 7 kB an event)
DENSE_MAX_EVENTS = 100_000
#: relative and absolute tolerance of the root finding on a dense output (scipy's own for events)
ROOT_TOLERANCE = 4.0 * np.finfo(float).eps


@dataclass(frozen=True)
class Watch:
    """An event a segment watches: ``x`` reaching ``position`` while moving in ``direction``
    (``position`` None: the velocity vanishing while moving in ``direction``)."""

    position: float | None
    direction: int

    def value(self, y) -> float:
        return y[1] if self.position is None else y[0] - self.position

    @property
    def crossing(self) -> int:
        """Sign of the slope of ``value`` at the event."""
        return -self.direction if self.position is None else self.direction


@dataclass(frozen=True)
class Hit:
    t: float
    index: int
    y: tuple[float, float]


@dataclass(frozen=True)
class Segment:
    """One segment to integrate: ``x'' = -omega2 (x - centre)`` from ``y0`` at ``t0`` up to ``t1``
    at most, ending at the first of ``watches``."""

    omega2: float
    centre: float
    t0: float
    y0: tuple[float, float]
    t1: float
    watches: tuple[Watch, ...]

    @property
    def max_step(self) -> float:
        """The longest step, below half a period (see :data:`MAX_STEP_HALF_PERIODS`)."""
        return MAX_STEP_HALF_PERIODS * math.pi / math.sqrt(self.omega2)


class SciPyIntegrator:
    """One segment with ``scipy.integrate.solve_ivp``."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray, dense: bool) -> None:
        # SciPy's integrators are loaded here, when a reference run starts, not when the solvers are
        # imported: a job that runs only the exact solver does not pay their import (about 0.7 s)
        from scipy.integrate import solve_ivp
        from scipy.optimize import brentq

        self._solve_ivp, self._brentq = solve_ivp, brentq
        self.method, self.rtol, self.atol, self.dense = method, rtol, atol, dense
        self.name = f"solve_ivp {method} rtol={rtol:g}"

    def segment(self, seg: Segment):
        """The first event of the segment (None: none before ``t1``) and, if kept, the dense output."""
        return self._solve(seg, self.dense)

    def _solve(self, seg: Segment, dense: bool):
        omega2, centre = seg.omega2, seg.centre

        def rhs(_t, y):
            return [y[1], -omega2 * (y[0] - centre)]

        functions = []
        for w in seg.watches:
            def event(t, y, w=w):
                return w.value(y)

            event.terminal, event.direction = True, w.crossing
            functions.append(event)
        implicit = {"jac": [[0.0, 1.0], [-omega2, 0.0]]} if self.method in ("Radau", "BDF", "LSODA") else {}
        sol = self._solve_ivp(rhs, (seg.t0, seg.t1), list(seg.y0), method=self.method, rtol=self.rtol, atol=self.atol,
                        events=functions or None, dense_output=dense, max_step=seg.max_step, **implicit)
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at t = {seg.t0:.12g} s: {sol.message}")
        hits = [(te[0], i, ye[0]) for i, (te, ye) in enumerate(zip(sol.t_events or [], sol.y_events or [])) if len(te)]
        first = min(hits, key=lambda h: h[0]) if hits else None
        hit = None if first is None else Hit(float(first[0]), first[1], (float(first[2][0]), float(first[2][1])))
        return hit, (sol.sol if dense else None)

    def crossing(self, seg: Segment, dense, end: Hit, index: int) -> Hit:
        """Where ``x`` reaches the position of ``seg.watches[index]`` before ``end``, on the segment's
        dense output, where ``x`` is monotone from the start to ``end``; the segment is integrated
        again with dense output if it was not kept (the same steps, so the same ``end``)."""
        if dense is None:
            again, dense = self._solve(seg, True)
            if again != end:
                raise RuntimeError(f"solve_ivp is not repeatable at t = {seg.t0:.12g} s: {again} != {end}")
        position = seg.watches[index].position

        def gap(t: float) -> float:
            return float(dense(t)[0]) - position

        t = self._brentq(gap, seg.t0, end.t, xtol=ROOT_TOLERANCE, rtol=ROOT_TOLERANCE)
        y = dense(t)
        return Hit(float(t), index, (float(y[0]), float(y[1])))


class CvodeIntegrator:
    """One segment with SUNDIALS CVODE (scikit-sundae), Adams or BDF, with its root finding."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray) -> None:
        from sksundae.cvode import CVODE  # optional: only the benchmark needs it

        self._cvode = CVODE
        self.method, self.rtol, self.atol = method, rtol, atol
        self.name = f"CVODE {method} rtol={rtol:g}"

    def _solve(self, seg: Segment, watches: tuple[Watch, ...], directions: list[int], t_from: float, y_from,
               t_to: float):
        omega2, centre = seg.omega2, seg.centre

        def rhs(_t, y, yp):
            yp[0] = y[1]
            yp[1] = -omega2 * (y[0] - centre)

        def events(_t, y, out):
            for i, w in enumerate(watches):
                out[i] = w.value(y)

        events.terminal = [True] * len(watches)
        events.direction = directions
        solver = self._cvode(rhs, method=self.method, rtol=self.rtol, atol=self.atol, eventsfn=events,
                             num_events=len(watches), max_num_steps=1_000_000, max_step=seg.max_step)
        result = solver.solve([t_from, t_to], np.array(y_from, dtype=float))
        if not result.success:
            raise RuntimeError(f"CVODE failed at t = {t_from:.12g} s: {result.message}")
        if result.t_events is None or len(result.t_events) == 0:
            return None
        index = int(np.flatnonzero(result.i_events[0])[0])
        y = result.y_events[0]
        return Hit(float(result.t_events[0]), index, (float(y[0]), float(y[1])))

    def segment(self, seg: Segment):
        """The first event of the segment (None: none before ``t1``); CVODE keeps no dense output."""
        return self._solve(seg, seg.watches, [w.crossing for w in seg.watches], seg.t0, seg.y0, seg.t1), None

    def crossing(self, seg: Segment, dense, end: Hit, index: int) -> Hit:
        """Where ``x`` reaches the position of ``seg.watches[index]`` before ``end``, by integrating
        back from ``end`` towards the start: ``x`` is monotone on that stretch, which holds one crossing."""
        watch = seg.watches[index]
        back = self._solve(seg, (watch,), [0], end.t, end.y, seg.t0)
        if back is None:
            raise RuntimeError(f"CVODE found no crossing of x = {watch.position!r} m between t = {seg.t0:.12g} s "
                               f"and t = {end.t:.12g} s, where the segment passed it")
        return Hit(back.t, index, back.y)


@dataclass(frozen=True)
class DenseSegments:
    """The motion as solve_ivp's dense output, one interpolant per segment."""

    t_start: np.ndarray
    interpolants: tuple
    centre: np.ndarray
    omega: float
    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=float)
        x = np.full(t.shape, np.nan)
        v = np.full(t.shape, np.nan)
        a = np.full(t.shape, np.nan)
        idx = np.searchsorted(self.t_start, t, side="right") - 1
        valid = (idx >= 0) & (t >= 0.0) & (t <= self.t_final)
        for i in np.unique(idx[valid]):
            sel = valid & (idx == i)
            y = self.interpolants[i](t[sel])
            x[sel], v[sel] = y[0], y[1]
            a[sel] = -(self.omega**2) * (y[0] - self.centre[i])
        return x, v, a


def _heading(centre: float, x: float, v: float) -> int:
    """The direction of motion: that of ``v``, or at rest that of the spring's pull (0 at the centre)."""
    return 1 if v > 0 else -1 if v < 0 else (1 if centre > x else -1 if centre < x else 0)


class IvpStepper:
    """The next event by numerical integration, segment by segment (turning points end segments)."""

    def __init__(self, params: Parameters, integrator, record_trajectory: bool) -> None:
        self.omega, self.omega2 = params.omega, params.omega2
        self.period = params.natural_period
        self.name = integrator.name
        self.integrator = integrator
        self.surfaces = {kind: Watch(automaton.position(kind, params), s.direction)
                         for kind, s in automaton.SURFACES.items()}
        self.record = record_trajectory
        #: bytes kept per event besides the loop's: each segment's dense output where the trajectory is kept
        #: (measured about 6_400 an event); and whatever the run's length, SciPy's work arrays (about 190 kB)
        self.trajectory_bytes_per_event = 7_000 if record_trajectory else 0
        self.fixed_bytes = 256_000
        self.seg_t: list[float] = []
        self.seg_sol: list = []
        self.seg_c: list[float] = []

    def next_event(self, mode, centre, t, x, v, watched, t_stop) -> Step:
        t_start = t
        largest = x
        rests = 0
        # each pass ends in a return or a turning point; a free run stops after HALF_SWINGS_TO_STOP of
        # them, or one more if a watched surface lies ahead of the last (see _ahead)
        for _ in range(HALF_SWINGS_TO_STOP + 1):
            heading = _heading(centre, x, v)
            # x is monotone inside a segment, so only the surfaces ahead can be crossed; one it
            # starts on cannot, and watching it would only give scipy's spurious event at the
            # start (the paper's initial condition is the state at t0+, after any jump).
            kinds = [k for k in watched if self.surfaces[k].direction == heading]
            kinds = [k for k in kinds if self.surfaces[k].value((x, v)) != 0.0]
            horizon = min(t + 0.75 * self.period, t_stop)
            watches = [self.surfaces[k] for k in kinds] + ([Watch(None, heading)] if heading else [])
            seg = Segment(self.omega2, centre, t, (x, v), horizon, tuple(watches))
            hit, dense = self.integrator.segment(seg)
            if self.record:
                self.seg_t.append(t), self.seg_sol.append(dense), self.seg_c.append(centre)
            if hit is None:
                if horizon >= t_stop:
                    return Step(HORIZON, math.inf, 0.0, largest)
                # at rest at the centre (an equilibrium): no surface is ever reached
                if mode == Mode.FREE:
                    return Step(NO_EVENT, math.inf, 0.0, abs(x))
                return Step(NO_EVENT, t - t_start, 0.0, x)
            hit = self._first_crossing(seg, hit, dense, heading)
            t = hit.t
            if hit.index == len(kinds):  # the velocity vanished: a turning point
                x, v = hit.y[0], 0.0
                if mode != Mode.FREE:
                    return Step(NO_EVENT, t - t_start, 0.0, x)
                largest = max(largest, x)
                rests += 1
                if rests >= HALF_SWINGS_TO_STOP and not self._ahead(watched, centre, x):
                    break
                continue
            kind = kinds[hit.index]
            surface = self.surfaces[kind]
            # the surface is crossed moving in its direction; near grazing the integrated velocity
            # there is within the tolerance of zero, and may have the other sign: it is put at zero
            v_hit = surface.direction * max(surface.direction * hit.y[1], 0.0)
            return Step(kind, t - t_start, v_hit, max(largest, surface.position), t_abs=t)
        # free half-swings in a row without an event: the escapement has stopped
        return Step(NO_EVENT, math.inf, 0.0, abs(x))

    def _first_crossing(self, seg: Segment, hit: Hit, dense, heading: int) -> Hit:
        """The segment's first event: ``hit``, or the crossing of a watched surface that lies between
        the start and ``hit`` in the direction of motion and that the integrator missed (a step that
        spans the crossing and the turning point just beyond it shows no change of sign)."""
        x0, x1 = seg.y0[0], hit.y[0]
        passed = [i for i, w in enumerate(seg.watches)
                  if i != hit.index and w.position is not None
                  and (w.position - x0) * heading > 0.0 and (x1 - w.position) * heading > 0.0]
        if not passed:
            return hit
        nearest = min(passed, key=lambda i: (seg.watches[i].position - x0) * heading)
        return self.integrator.crossing(seg, dense, hit, nearest)

    def _ahead(self, watched, centre: float, x: float) -> bool:
        """True if, from a turning point at ``x``, a watched surface lies ahead in the direction of
        the motion that follows (an impact position, a1 < 0 < a3, then lies between the turning point
        and the free centre: the next segment crosses it)."""
        heading = _heading(centre, x, 0.0)
        return any(self.surfaces[k].direction == heading and (self.surfaces[k].position - x) * heading > 0.0
                   for k in watched)

    def trajectory(self, t_final: float):
        if not self.record:
            return None
        return DenseSegments(np.array(self.seg_t), tuple(self.seg_sol), np.array(self.seg_c), self.omega, t_final)


def solve_reference(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int | None = None,
    t_end: float | None = None,
    max_events: int | None = None,
    method: str = "DOP853",
    rtol: float = 1e-12,
    atol: float | None = None,
    record_trajectory: bool = True,
) -> Solution:
    """Integrate the escapement model numerically, segment by segment.

    ``method`` is a ``solve_ivp`` method ("RK45", "DOP853", "LSODA", "Radau", ...) or
    "CVODE-Adams" / "CVODE-BDF" (SUNDIALS through scikit-sundae, no dense output).
    ``atol`` defaults to ``rtol`` times a length scale (the largest of |x0|, |a_i|, F/K
    and |v0|/omega) for x, and omega times that for v.  Same limits and outcomes as
    :func:`escapement.solvers.exact.solve_exact`.

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
        Bound on the number of events (default: as :func:`~escapement.solvers.exact.solve_exact`, but
        :data:`DENSE_MAX_EVENTS` for a run to ``t_end`` alone that keeps its dense output, about 0.7 GB).
    method : str, default "DOP853"
        The integrator (see above).
    rtol : float, default 1e-12
        Relative tolerance, dimensionless, in ``(0, 1)``.
    atol : float, optional
        Absolute tolerance on ``x``, m (``omega`` times it on ``v``, m/s); default see above.
    record_trajectory : bool, default True
        Keep the dense output, for :meth:`Solution.sample <escapement.Solution.sample>` (not with CVODE).

    Returns
    -------
    Solution
        The run (times in s, positions in m, velocities in m/s).

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ValueError
        If ``rtol`` is outside ``(0, 1)``, a CVODE method is asked to keep the trajectory, or (a
        :class:`~escapement.ParameterError`) ``x0``, ``v0`` or a limit is invalid.
    RuntimeError
        If the integrator fails.

    Examples
    --------
    >>> from escapement import Parameters, solve_exact, solve_reference
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> ivp = solve_reference(p, x0=1.0, n_cycles=1, rtol=1e-10, record_trajectory=False)
    >>> ivp.method, ivp.status.value
    ('solve_ivp DOP853 rtol=1e-10', 'completed')
    >>> bool(abs(ivp.cycles.period[0] - solve_exact(p, x0=1.0, n_cycles=1).cycles.period[0]) < 1e-8)  # s
    True
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    if max_events is None and n_cycles is None and record_trajectory:
        max_events = DENSE_MAX_EVENTS
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    if isinstance(rtol, bool) or not isinstance(rtol, float | int) or not 0 < rtol < 1:
        raise ValueError(f"rtol = {rtol!r} is invalid: rtol must be in (0, 1)")
    omega = params.omega
    length = max(abs(x), abs(params.a1), abs(params.a2), abs(params.a3), abs(params.a4), params.zone_offset,
                 abs(v) / omega)
    atol_x = rtol * length if atol is None else atol
    atol_vec = np.array([atol_x, atol_x * omega])
    if method.startswith("CVODE-"):
        if record_trajectory:
            raise ValueError(f"method = {method!r} keeps no trajectory: pass record_trajectory=False")
        integrator = CvodeIntegrator(method.removeprefix("CVODE-"), rtol, atol_vec)
    else:
        integrator = SciPyIntegrator(method, rtol, atol_vec, record_trajectory)
    return drive(params, x, v, limits, IvpStepper(params, integrator, record_trajectory), x0=x, v0=v)
