"""Long runs: how the error of the impact time grows with the number of cycles.

The reference is the 50-digit solution of :mod:`escapement.integrators.high_precision` until the
transient has decayed below 1e-45 (in v^2 it decays by (1-b)^4 per cycle), and from there
on exactly periodic: t_ref(n) = t_ref(n0) + (n - n0) T*, computed in 50 digits.

The subject is the exact event solver: its cycles come in chunks
(:func:`escapement.solvers.stream.iter_cycles`), of which only the sampled cycles and the largest
deviations after convergence are kept, so the run takes the same memory for 10**4 cycles as for 10**8;
it runs over the first ``check_cycles`` cycles (by default the whole run up to :data:`EXACT_CHECK_CYCLES`).
Beside it, the per-cycle closed forms (:func:`escapement.solvers.cycles.iter_closed_form_cycles`: the
return map of v^2 and each cycle's arcs, the impact times a compensated sum of the periods) give the
same series over all ``n_cycles`` cycles, streamed in chunks of the same size, a few vectorised calls
each; every chunk of the event solver is compared with the closed forms' chunk beside it, quantity by
quantity, and the largest relative difference is reported. Both take memory for one chunk at a time.
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from ..model.limits import MAX_CYCLES, check_count
from ..model.parameters import ParameterError, Parameters
from ..solvers.cycles import compare_tables, iter_closed_form_cycles
from ..integrators.high_precision import solve_high_precision
from ..integrators.reference import solve_reference
from ..solvers.result import CycleTable
from ..solvers.stream import iter_cycles

__all__ = ["EXACT_CHECK_CYCLES", "converged_after", "sample_cycles", "long_run"]

#: cycles per chunk of both streamed series
CHUNK = 100_000
#: the cycles the streamed event solver checks the closed form over unless told otherwise: the whole of the
#: workflow's long run (10**6 cycles, a couple of seconds); a longer run is checked on this prefix
EXACT_CHECK_CYCLES = 1_000_000


def converged_after(params: Parameters, digits: int = 45) -> int:
    """Cycles after which the transient of v^2 is below 10**-digits of its start."""
    mu = (1 - params.b) ** 4
    if mu == 0.0:
        return 2
    return int(math.ceil(digits * math.log(10) / -math.log(mu))) + 2


def sample_cycles(n_cycles: int, per_decade: int = 40) -> np.ndarray:
    """Cycle numbers 1 .. n_cycles, spaced evenly in log."""
    decades = math.log10(n_cycles)
    return np.unique(np.round(np.logspace(0, decades, int(per_decade * decades) + 1)).astype(int))


def long_run(params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float, ivp_cycles: int,
             check_cycles: int | None = None) -> dict:
    """Errors of the exact solver and of the per-cycle closed forms over ``n_cycles``, and of ``solve_ivp``
    over ``ivp_cycles``, against the 50-digit reference.

    ``exact``, ``closed_form`` and ``ivp`` hold each method's relative errors of the impact time and of the
    velocity, and the drift of the impact time, at the sampled ``cycles`` (NaN past the cycles it ran: the
    event solver runs ``check_cycles`` cycles, by default ``n_cycles`` up to :data:`EXACT_CHECK_CYCLES`).
    ``max_velocity_deviation`` and ``max_period_deviation`` are the event solver's largest relative
    deviations from the limit cycle after :func:`converged_after` cycles. ``check_differences`` holds the
    largest relative difference between the closed forms and the event solver per quantity
    (``check_max_relative_difference`` the largest; inf if one ended where the other did not);
    ``series_method`` says which method made the closed-form series (``"closed-form cycles"``, or
    ``"exact"`` where the closed form does not apply). ``exact_wall_s``, ``closed_form_wall_s`` and
    ``ivp_wall_s`` are the wall times.

    ``n_cycles`` and ``check_cycles`` must exceed :func:`converged_after` (the deviations are taken after it)."""
    n_cycles = check_count("n_cycles", n_cycles, MAX_CYCLES)
    n_check = min(n_cycles, EXACT_CHECK_CYCLES) if check_cycles is None else check_count(
        "check_cycles", check_cycles, n_cycles)
    n0 = converged_after(params)
    for name, value in (("n_cycles", n_cycles), ("check_cycles", n_check)):
        if value <= n0:
            raise ParameterError(name, value, f"> {n0:_}, the cycles after which the transient has decayed "
                                 "below 1e-45 (the deviations from the fixed point are taken after them)")
    hp = solve_high_precision(params, x0, n_cycles=n0 + 1, dps=50).cycles
    cycles = sample_cycles(n_cycles)
    with mpmath.workdps(60):
        t_star, v_star = hp.period[-1], hp.velocity_before_impact[-1]

        def t_ref(n):
            return hp.impact_time[n - 1] if n <= n0 + 1 else hp.impact_time[n0] + (n - n0 - 1) * t_star

        def v_ref(n):
            return hp.velocity_before_impact[n - 1] if n <= n0 + 1 else v_star

        reference_t = [t_ref(int(n)) for n in cycles]
        reference_v = [v_ref(int(n)) for n in cycles]

        def errors(t, v, available):
            """Errors at the sampled cycles; ``t``, ``v`` hold the run's values at them (NaN past ``available``)."""
            et, ev, drift = (np.full(len(cycles), np.nan) for _ in range(3))
            for i, n in enumerate(cycles):
                if n <= available:
                    drift[i] = float(mpmath.mpf(t[i]) - reference_t[i])
                    et[i] = abs(drift[i]) / float(reference_t[i])
                    ev[i] = float(abs(mpmath.mpf(v[i]) - reference_v[i]) / reference_v[i])
            return et, ev, drift

        # the per-cycle series in closed form over n_cycles and the event solver's over the first n_check,
        # both streamed in chunks of the same size, side by side: the sampled cycles of each, the event
        # solver's deviations from the limit cycle once converged, and the two series' differences
        wall = time.perf_counter()
        closed = iter_closed_form_cycles(params, x0, n_cycles=n_cycles, chunk=CHUNK)
        closed_wall = time.perf_counter() - wall
        wall = time.perf_counter()
        stream = iter_cycles(params, x0, n_cycles=n_check, chunk=CHUNK)
        exact_wall = time.perf_counter() - wall
        closed_t, closed_v, sampled_t, sampled_v = (np.full(len(cycles), np.nan) for _ in range(4))
        differences = dict.fromkeys(("impact_time", "velocity_before_impact", "period", "largest_displacement"), 0.0)
        max_v_dev = max_t_dev = -math.inf
        any_nan = False
        done = checked = 0  # cycles before the chunk, of each series
        parts = [closed, stream]  # the series still under way
        for _ in range(n_cycles // CHUNK + 3):
            wall = time.perf_counter()
            part = next(closed, None) if closed in parts else None
            closed_wall += time.perf_counter() - wall
            wall = time.perf_counter()
            chunk = next(stream, None) if stream in parts else None
            exact_wall += time.perf_counter() - wall
            if part is None and closed in parts:
                parts.remove(closed)
            if chunk is None and stream in parts:
                parts.remove(stream)
            if not parts:
                break
            if part is not None:
                _take(part, done, cycles, closed_t, closed_v)
                done += len(part)
            if chunk is None:
                continue
            size = len(chunk)
            _take(chunk, checked, cycles, sampled_t, sampled_v)
            tail = slice(max(n0 - checked, 0), size)  # the cycles from n0 + 1 on (index n0 of the whole run)
            if tail.start < size:
                max_v_dev = max(max_v_dev, float(np.max(np.abs(chunk.velocity_before_impact[tail] - float(v_star)))))
                max_t_dev = max(max_t_dev, float(np.max(np.abs(chunk.period[tail] - float(t_star)))))
            any_nan = any_nan or bool(np.isnan(chunk.impact_time).any() or np.isnan(chunk.velocity_before_impact).any())
            if part is not None:  # the same cycles, both series chunked alike
                for name, gap in compare_tables(part, chunk).items():
                    differences[name] = math.nan if math.isnan(gap) or math.isnan(differences[name]) else max(
                        differences[name], gap)
            checked += size
        else:
            raise RuntimeError(f"the two series did not end within {n_cycles // CHUNK + 3} chunks")
        if done <= n0:
            raise RuntimeError(f"the run ended after {done} cycles, before cycle {n0 + 1}: {closed.summary.message}")
        closed_form = errors(closed_t, closed_v, done)
        if checked <= n0:
            raise RuntimeError(f"the exact run ended after {checked} cycles, before cycle {n0 + 1}: "
                               f"{stream.summary.message}")
        if checked != min(n_check, done):
            differences = dict.fromkeys(differences, math.inf)  # one run ended where the other did not
        exact = errors(sampled_t, sampled_v, checked)
        max_v_dev /= float(v_star)
        max_t_dev /= float(t_star)
        worst = math.nan if any(math.isnan(d) for d in differences.values()) else max(differences.values())
        start = time.perf_counter()
        ivp = solve_reference(params, x0, n_cycles=ivp_cycles, method=ivp_method, rtol=ivp_rtol,
                              record_trajectory=False)
        ivp_wall = time.perf_counter() - start
        ivp_errors = errors(*_sampled(ivp.cycles, cycles), len(ivp.cycles))
    return {
        "cycles": cycles,
        "exact": exact,
        "closed_form": closed_form,
        "ivp": ivp_errors,
        "converged_after": n0,
        "max_velocity_deviation": max_v_dev,
        "max_period_deviation": max_t_dev,
        "fixed_point_velocity": float(v_star),
        "fixed_point_period": float(t_star),
        "exact_wall_s": exact_wall,
        "ivp_wall_s": ivp_wall,
        "any_nan": any_nan,
        "series_method": closed.method,
        "fallback": closed.fallback,
        "distinct_cycles": closed.distinct_cycles,
        "closed_form_wall_s": closed_wall,
        "check_cycles": checked,
        "check_differences": differences,
        "check_max_relative_difference": worst,
    }


def _take(chunk: CycleTable, before: int, cycles: np.ndarray, t: np.ndarray, v: np.ndarray) -> None:
    """Into ``t`` and ``v``, the impact times and velocities of a chunk that follows ``before`` cycles at the
    sampled cycle numbers ``cycles`` it holds."""
    here = (cycles > before) & (cycles <= before + len(chunk))
    t[here] = chunk.impact_time[cycles[here] - before - 1]
    v[here] = chunk.velocity_before_impact[cycles[here] - before - 1]


def _sampled(table, cycles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Impact times and velocities of a cycle table at the cycle numbers ``cycles`` (NaN past its end)."""
    here = cycles <= len(table)
    t, v = (np.full(len(cycles), np.nan) for _ in range(2))
    t[here] = table.impact_time[cycles[here] - 1]
    v[here] = table.velocity_before_impact[cycles[here] - 1]
    return t, v
