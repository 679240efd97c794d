"""Long runs: how the error of the impact time grows with the number of cycles.

The reference is the 50-digit solution of :mod:`escapement.solvers.high_precision` until the
transient has decayed below 1e-45 (in v^2 it decays by (1-b)^4 per cycle), and from there
on exactly periodic: t_ref(n) = t_ref(n0) + (n - n0) T*, computed in 50 digits.
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from ..model.parameters import Parameters
from ..solvers.exact import solve_exact
from ..solvers.high_precision import solve_high_precision
from ..solvers.reference import solve_reference

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
    """Errors of the exact solver over ``n_cycles`` and of ``solve_ivp`` over ``ivp_cycles``."""
    n0 = converged_after(params)
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
            et, ev, drift = (np.full(len(cycles), np.nan) for _ in range(3))
            for i, n in enumerate(cycles):
                if n <= available:
                    drift[i] = float(mpmath.mpf(t[n - 1]) - reference_t[i])
                    et[i] = abs(drift[i]) / float(reference_t[i])
                    ev[i] = float(abs(mpmath.mpf(v[n - 1]) - reference_v[i]) / reference_v[i])
            return et, ev, drift

        start = time.perf_counter()
        run = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=False)
        exact_wall = time.perf_counter() - start
        c = run.cycles
        exact = errors(c.impact_time, c.velocity_before_impact, len(c))
        tail = slice(n0, len(c))
        max_v_dev = float(np.max(np.abs(c.velocity_before_impact[tail] - float(v_star)))) / float(v_star)
        max_t_dev = float(np.max(np.abs(c.period[tail] - float(t_star)))) / float(t_star)

        start = time.perf_counter()
        ivp = solve_reference(params, x0, n_cycles=ivp_cycles, method=ivp_method, rtol=ivp_rtol,
                              record_trajectory=False)
        ivp_wall = time.perf_counter() - start
        ivp_errors = errors(ivp.cycles.impact_time, ivp.cycles.velocity_before_impact, len(ivp.cycles))
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
        "any_nan": bool(np.isnan(c.impact_time).any() or np.isnan(c.velocity_before_impact).any()),
    }
