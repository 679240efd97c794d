"""Long runs: how the error of the impact time grows with the number of cycles.

The reference is the 50-digit solution of :mod:`escapement.solvers.high_precision` until the
transient has decayed below 1e-45 (in v^2 it decays by (1-b)^4 per cycle), and from there
on exactly periodic: t_ref(n) = t_ref(n0) + (n - n0) T*, computed in 50 digits.

The exact solver's cycles come in chunks (:func:`escapement.solvers.stream.iter_cycles`), of which only
the sampled cycles and the largest deviations after convergence are kept: the run takes the same memory
for 10**4 cycles as for 10**8.
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from ..model.limits import MAX_CYCLES, check_count
from ..model.parameters import ParameterError, Parameters
from ..solvers.high_precision import solve_high_precision
from ..solvers.reference import solve_reference
from ..solvers.stream import iter_cycles

__all__ = ["converged_after", "sample_cycles", "long_run"]


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


def long_run(params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float, ivp_cycles: int) -> dict:
    """Errors of the exact solver over ``n_cycles`` and of ``solve_ivp`` over ``ivp_cycles``.

    ``n_cycles`` must exceed :func:`converged_after` (the deviations are taken after it)."""
    n_cycles = check_count("n_cycles", n_cycles, MAX_CYCLES)
    n0 = converged_after(params)
    if n_cycles <= n0:
        raise ParameterError("n_cycles", n_cycles, f"> {n0:_}, the cycles after which the transient has decayed "
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

        start = time.perf_counter()
        sampled_t, sampled_v = (np.full(len(cycles), np.nan) for _ in range(2))
        max_v_dev = max_t_dev = -math.inf
        any_nan = False
        done = 0  # cycles before the chunk
        stream = iter_cycles(params, x0, n_cycles=n_cycles)
        for chunk in stream:
            size = len(chunk)
            here = (cycles > done) & (cycles <= done + size)
            sampled_t[here] = chunk.impact_time[cycles[here] - done - 1]
            sampled_v[here] = chunk.velocity_before_impact[cycles[here] - done - 1]
            tail = slice(max(n0 - done, 0), size)  # the cycles from n0 + 1 on (index n0 of the whole run)
            if tail.start < size:
                max_v_dev = max(max_v_dev, float(np.max(np.abs(chunk.velocity_before_impact[tail] - float(v_star)))))
                max_t_dev = max(max_t_dev, float(np.max(np.abs(chunk.period[tail] - float(t_star)))))
            any_nan = any_nan or bool(np.isnan(chunk.impact_time).any() or np.isnan(chunk.velocity_before_impact).any())
            done += size
        exact_wall = time.perf_counter() - start
        if done <= n0:
            raise RuntimeError(f"the exact run ended after {done} cycles, before cycle {n0 + 1}: "
                               f"{stream.summary.message}")
        exact = errors(sampled_t, sampled_v, done)
        max_v_dev /= float(v_star)
        max_t_dev /= float(t_star)

        start = time.perf_counter()
        ivp = solve_reference(params, x0, n_cycles=ivp_cycles, method=ivp_method, rtol=ivp_rtol,
                              record_trajectory=False)
        ivp_wall = time.perf_counter() - start
        ivp_errors = errors(*_sampled(ivp.cycles, cycles), len(ivp.cycles))
    return {
        "cycles": cycles,
        "exact": exact,
        "ivp": ivp_errors,
        "converged_after": n0,
        "max_velocity_deviation": max_v_dev,
        "max_period_deviation": max_t_dev,
        "fixed_point_velocity": float(v_star),
        "fixed_point_period": float(t_star),
        "exact_wall_s": exact_wall,
        "ivp_wall_s": ivp_wall,
        "any_nan": any_nan,
    }


def _sampled(table, cycles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Impact times and velocities of a cycle table at the cycle numbers ``cycles`` (NaN past its end)."""
    here = cycles <= len(table)
    t, v = (np.full(len(cycles), np.nan) for _ in range(2))
    t[here] = table.impact_time[cycles[here] - 1]
    v[here] = table.velocity_before_impact[cycles[here] - 1]
    return t, v
