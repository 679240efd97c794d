"""Reference solver: numerical integration with scipy's ``solve_ivp`` and terminal events.

It exists to check the exact solver independently, and to measure what a general-purpose
integrator costs (the benchmark runs it with SciPy's methods and with SUNDIALS CVODE): it shares the model and the
mode logic but none of the closed forms.  The motion is integrated segment by
segment, and a segment ends at every event and at every turning point, so that
``x`` is monotone inside each segment and a surface can be crossed at most once
in it: scipy locates an event only where the event function has opposite signs
at the two ends of a step, and would miss a surface crossed and re-crossed
inside one step near a turning point.  Each segment watches only the surfaces it
can hit next (free flight: the impact the escapement expects, a3 moving left
after the impulse (a1, a2), a1 moving right after the impulse (a4, a3), either at
the start; zone (a1, a2): a2 moving right; zone (a4, a3): a4 moving left; and
rest), and after each event the state is put exactly on the surface, since scipy
reports a spurious event when a segment starts on a surface it watches.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from . import outcome
from .cycles import cycle_table
from .events import EventKind, EventLog
from .limits import RunLimits
from .outcome import Status
from .parameters import Parameters, check_initial_state
from .solution import Solution

__all__ = ["DenseSegments", "solve_reference"]

FREE, ZONE_RIGHT, ZONE_LEFT = 0, 1, 2
REST = "rest"
#: free half-swings in a row without an event after which the escapement has stopped
#: (three turning points cover more than one whole revolution from any start)
HALF_SWINGS_TO_STOP = 3


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


class SciPyIntegrator:
    """One segment with ``scipy.integrate.solve_ivp``."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray, dense: bool) -> None:
        self.method, self.rtol, self.atol, self.dense = method, rtol, atol, dense
        self.name = f"solve_ivp {method} rtol={rtol:g}"

    def segment(self, omega2: float, centre: float, t0: float, y0, t1: float, watches: list[Watch]):
        def rhs(_t, y):
            return [y[1], -omega2 * (y[0] - centre)]

        functions = []
        for w in watches:
            def event(t, y, w=w):
                return w.value(y)

            event.terminal, event.direction = True, w.crossing
            functions.append(event)
        implicit = {"jac": [[0.0, 1.0], [-omega2, 0.0]]} if self.method in ("Radau", "BDF", "LSODA") else {}
        sol = solve_ivp(rhs, (t0, t1), list(y0), method=self.method, rtol=self.rtol, atol=self.atol,
                        events=functions or None, dense_output=self.dense, **implicit)
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at t = {t0:.12g} s: {sol.message}")
        hits = [(te[0], i, ye[0]) for i, (te, ye) in enumerate(zip(sol.t_events or [], sol.y_events or [])) if len(te)]
        first = min(hits, key=lambda h: h[0]) if hits else None
        hit = None if first is None else Hit(float(first[0]), first[1], (float(first[2][0]), float(first[2][1])))
        return hit, (sol.sol if self.dense else None)


class CvodeIntegrator:
    """One segment with SUNDIALS CVODE (scikit-sundae), Adams or BDF, with its root finding."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray) -> None:
        from sksundae.cvode import CVODE  # optional: only the benchmark needs it

        self._cvode = CVODE
        self.method, self.rtol, self.atol = method, rtol, atol
        self.name = f"CVODE {method} rtol={rtol:g}"

    def segment(self, omega2: float, centre: float, t0: float, y0, t1: float, watches: list[Watch]):
        def rhs(_t, y, yp):
            yp[0] = y[1]
            yp[1] = -omega2 * (y[0] - centre)

        def events(_t, y, out):
            for i, w in enumerate(watches):
                out[i] = w.value(y)

        events.terminal = [True] * len(watches)
        events.direction = [w.crossing for w in watches]
        solver = self._cvode(rhs, method=self.method, rtol=self.rtol, atol=self.atol, eventsfn=events,
                             num_events=len(watches), max_num_steps=1_000_000)
        result = solver.solve([t0, t1], np.array(y0, dtype=float))
        if not result.success:
            raise RuntimeError(f"CVODE failed at t = {t0:.12g} s: {result.message}")
        if result.t_events is None or len(result.t_events) == 0:
            return None, None
        index = int(np.flatnonzero(result.i_events[0])[0])
        y = result.y_events[0]
        return Hit(float(result.t_events[0]), index, (float(y[0]), float(y[1]))), None


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
    :func:`escapement.exact.solve_exact`.
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    if isinstance(rtol, bool) or not isinstance(rtol, float | int) or not 0 < rtol < 1:
        raise ValueError(f"rtol = {rtol!r} is invalid: rtol must be in (0, 1)")
    target_impacts = None if limits.n_cycles is None else limits.n_cycles + 1
    t_stop = math.inf if limits.t_end is None else limits.t_end

    omega, omega2 = params.omega, params.omega2
    offset = params.zone_offset
    keep = 1.0 - params.b
    a1, a2, a3, a4 = params.a1, params.a2, params.a3, params.a4
    period = params.natural_period
    length = max(abs(x), abs(a1), abs(a2), abs(a3), abs(a4), offset, abs(v) / omega)
    atol_x = rtol * length if atol is None else atol
    atol_vec = np.array([atol_x, atol_x * omega])
    if method.startswith("CVODE-"):
        if record_trajectory:
            raise ValueError(f"method = {method!r} keeps no trajectory: pass record_trajectory=False")
        integrator = CvodeIntegrator(method.removeprefix("CVODE-"), rtol, atol_vec)
    else:
        integrator = SciPyIntegrator(method, rtol, atol_vec, record_trajectory)
    position_of = {EventKind.IMPACT_A1: a1, EventKind.IMPACT_A3: a3, EventKind.ZONE_END_A2: a2, EventKind.ZONE_END_A4: a4}
    surfaces = {kind: Watch(position_of[kind], 1 if kind in (EventKind.IMPACT_A1, EventKind.ZONE_END_A2) else -1)
                for kind in EventKind}

    ev_t, ev_kind, ev_x, ev_vb, ev_va = [], [], [], [], []
    seg_t, seg_sol, seg_c = [], [], []
    maxima: list[float] = []
    cycle_max = -math.inf
    impacts_a1 = 0
    t = 0.0
    t_last_event = 0.0
    mode = FREE
    expect: EventKind | None = None  # the impact the escapement waits for; None: either
    quiet_half_swings = 0
    status, message, detail = Status.EVENT_LIMIT, "", {}
    t_final = t
    # Each event needs at most three segments (two turning points of free flight, then the hit).
    max_segments = 3 * limits.max_events + HALF_SWINGS_TO_STOP + 1

    for _ in range(max_segments):
        if len(ev_t) >= limits.max_events:
            message = outcome.event_limit_message(t, limits.max_events)
            break
        centre = {FREE: 0.0, ZONE_RIGHT: offset, ZONE_LEFT: -offset}[mode]
        heading = 1 if v > 0 else -1 if v < 0 else (1 if centre > x else -1 if centre < x else 0)
        if heading == 0:  # at rest at the centre: an equilibrium
            watch: list[EventKind] = []
        elif mode == ZONE_RIGHT:
            watch = [EventKind.ZONE_END_A2]
        elif mode == ZONE_LEFT:
            watch = [EventKind.ZONE_END_A4]
        else:
            wanted = {1: EventKind.IMPACT_A1, -1: EventKind.IMPACT_A3}[heading]
            watch = [wanted] if expect in (None, wanted) else []

        # x is monotone inside a segment, so a surface it starts on cannot be crossed in it; watching
        # it would only give scipy's spurious event at the start (and the paper's initial condition is
        # the state at t0+, after any jump: no impact at t = 0).
        watch = [k for k in watch if surfaces[k].value((x, v)) != 0.0]
        horizon = min(t + 0.75 * period, t_stop)
        labels = watch + ([REST] if heading else [])
        watches = [surfaces[k] for k in watch] + ([Watch(None, heading)] if heading else [])
        hit, dense = integrator.segment(omega2, centre, t, (x, v), horizon, watches)
        if record_trajectory:
            seg_t.append(t), seg_sol.append(dense), seg_c.append(centre)
        if hit is None:
            if horizon >= t_stop:
                status, t_final = Status.COMPLETED, t_stop
                message = f"reached t_end = {t_stop:.12g} s after {impacts_a1} impacts at a1"
            elif mode == FREE:  # at rest at the centre of free flight
                status, t_final = Status.STOPPED, math.inf
                message = outcome.stopped_message(t_last_event, 0.0, {"a1": a1, "a3": a3})
                detail = {"turning_point": 0.0, "margin": min(abs(a1), abs(a3))}
            else:
                zone, end = ("(a1, a2)", a2) if mode == ZONE_RIGHT else ("(a4, a3)", a4)
                status, t_final = Status.TURNED_BACK_IN_ZONE, t
                message = outcome.turned_back_message(t, zone, x, centre, end)
                detail = {"turning_point": x, "margin": abs(end - x)}
            break
        t_hit, y_hit, label = hit.t, hit.y, labels[hit.index]
        t = float(t_hit)
        if label == REST:
            x, v = float(y_hit[0]), 0.0
            if mode != FREE:
                zone, end = ("(a1, a2)", a2) if mode == ZONE_RIGHT else ("(a4, a3)", a4)
                status, t_final = Status.TURNED_BACK_IN_ZONE, t
                message = outcome.turned_back_message(t, zone, x, centre, end)
                detail = {"turning_point": x, "margin": abs(end - x)}
                break
            cycle_max = max(cycle_max, x)
            quiet_half_swings += 1
            if quiet_half_swings >= HALF_SWINGS_TO_STOP:
                radius = abs(x)
                missed = {EventKind.IMPACT_A1: {"a1": a1}, EventKind.IMPACT_A3: {"a3": a3}}.get(
                    expect, {"a1": a1, "a3": a3}
                )
                status, t_final = Status.STOPPED, math.inf
                message = outcome.stopped_message(t_last_event, radius, missed)
                detail = {"turning_point": radius, "margin": min(abs(m) for m in missed.values()) - radius}
                break
            continue
        kind = label
        quiet_half_swings = 0
        x = position_of[kind]
        v_before = float(y_hit[1])
        v_after = keep * v_before if kind.is_impact else v_before
        cycle_max = max(cycle_max, x)
        ev_t.append(t), ev_kind.append(int(kind)), ev_x.append(x), ev_vb.append(v_before), ev_va.append(v_after)
        t_final = t_last_event = t
        if kind == EventKind.IMPACT_A1:
            impacts_a1 += 1
            if impacts_a1 > 1:
                maxima.append(cycle_max)
            cycle_max = x
            if target_impacts is not None and impacts_a1 >= target_impacts:
                status, message = Status.COMPLETED, f"completed {impacts_a1 - 1} cycles"
                break
        if kind.is_impact:
            if v_after * v_before < 0.0:
                position = "a1" if kind == EventKind.IMPACT_A1 else "a3"
                status = Status.CHATTERING
                message = outcome.chattering_message(t, position, params.b, None)
                break
            mode = ZONE_RIGHT if kind == EventKind.IMPACT_A1 else ZONE_LEFT
        else:
            mode = FREE
            expect = EventKind.IMPACT_A3 if kind == EventKind.ZONE_END_A2 else EventKind.IMPACT_A1
        v = v_after
    else:
        message = outcome.event_limit_message(t, limits.max_events)

    events = EventLog(
        t=np.array(ev_t, dtype=float),
        kind=np.array(ev_kind, dtype=np.int8),
        x=np.array(ev_x, dtype=float),
        v_before=np.array(ev_vb, dtype=float),
        v_after=np.array(ev_va, dtype=float),
    )
    trajectory = None
    if record_trajectory:
        trajectory = DenseSegments(np.array(seg_t), tuple(seg_sol), np.array(seg_c), omega, t_final)
    detail["t_final"] = t_final
    return Solution(
        params=params, x0=float(x0), v0=float(v0), method=integrator.name,
        status=status, message=message, events=events,
        cycles=cycle_table(events, np.array(maxima, dtype=float)), trajectory=trajectory, detail=detail,
    )
