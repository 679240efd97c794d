"""Work-precision benchmark: wall time against error for every method, timed in one run.

Errors are relative, at the last of ``n_cycles`` cycles from release at rest, of the velocity before impact and the
impact time, against 50 digits. Each setting is timed by the median of its runs, repeated against a shared
machine's noise, after one untimed cycle of its method, so that no row times the loading of its modules.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable

from ..model.arguments import check_count
from ..model.limits import MAX_CYCLES
from ..model.parameters import ParameterError, Parameters
from ..paper import corrected as derived
from ..solvers.cycles import CLOSED_FORM, solve_cycles
from ..solvers.exact import solve_exact
from ..integrators.high_precision import solve_high_precision
from ..integrators.naive import solve_naive
from ..integrators.reference import solve_reference

__all__ = ["HEADLINE_SETTINGS", "METHODS", "closed_form_map", "headline_ratios", "median_wall", "per_cycle_times",
           "run_method", "work_precision"]

#: methods of solve_reference (SciPy's solve_ivp and SUNDIALS CVODE), by the benchmark's names
INTEGRATORS = ("RK45", "DOP853", "LSODA", "Radau", "CVODE-Adams", "CVODE-BDF")
METHODS = ("exact", CLOSED_FORM, "map16", *INTEGRATORS, "naive-RK4")
#: the integrator settings :func:`headline_ratios` tries by default: those that can reach 1e-12 on 1000 cycles
#: in a run of seconds (Radau, several minutes there, is left out)
HEADLINE_SETTINGS = {"DOP853": [1e-12, 1e-13], "LSODA": [1e-12, 1e-13], "CVODE-Adams": [1e-12, 1e-13],
                     "CVODE-BDF": [1e-12, 1e-13], "RK45": [1e-12]}


def closed_form_map(params: Parameters, x0: float, n_cycles: int) -> tuple[float, float]:
    """Velocity before impact and impact time at cycle ``n_cycles`` from closed forms alone: the first impact at a1
    from release at rest (passing a3 and its zone first from ``x0 > a3``), then Eq. (16) and the corrected (23)."""
    p = params
    w = p.omega
    n_cycles = check_count("n_cycles", n_cycles, MAX_CYCLES)
    if x0 < p.a1 < 0:
        v, t = w * math.sqrt((x0 - p.a1) * (x0 + p.a1)), math.acos(p.a1 / x0) / w
    elif x0 > p.a3 > 0:  # to a3, through the zone (a4, a3), then the free swing to a1
        v3p = (1 - p.b) * (-w * math.sqrt((x0 - p.a3) * (x0 + p.a3)))
        v4_sq = v3p**2 + p.omega2 * (p.a3 - p.a4) * (p.a3 + p.a4) + 2 * (p.a3 - p.a4) * p.f
        h = math.sqrt(p.a4**2 + v4_sq / p.omega2)
        t = (math.acos(p.a3 / x0) / w + derived._zone_time(-p.zone_offset, p.a3, p.a4, v3p, w)
             + (math.acos(-p.a4 / h) + math.acos(-p.a1 / h)) / w)
        v = math.sqrt(v4_sq + p.omega2 * (p.a4 - p.a1) * (p.a4 + p.a1))
    else:
        raise ParameterError("x0", x0, f"a release left of a1 = {p.a1!r} < 0 or right of a3 = {p.a3!r} > 0 (m), "
                             "from which the first swing reaches an impact")
    for _ in range(n_cycles - 1):
        t += derived.period(v, p)
        v = math.sqrt((1 - p.b) ** 4 * v * v + derived.map_constant(p))
    return v, t


def run_method(method: str, setting: float | None, params: Parameters, x0: float, n_cycles: int):
    """One run; returns (velocity before impact, impact time) at cycle ``n_cycles``."""
    _check_methods([method])
    if method == "map16":
        return closed_form_map(params, x0, n_cycles)
    if method == "exact":
        cycles = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=False).cycles
    else:
        if method == CLOSED_FORM:
            run, what = solve_cycles(params, x0, n_cycles=n_cycles), CLOSED_FORM
        elif method in INTEGRATORS:
            run = solve_reference(params, x0, n_cycles=n_cycles, method=method, rtol=setting, record_trajectory=False)
            what = f"{method} at rtol {setting:g}"
        else:  # naive-RK4
            run, what = solve_naive(params, x0, n_cycles=n_cycles, step=setting), f"naive-RK4 at step {setting:g}"
        if len(run.cycles) < n_cycles:
            raise RuntimeError(f"{what} ended early: {run.message}")
        cycles = run.cycles
    return float(cycles.velocity_before_impact[-1]), float(cycles.impact_time[-1])


def median_wall(fn: Callable[[], object], min_seconds: float, max_repeats: int) -> tuple[float, int, object]:
    """Run ``fn`` until ``min_seconds`` of runs are measured or ``max_repeats`` runs are done (at least one): the
    median wall time, the number of runs and the last result. Not :mod:`timeit`, which returns no result."""
    if not callable(fn):
        raise TypeError(f"fn = {fn!r} is invalid: fn must be callable with no argument")
    _check_timing(min_seconds, max_repeats)
    walls: list[float] = []
    result = None
    while len(walls) < max_repeats and (not walls or sum(walls) < min_seconds):
        start = time.perf_counter()
        result = fn()
        walls.append(time.perf_counter() - start)
    return statistics.median(walls), len(walls), result


def _check_timing(min_seconds, max_repeats) -> None:
    if not (isinstance(min_seconds, int | float) and 0 < min_seconds <= 60):
        raise ValueError(f"min_seconds = {min_seconds!r} is invalid: min_seconds must be in (0, 60] (s)")
    if isinstance(max_repeats, bool) or not isinstance(max_repeats, int) or not 1 <= max_repeats <= 10_000:
        raise ValueError(f"max_repeats = {max_repeats!r} is invalid: max_repeats must be an integer in [1, 10000]")


def _check_methods(settings) -> None:
    for method in settings:
        if method not in METHODS:
            raise ValueError(f"method = {method!r} is invalid: method must be one of {', '.join(METHODS)}")


def _reference(settings: dict[str, list], params: Parameters, x0: float, n_cycles: int) -> tuple[float, float]:
    """The 50-digit velocity and time at the last cycle, once every method has run one untimed cycle."""
    ref = solve_high_precision(params, x0, n_cycles=n_cycles).cycles
    for method, values in settings.items():
        run_method(method, values[0] if values else None, params, x0, 1)
    return float(ref.velocity_before_impact[-1]), float(ref.impact_time[-1])


def _row(method: str, setting, params: Parameters, x0: float, n_cycles: int, reference: tuple[float, float],
         min_seconds: float, max_repeats: int, log=None) -> dict:
    v_ref, t_ref = reference
    wall, runs, (v, t) = median_wall(lambda: run_method(method, setting, params, x0, n_cycles), min_seconds,
                                     max_repeats)
    row = {"method": method, "setting": "" if setting is None else f"{setting:g}", "wall_s": wall, "repeats": runs,
           "error_velocity": abs(v - v_ref) / abs(v_ref), "error_time": abs(t - t_ref) / abs(t_ref)}
    if log is not None:
        log(f"{method} {row['setting']}: {wall:.3e} s (median of {runs}), "
            f"errors {row['error_velocity']:.2e} {row['error_time']:.2e}")
    return row


def work_precision(params: Parameters, x0: float, n_cycles: int, settings: dict[str, list], min_seconds: float,
                   max_repeats: int, log=None, closed_form: bool = True) -> list[dict]:
    """Rows ``method, setting, wall_s, repeats, error_velocity, error_time`` for every method and setting; with
    ``closed_form``, the per-cycle closed form's row follows ``exact``'s wherever the settings name ``exact`` only."""
    _check_timing(min_seconds, max_repeats)
    _check_methods(settings)
    if closed_form and "exact" in settings and CLOSED_FORM not in settings:
        items = list(settings.items())
        at = list(settings).index("exact") + 1
        settings = dict(items[:at] + [(CLOSED_FORM, [])] + items[at:])
    reference = _reference(settings, params, x0, n_cycles)
    return [_row(method, setting, params, x0, n_cycles, reference, min_seconds, max_repeats, log)
            for method, values in settings.items() for setting in values or [None]]


def headline_ratios(params: Parameters, x0: float, n_cycles: int = 1000, settings: dict[str, list] | None = None,
                    target: float = 1e-12, errors: tuple[str, ...] = ("error_velocity", "error_time"),
                    min_seconds: float = 0.2, max_repeats: int = 500, log=None) -> dict:
    """The rows ``exact``, ``closed_form``, ``candidates`` and ``ode`` (the fastest integrator setting whose
    ``errors`` are at most ``target``, or None) timed as in :func:`work_precision`, and the ratios of their wall
    times (NaN without an ``ode`` row)."""
    _check_timing(min_seconds, max_repeats)
    settings = HEADLINE_SETTINGS if settings is None else settings
    _check_methods(settings)
    if not set(errors) <= {"error_velocity", "error_time"} or not errors:
        raise ValueError(f"errors = {errors!r} is invalid: errors must name error_velocity, error_time or both")
    if not (isinstance(target, int | float) and target > 0):
        raise ValueError(f"target = {target!r} is invalid: target must be > 0")
    reference = _reference({"exact": [], CLOSED_FORM: [], **settings}, params, x0, n_cycles)

    def row(method, setting=None):
        return _row(method, setting, params, x0, n_cycles, reference, min_seconds, max_repeats, log)

    exact, closed = row("exact"), row(CLOSED_FORM)
    candidates = [row(method, setting) for method, values in settings.items() if method in INTEGRATORS
                  for setting in values]
    reaching = [r for r in candidates if all(r[name] <= target for name in errors)]
    ode = min(reaching, key=lambda r: r["wall_s"]) if reaching else None
    ode_wall = math.nan if ode is None else ode["wall_s"]
    return {"n_cycles": n_cycles, "target": target, "errors": tuple(errors), "exact": exact, "closed_form": closed,
            "ode": ode, "candidates": candidates, "exact_over_closed_form": exact["wall_s"] / closed["wall_s"],
            "ode_over_closed_form": ode_wall / closed["wall_s"], "ode_over_exact": ode_wall / exact["wall_s"]}


def per_cycle_times(params: Parameters, x0: float, n_cycles=(50, 1000, 100_000), min_seconds: float = 0.2,
                    max_repeats: int = 500) -> list[dict]:
    """Wall time per cycle of the exact solver and of the per-cycle closed form, and their ratio, per ``n_cycles``."""
    _check_timing(min_seconds, max_repeats)
    rows = []
    for n in n_cycles:
        exact = median_wall(lambda: solve_exact(params, x0, n_cycles=n, record_trajectory=False), min_seconds,
                            max_repeats)[0]
        closed = median_wall(lambda: solve_cycles(params, x0, n_cycles=n), min_seconds, max_repeats)[0]
        rows.append({"n_cycles": n, "exact_s_per_cycle": exact / n, "closed_form_s_per_cycle": closed / n,
                     "ratio": exact / closed})
    return rows
