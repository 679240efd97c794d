"""Work-precision benchmark: wall time against error for every method, timed in one run.

Workload: ``n_cycles`` cycles from release at rest (the paper's Fig. 3 case (a) by default).
Errors are relative, at the last cycle, for the velocity before impact and the impact time,
against the 50-digit reference of :mod:`escapement.solvers.high_precision`.

Timing is adaptive: each setting is run again until ``min_seconds`` of runs have been measured
(at least once, at most ``max_repeats`` times), and its wall time is the median. A fast method
(the exact solver: a millisecond) is repeated hundreds of times, which keeps the noise of a
shared machine in check; a slow one (seconds per run) runs once or twice. The whole table then
costs about ``min_seconds`` per setting, plus the slow runs.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable

from ..model.parameters import Parameters
from ..paper import corrected as derived
from ..solvers.exact import solve_exact
from ..solvers.high_precision import solve_high_precision
from ..solvers.naive import solve_naive
from ..solvers.reference import solve_reference

__all__ = ["METHODS", "closed_form_map", "median_wall", "run_method", "work_precision"]

#: methods of solve_reference (SciPy's solve_ivp and SUNDIALS CVODE), by the benchmark's names
INTEGRATORS = ("RK45", "DOP853", "LSODA", "Radau", "CVODE-Adams", "CVODE-BDF")
METHODS = ("exact", "map16", *INTEGRATORS, "naive-RK4")


def closed_form_map(params: Parameters, x0: float, n_cycles: int) -> tuple[float, float]:
    """Velocity before impact and impact time at cycle ``n_cycles`` from closed forms alone.

    The first impact at a1 from release at rest at ``x0 > a3``: the swing reaches a3 at
    acos(a3/x0)/w, runs through the zone to a4 and swings to a1 (energy and arccos forms);
    then Eq. (16) for the velocities and the corrected Eq. (23) for the periods.
    """
    p = params
    w = p.omega
    if not x0 > p.a3 > 0:
        raise ValueError("the closed-form map starts from release at x0 > a3 > 0")
    v3 = -w * math.sqrt((x0 - p.a3) * (x0 + p.a3))
    v3p = (1 - p.b) * v3
    v4_sq = v3p**2 + p.omega2 * (p.a3 - p.a4) * (p.a3 + p.a4) + 2 * (p.a3 - p.a4) * p.f
    h = math.sqrt(p.a4**2 + v4_sq / p.omega2)
    t = (
        math.acos(p.a3 / x0) / w
        + derived._zone_time(-p.zone_offset, p.a3, p.a4, v3p, w)
        + (math.acos(-p.a4 / h) + math.acos(-p.a1 / h)) / w
    )
    v = math.sqrt(v4_sq + p.omega2 * (p.a4 - p.a1) * (p.a4 + p.a1))
    for _ in range(n_cycles - 1):
        t += derived.period(v, p)
        v = math.sqrt((1 - p.b) ** 4 * v * v + derived.map_constant(p))
    return v, t


def run_method(method: str, setting: float | None, params: Parameters, x0: float, n_cycles: int):
    """One run; returns (velocity before impact, impact time) at cycle ``n_cycles``."""
    if method == "exact":
        c = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=False).cycles
        return float(c.velocity_before_impact[-1]), float(c.impact_time[-1])
    if method == "map16":
        return closed_form_map(params, x0, n_cycles)
    if method in INTEGRATORS:
        run = solve_reference(params, x0, n_cycles=n_cycles, method=method, rtol=setting, record_trajectory=False)
        if len(run.cycles) < n_cycles:
            raise RuntimeError(f"{method} at rtol {setting:g} ended early: {run.message}")
        return float(run.cycles.velocity_before_impact[-1]), float(run.cycles.impact_time[-1])
    if method == "naive-RK4":
        run = solve_naive(params, x0, n_cycles=n_cycles, step=setting)
        if len(run.cycles) < n_cycles:
            raise RuntimeError(f"naive-RK4 at step {setting:g} ended early: {run.message}")
        return float(run.cycles.velocity_before_impact[-1]), float(run.cycles.impact_time[-1])
    raise ValueError(f"method = {method!r} is invalid: method must be one of {', '.join(METHODS)}")


def median_wall(fn: Callable[[], object], min_seconds: float, max_repeats: int) -> tuple[float, int, object]:
    """Run ``fn`` until ``min_seconds`` of runs are measured or ``max_repeats`` runs are done (at least
    one); return the median wall time, the number of runs and the last result."""
    walls: list[float] = []
    result = None
    while len(walls) < max_repeats and (not walls or sum(walls) < min_seconds):
        start = time.perf_counter()
        result = fn()
        walls.append(time.perf_counter() - start)
    return statistics.median(walls), len(walls), result


def work_precision(
    params: Parameters, x0: float, n_cycles: int, settings: dict[str, list], min_seconds: float, max_repeats: int,
    log=None,
) -> list[dict]:
    """Rows ``method, setting, wall_s, repeats, error_velocity, error_time`` for every method and setting."""
    if not (isinstance(min_seconds, int | float) and 0 < min_seconds <= 60):
        raise ValueError(f"min_seconds = {min_seconds!r} is invalid: min_seconds must be in (0, 60] (s)")
    if isinstance(max_repeats, bool) or not isinstance(max_repeats, int) or not 1 <= max_repeats <= 10_000:
        raise ValueError(f"max_repeats = {max_repeats!r} is invalid: max_repeats must be an integer in [1, 10000]")
    for method in settings:
        if method not in METHODS:
            raise ValueError(f"method = {method!r} is invalid: method must be one of {', '.join(METHODS)}")
    ref = solve_high_precision(params, x0, n_cycles=n_cycles).cycles
    v_ref, t_ref = float(ref.velocity_before_impact[-1]), float(ref.impact_time[-1])
    rows = []
    for method, values in settings.items():
        for setting in values or [None]:
            wall, runs, (v, t) = median_wall(
                lambda: run_method(method, setting, params, x0, n_cycles), min_seconds, max_repeats
            )
            row = {
                "method": method,
                "setting": "" if setting is None else f"{setting:g}",
                "wall_s": wall,
                "repeats": runs,
                "error_velocity": abs(v - v_ref) / abs(v_ref),
                "error_time": abs(t - t_ref) / abs(t_ref),
            }
            rows.append(row)
            if log is not None:
                log(f"{method} {row['setting']}: {wall:.3e} s (median of {runs}), "
                    f"errors {row['error_velocity']:.2e} {row['error_time']:.2e}")
    return rows
