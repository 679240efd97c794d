"""Long runs: how the error of the impact time grows with the number of cycles, against the 50-digit solution until
the transient has decayed below 1e-45, exactly periodic from there on (t_ref(n) = t_ref(n0) + (n - n0) T*). The
closed forms and the event solver are streamed chunk by chunk side by side and compared; only the sampled cycles and
running maxima are kept, so that 10**8 cycles take the memory of one chunk.
"""

from __future__ import annotations

import itertools
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
#: the cycles the event solver checks the closed form over by default: the workflow's whole long run
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
    """Errors against the 50-digit reference of the exact solver over ``check_cycles``, of the closed forms over
    ``n_cycles`` and of ``solve_ivp`` over ``ivp_cycles``: ``exact``, ``closed_form`` and ``ivp`` hold the relative
    errors of the impact time and velocity and the drift of the impact time at the sampled ``cycles`` (NaN past the
    cycles a method ran); the event solver's largest relative deviations from the limit cycle after
    :func:`converged_after` cycles; ``check_differences``, the largest relative difference of the two series per
    quantity (inf if one ended where the other did not); and the wall times."""
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

        reference_t = [hp.impact_time[n - 1] if n <= n0 + 1 else hp.impact_time[n0] + (n - n0 - 1) * t_star
                       for n in map(int, cycles)]
        reference_v = [hp.velocity_before_impact[n - 1] if n <= n0 + 1 else v_star for n in map(int, cycles)]

        def errors(t, v, available):
            """Errors at the sampled cycles; ``t``, ``v`` hold the run's values at them (NaN past ``available``)."""
            et, ev, drift = (np.full(len(cycles), np.nan) for _ in range(3))
            for i, n in enumerate(cycles):
                if n <= available:
                    drift[i] = float(mpmath.mpf(t[i]) - reference_t[i])
                    et[i] = abs(drift[i]) / float(reference_t[i])
                    ev[i] = float(abs(mpmath.mpf(v[i]) - reference_v[i]) / reference_v[i])
            return et, ev, drift

        walls = {"closed": 0.0, "exact": 0.0, "ivp": 0.0}

        def timed(key, make):
            start = time.perf_counter()
            made = make()
            walls[key] += time.perf_counter() - start
            return made

        closed = timed("closed", lambda: iter_closed_form_cycles(params, x0, n_cycles=n_cycles, chunk=CHUNK))
        stream = timed("exact", lambda: iter_cycles(params, x0, n_cycles=n_check, chunk=CHUNK))
        parts = iter(lambda: timed("closed", lambda: next(closed, None)), None)
        chunks = iter(lambda: timed("exact", lambda: next(stream, None)), None)
        closed_t, closed_v, sampled_t, sampled_v = (np.full(len(cycles), np.nan) for _ in range(4))
        differences = dict.fromkeys(("impact_time", "velocity_before_impact", "period", "largest_displacement"), 0.0)
        max_v_dev = max_t_dev = -math.inf
        any_nan = False
        done = checked = 0  # cycles before the chunk, of each series
        for part, chunk in itertools.zip_longest(parts, chunks):  # None once a series has ended
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
                    differences[name] = float(np.maximum(differences[name], gap))  # NaN stays NaN
            checked += size
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
        worst = float(np.max(list(differences.values())))  # NaN if any is
        ivp = timed("ivp", lambda: solve_reference(params, x0, n_cycles=ivp_cycles, method=ivp_method, rtol=ivp_rtol,
                                                   record_trajectory=False))
        ivp_t, ivp_v = (np.full(len(cycles), np.nan) for _ in range(2))
        _take(ivp.cycles, 0, cycles, ivp_t, ivp_v)
        ivp_errors = errors(ivp_t, ivp_v, len(ivp.cycles))
    return {"cycles": cycles, "exact": exact, "closed_form": closed_form, "ivp": ivp_errors, "converged_after": n0,
            "max_velocity_deviation": max_v_dev, "max_period_deviation": max_t_dev,
            "fixed_point_velocity": float(v_star), "fixed_point_period": float(t_star), "exact_wall_s": walls["exact"],
            "ivp_wall_s": walls["ivp"], "any_nan": any_nan, "series_method": closed.method, "fallback": closed.fallback,
            "distinct_cycles": closed.distinct_cycles, "closed_form_wall_s": walls["closed"], "check_cycles": checked,
            "check_differences": differences, "check_max_relative_difference": worst}


def _take(chunk: CycleTable, before: int, cycles: np.ndarray, t: np.ndarray, v: np.ndarray) -> None:
    """Into ``t``, ``v``: the impact times, velocities at the sampled ``cycles`` of a chunk after ``before`` cycles."""
    here = (cycles > before) & (cycles <= before + len(chunk))
    t[here] = chunk.impact_time[cycles[here] - before - 1]
    v[here] = chunk.velocity_before_impact[cycles[here] - before - 1]

