"""Work-precision benchmark: wall time against error for every method, timed in one run.

Workload: ``n_cycles`` cycles from release at rest (the workflow gives the Fig. 3 case its config names).
Errors are relative, at the last cycle, for the velocity before impact and the impact time,
against the 50-digit reference of :mod:`escapement.integrators.high_precision`.

Timing is adaptive: each setting is run again until ``min_seconds`` of runs have been measured
(at least once, at most ``max_repeats`` times), and its wall time is the median. Every method first runs
one untimed cycle, so that no row times the loading of a method's modules. A fast method
(the exact solver: a millisecond) is repeated hundreds of times, which keeps the noise of a
shared machine in check; a slow one (seconds per run) runs once or twice. The whole table then
costs about ``min_seconds`` per setting, plus the slow runs.

Beside the exact event solver, ``closed-form cycles`` is the per-cycle closed form
(:func:`escapement.solvers.cycles.solve_cycles`: the event solver up to the first impact at a1, then the return
map of v^2 and each cycle's arcs in a few vectorised calls); :func:`work_precision` adds its row after
``exact`` whenever ``exact`` is among the settings. :func:`headline_ratios` measures, side by side in one process,
the exact solver, the closed form and the fastest ``solve_ivp``/CVODE setting that reaches a target error
(1e-12 on 1000 cycles by default), and :func:`per_cycle_times` the time per cycle of the closed form and of the
exact solver at several lengths.
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
    """Velocity before impact and impact time at cycle ``n_cycles`` from closed forms alone.

    The first impact at a1 from release at rest (energy and arccos forms): from ``x0 < a1 < 0`` the swing
    reaches a1 at acos(a1/x0)/w; from ``x0 > a3 > 0`` it reaches a3 at acos(a3/x0)/w, runs through the zone
    to a4 and swings to a1. Then Eq. (16) for the velocities and the corrected Eq. (23) for the periods.
    """
    p = params
    w = p.omega
    n_cycles = check_count("n_cycles", n_cycles, MAX_CYCLES)
    if x0 < p.a1 < 0:
        v, t = w * math.sqrt((x0 - p.a1) * (x0 + p.a1)), math.acos(p.a1 / x0) / w
    elif x0 > p.a3 > 0:
        v, t = _first_impact_from_the_right(p, x0)
    else:
        raise ParameterError("x0", x0, f"a release left of a1 = {p.a1!r} < 0 or right of a3 = {p.a3!r} > 0 (m), "
                             "from which the first swing reaches an impact")
    for _ in range(n_cycles - 1):
        t += derived.period(v, p)
        v = math.sqrt((1 - p.b) ** 4 * v * v + derived.map_constant(p))
    return v, t


def _first_impact_from_the_right(p: Parameters, x0: float) -> tuple[float, float]:
    """Velocity before and time of the first impact at a1 from rest at ``x0 > a3 > 0``."""
    w = p.omega
    v3 = -w * math.sqrt((x0 - p.a3) * (x0 + p.a3))
    v3p = (1 - p.b) * v3
    v4_sq = v3p**2 + p.omega2 * (p.a3 - p.a4) * (p.a3 + p.a4) + 2 * (p.a3 - p.a4) * p.f
    h = math.sqrt(p.a4**2 + v4_sq / p.omega2)
    t = (
        math.acos(p.a3 / x0) / w
        + derived._zone_time(-p.zone_offset, p.a3, p.a4, v3p, w)
        + (math.acos(-p.a4 / h) + math.acos(-p.a1 / h)) / w
    )
    return math.sqrt(v4_sq + p.omega2 * (p.a4 - p.a1) * (p.a4 + p.a1)), t


def run_method(method: str, setting: float | None, params: Parameters, x0: float, n_cycles: int):
    """One run; returns (velocity before impact, impact time) at cycle ``n_cycles``."""
    if method == "exact":
        c = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=False).cycles
        return float(c.velocity_before_impact[-1]), float(c.impact_time[-1])
    if method == CLOSED_FORM:
        run = solve_cycles(params, x0, n_cycles=n_cycles)
        if len(run.cycles) < n_cycles:
            raise RuntimeError(f"{CLOSED_FORM} ended early: {run.message}")
        return float(run.cycles.velocity_before_impact[-1]), float(run.cycles.impact_time[-1])
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
    one); return the median wall time, the number of runs and the last result.

    Not :mod:`timeit`: its ``autorange`` has a fixed 0.2 s budget and a mean over loops, and neither it nor
    ``repeat`` returns the call's result, which a setting of seconds (run once) would then have to run again for.
    """
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


def _warm_up(settings: dict[str, list], params: Parameters, x0: float) -> None:
    """One untimed cycle of every method at its first setting: the modules a method loads on first use
    (SciPy's integrators: a third of a second) and its first call's set-up are not timed in its first row."""
    for method, values in settings.items():
        run_method(method, values[0] if values else None, params, x0, 1)


def _reference(params: Parameters, x0: float, n_cycles: int) -> tuple[float, float]:
    """Velocity before impact and impact time at cycle ``n_cycles``, 50 digits, as floats."""
    ref = solve_high_precision(params, x0, n_cycles=n_cycles).cycles
    return float(ref.velocity_before_impact[-1]), float(ref.impact_time[-1])


def _row(method: str, setting, params: Parameters, x0: float, n_cycles: int, reference: tuple[float, float],
         min_seconds: float, max_repeats: int, log=None) -> dict:
    """One setting timed (:func:`median_wall`) and its errors at the last cycle against ``reference``."""
    v_ref, t_ref = reference
    wall, runs, (v, t) = median_wall(lambda: run_method(method, setting, params, x0, n_cycles), min_seconds,
                                     max_repeats)
    row = {
        "method": method,
        "setting": "" if setting is None else f"{setting:g}",
        "wall_s": wall,
        "repeats": runs,
        "error_velocity": abs(v - v_ref) / abs(v_ref),
        "error_time": abs(t - t_ref) / abs(t_ref),
    }
    if log is not None:
        log(f"{method} {row['setting']}: {wall:.3e} s (median of {runs}), "
            f"errors {row['error_velocity']:.2e} {row['error_time']:.2e}")
    return row


def work_precision(
    params: Parameters, x0: float, n_cycles: int, settings: dict[str, list], min_seconds: float, max_repeats: int,
    log=None, closed_form: bool = True,
) -> list[dict]:
    """Rows ``method, setting, wall_s, repeats, error_velocity, error_time`` for every method and setting.

    With ``closed_form`` (the default) the per-cycle closed form's row (``closed-form cycles``, no setting)
    follows ``exact``'s wherever the settings name ``exact`` but not it."""
    _check_timing(min_seconds, max_repeats)
    _check_methods(settings)
    if closed_form and "exact" in settings and CLOSED_FORM not in settings:
        ordered = {}
        for method, values in settings.items():
            ordered[method] = values
            if method == "exact":
                ordered[CLOSED_FORM] = []
        settings = ordered
    reference = _reference(params, x0, n_cycles)
    _warm_up(settings, params, x0)
    return [_row(method, setting, params, x0, n_cycles, reference, min_seconds, max_repeats, log)
            for method, values in settings.items() for setting in values or [None]]


def headline_ratios(
    params: Parameters, x0: float, n_cycles: int = 1000, settings: dict[str, list] | None = None,
    target: float = 1e-12, errors: tuple[str, ...] = ("error_velocity", "error_time"), min_seconds: float = 0.2,
    max_repeats: int = 500, log=None,
) -> dict:
    """The exact solver, the per-cycle closed form and the fastest integrator setting that reaches ``target``,
    timed side by side in one process on ``n_cycles`` cycles, and the ratios of their wall times.

    Every run is timed as in :func:`work_precision` (:func:`median_wall`) and its errors measured the same way
    (relative, at the last cycle, against 50 digits). An integrator setting (``settings``: method to rtols,
    default :data:`HEADLINE_SETTINGS`) reaches the target where each error named in ``errors`` is at most
    ``target``; the fastest of those is the one compared.

    Returns a dict: ``n_cycles``, ``target``, ``errors``; the rows (as :func:`work_precision`'s) ``exact``,
    ``closed_form`` and ``ode`` (None where no setting reaches the target), and ``candidates`` (every integrator
    row); and the ratios ``exact_over_closed_form``, ``ode_over_closed_form`` and ``ode_over_exact`` (wall
    time over wall time; NaN without an ``ode`` row).
    """
    _check_timing(min_seconds, max_repeats)
    settings = HEADLINE_SETTINGS if settings is None else settings
    _check_methods(settings)
    if not set(errors) <= {"error_velocity", "error_time"} or not errors:
        raise ValueError(f"errors = {errors!r} is invalid: errors must name error_velocity, error_time or both")
    if not (isinstance(target, int | float) and target > 0):
        raise ValueError(f"target = {target!r} is invalid: target must be > 0")
    reference = _reference(params, x0, n_cycles)
    _warm_up({"exact": [], CLOSED_FORM: [], **settings}, params, x0)

    def row(method, setting=None):
        return _row(method, setting, params, x0, n_cycles, reference, min_seconds, max_repeats, log)

    exact, closed = row("exact"), row(CLOSED_FORM)
    candidates = [row(method, setting) for method, values in settings.items() if method in INTEGRATORS
                  for setting in values]
    reaching = [r for r in candidates if all(r[name] <= target for name in errors)]
    ode = min(reaching, key=lambda r: r["wall_s"]) if reaching else None
    ode_wall = math.nan if ode is None else ode["wall_s"]
    return {
        "n_cycles": n_cycles,
        "target": target,
        "errors": tuple(errors),
        "exact": exact,
        "closed_form": closed,
        "ode": ode,
        "candidates": candidates,
        "exact_over_closed_form": exact["wall_s"] / closed["wall_s"],
        "ode_over_closed_form": ode_wall / closed["wall_s"],
        "ode_over_exact": ode_wall / exact["wall_s"],
    }


def per_cycle_times(params: Parameters, x0: float, n_cycles=(50, 1000, 100_000), min_seconds: float = 0.2,
                    max_repeats: int = 500) -> list[dict]:
    """Wall time per cycle of the per-cycle closed form and of the exact solver, timed side by side
    (:func:`median_wall`) for each number of cycles: rows ``n_cycles``, ``exact_s_per_cycle``,
    ``closed_form_s_per_cycle`` and ``ratio`` (exact over closed form)."""
    _check_timing(min_seconds, max_repeats)
    rows = []
    for n in n_cycles:
        exact = median_wall(lambda: solve_exact(params, x0, n_cycles=n, record_trajectory=False), min_seconds,
                            max_repeats)[0]
        closed = median_wall(lambda: solve_cycles(params, x0, n_cycles=n), min_seconds, max_repeats)[0]
        rows.append({"n_cycles": n, "exact_s_per_cycle": exact / n, "closed_form_s_per_cycle": closed / n,
                     "ratio": exact / closed})
    return rows
