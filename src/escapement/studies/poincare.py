"""Measuring the Poincare map of the simulated motion: fixed point, period, multiplier.

The multiplier mu_2 is measured (a central difference of P), not taken from Eq. (21). :func:`stability_grid` keeps its
own vectorised Newton iteration: ``scipy.optimize.newton`` on arrays stops on an absolute step only and takes a NaN step
(a stop) as converged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.status import Status
from ..solvers.ensemble import solve_ensemble
from ..solvers.exact import solve_exact

__all__ = ["CycleMeasurement", "NoReturn", "ensemble_return_map", "floquet_multipliers", "largest_speed",
           "measure_cycle", "return_map", "section_crossing_counts", "stability_grid"]

#: relative step of the central difference: truncation ~ h**2, rounding ~ 1e-16 / h
RELATIVE_STEP = 1e-5


class NoReturn(ValueError):
    """The motion from the section leaves the regime before it returns to the section."""


def return_map(params: Parameters, v: float, strict: bool = True) -> tuple[float, float]:
    """``(v_in, P(v_in))``: the velocity of the first impact at a1 (v up to rounding) and of the next; where the
    motion leaves the regime first, :class:`NoReturn` (``strict``) or NaN for ``P(v_in)``."""
    release = -math.hypot(params.a1, v / params.omega)
    run = solve_exact(params, release, 0.0, n_cycles=2, record_trajectory=False)
    if run.status != Status.COMPLETED or len(run.cycles) < 2:
        if not strict:
            first = run.events.of_kind(EventKind.IMPACT_A1)
            return (float(run.events.v_before[first[0]]) if len(first) else math.nan), math.nan
        raise NoReturn(f"no return to the section from v = {v!r}: {run.message}")
    return float(run.cycles.velocity_before_impact[0]), float(run.cycles.velocity_before_impact[1])


@dataclass(frozen=True)
class CycleMeasurement:
    """The limit cycle a run reached, measured at its last cycle (NaN where the run left the regime)."""

    outcome: str
    message: str
    velocity: float  #: velocity before impact after n_cycles (the measured fixed point)
    period: float
    largest_displacement: float
    multiplier: float  #: dP/dv at the measured fixed point, by a central difference
    cycles_to_converge: int  #: first cycle whose velocity is within 1e-9 (relative) of the last
    first_period: float  #: period of the first cycle (from the first impact at a1 to the second), s
    largest_speed: float  #: largest |v| on the last cycle, from the arcs' closed forms, m/s
    floquet: tuple[float, float]  #: the Floquet multipliers of the flow over the last period, larger first


def largest_speed(arcs, t_from: float, t_to: float) -> float:
    """The largest ``|v|`` of the motion between ``t_from`` and ``t_to``, exactly, from its harmonic arcs: ``w R``
    where an arc passes its centre, else at an end of the arc."""
    if not t_from < t_to:
        raise ValueError(f"t_from = {t_from!r} must be < t_to = {t_to!r}")
    starts = np.append(arcs.t_start, arcs.t_final)
    w = arcs.omega
    best = 0.0
    for i in np.flatnonzero((starts[1:] > t_from) & (starts[:-1] < t_to)):
        u0, w0 = arcs.x_start[i] - arcs.centre[i], arcs.v_start[i] / w
        # the arc's state at t_from (if it starts before) and its phase span up to t_to
        lead = max(t_from - starts[i], 0.0) * w
        radius, phase = math.hypot(u0, w0), math.atan2(u0, w0) + lead
        span = (min(starts[i + 1], t_to) - max(starts[i], t_from)) * w
        ends = (abs(radius * math.cos(phase)), abs(radius * math.cos(phase + span)))
        passes = math.floor((phase + span) / math.pi) > math.floor(phase / math.pi) or phase % math.pi == 0.0
        best = max(best, w * (radius if passes else max(ends)))
    return best


def floquet_multipliers(params: Parameters, x: float, v: float, period: float,
                        relative_step: float = 1e-6) -> tuple[float, float]:
    """Both Floquet multipliers of the limit cycle of ``period`` through ``(x, v)`` (in free flight), larger first:
    the eigenvalues of the flow's Jacobian over ``period`` by central differences of the exact solver, steps
    ``relative_step`` of ``|(x, v/w)|``. NaN where they are complex or a run leaves the regime."""
    if not (period > 0 and math.isfinite(period)):
        raise ValueError(f"period = {period!r} must be a finite number > 0")
    w = params.omega
    h = relative_step * math.hypot(x, v / w)

    def flow(x_start: float, v_start: float) -> np.ndarray:
        run = solve_exact(params, x_start, v_start, t_end=period)
        if run.status != Status.COMPLETED:
            return np.full(2, math.nan)
        end_x, end_v, _ = run.trajectory.sample(np.array([run.t_final]))
        return np.array([end_x[0], end_v[0] / w])

    columns = [(flow(x + h, v) - flow(x - h, v)) / (2 * h), (flow(x, v + h * w) - flow(x, v - h * w)) / (2 * h)]
    jacobian = np.column_stack(columns)  # in (x, v/w): the multipliers do not depend on the scaling
    if not np.isfinite(jacobian).all():
        return math.nan, math.nan
    trace, det = float(np.trace(jacobian)), float(np.linalg.det(jacobian))
    disc = trace * trace / 4 - det
    if disc < 0:
        return math.nan, math.nan
    root = math.sqrt(disc)
    return trace / 2 + root, trace / 2 - root


def _slope(map_at, v):
    """dP/dv at ``v`` by a central difference of ``map_at(v) = (v_in, P(v_in), ...)``."""
    lo_in, lo_out = map_at(v * (1 - RELATIVE_STEP))[:2]
    hi_in, hi_out = map_at(v * (1 + RELATIVE_STEP))[:2]
    return (hi_out - lo_out) / (hi_in - lo_in)


def _free_flight_state(run) -> tuple[float, float]:
    """The state halfway in time between the last a2 and the following impact at a3 (free flight)."""
    kinds, times = run.events.kind, run.events.t
    i = np.flatnonzero(kinds == EventKind.ZONE_END_A2)
    i = i[i + 1 < len(kinds)][-1]
    x, v, _ = run.trajectory.sample(np.array([0.5 * (times[i] + times[i + 1])]))
    return float(x[0]), float(v[0])


def measure_cycle(params: Parameters, x0: float, n_cycles: int = 300) -> CycleMeasurement:
    """Run ``n_cycles`` from release at ``x0`` and measure the map at where it ends."""
    run = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=True)
    nan = math.nan
    if run.status != Status.COMPLETED:
        return CycleMeasurement(run.status.value, run.message, nan, nan, nan, nan, -1, nan, nan, (nan, nan))
    v = run.cycles.velocity_before_impact
    star = float(v[-1])
    close = abs(v - star) <= 1e-9 * abs(star)
    first = int(close.argmax()) + 1 if close.any() else -1
    start, period = float(run.cycles.impact_time[-1]), float(run.cycles.period[-1])
    return CycleMeasurement(run.status.value, run.message, star, period, float(run.cycles.largest_displacement[-1]),
                            _slope(lambda u: return_map(params, u), star), first, float(run.cycles.period[0]),
                            largest_speed(run.trajectory, start, start + period),
                            floquet_multipliers(params, *_free_flight_state(run), period))


def ensemble_return_map(model: dict, b, F, v):
    """:func:`return_map` for arrays: ``(v_in, P(v_in), period, status codes)`` at every ``(b, F, v)``."""
    omega = math.sqrt(model["K"] / model["M"])
    out = solve_ensemble(model["M"], model["K"], F, b, model["a1"], model["a2"], model.get("a3"), model.get("a4"),
                         x0=-np.hypot(model["a1"], np.asarray(v) / omega), n_cycles=2, largest_displacement=False)
    c = out.cycles
    return c.velocity_before_impact[:, 0], c.velocity_before_impact[:, 1], c.period[:, 0], out.status


def stability_grid(model: dict, b, F, iterations: int = 40):
    """Fixed point and multiplier of the simulated return map at every ``(b, F)``, by Newton's method on ``P(v) - v``
    (``P`` is convex: it converges from any positive start): a dict of arrays."""
    b, F = np.asarray(b, dtype=float), np.asarray(F, dtype=float)
    omega = math.sqrt(model["K"] / model["M"])

    def slope_at(i, v):
        return _slope(lambda u: ensemble_return_map(model, b[i], F[i], u), v)

    v = np.full(b.shape, omega * abs(model["a1"])) + np.sqrt(2 * F / model["M"] * (model["a2"] - model["a1"]))
    converged = np.zeros(b.shape, dtype=bool)
    active = np.arange(b.size)  # the cells still iterating: neither converged nor out of the regime
    for _ in range(iterations):
        if active.size == 0:
            break
        v_in, v_out, _, status = ensemble_return_map(model, b[active], F[active], v[active])
        step = (v_out - v_in) / (1.0 - slope_at(active, v[active]))
        ok = np.isfinite(step) & (status == Status.COMPLETED.code)
        v[active[ok]] = v_in[ok] + step[ok]
        # 1 / (1 - slope) magnifies rounding as b -> 0, hence a tolerance above 1e-16
        done = ok & (np.abs(step) <= 1e-12 * np.abs(v[active]))
        converged[active[done]] = True
        active = active[ok & ~done]
    v_in, _, period, status = ensemble_return_map(model, b, F, v)
    good = status == Status.COMPLETED.code
    return {"fixed_point": np.where(good, v_in, np.nan), "multiplier": np.where(good, slope_at(np.arange(b.size), v),
            np.nan), "period": np.where(good, period, np.nan), "status": status, "newton_converged": converged}


def section_crossing_counts(t: np.ndarray, x: np.ndarray, v: np.ndarray, a1: float, starts: np.ndarray) -> np.ndarray:
    """Crossings of Sigma (x rising through a1 with xdot > 0) of the samples ``t, x, v`` in each cycle, from one
    impact at a1 (``starts``) to the next."""
    up = np.flatnonzero((x[:-1] < a1) & (x[1:] >= a1) & (v[1:] > 0))
    crossings = t[up + 1]
    slack = 1e-9 * max(1.0, float(t[-1]))
    return np.array([np.count_nonzero((crossings >= s - slack) & (crossings < e - slack))
                     for s, e in zip(starts[:-1], starts[1:])], dtype=int)
