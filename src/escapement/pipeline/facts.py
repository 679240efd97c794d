"""Numbers for the generated documents, read from the workflow's outputs.

A fact is deterministic (an error against 50 digits, a measured multiplier) or measured
(a wall time or a ratio of wall times, which varies from run to run and machine to
machine). Measured facts come from the timing tables, never from a netCDF dataset, and appear
only in ``results/docs/timings.md``, never in a document git tracks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..paper.claims import fmt

__all__ = ["Fact", "collect_facts"]


@dataclass(frozen=True)
class Fact:
    value: str
    measured: bool = False


def _row(rows: list[dict], method: str, setting: str = "") -> dict:
    for row in rows:
        if row["method"] == method and row["setting"] == setting:
            return row
    raise KeyError(f"the benchmark has no run of {method} {setting}")


def collect_facts(
    benchmark_rows: list[dict], long_run: xr.Dataset, stability: xr.Dataset, long_run_timings: dict[str, float],
    stability_timings: dict[str, float],
) -> dict[str, Fact]:
    facts: dict[str, Fact] = {}
    exact = _row(benchmark_rows, "exact")
    for row in benchmark_rows:
        key = f"bench_{row['method']}_{row['setting'] or 'none'}".replace("-", "_").replace(".", "p")
        facts[f"{key}_wall"] = Fact(fmt(float(row["wall_s"]), 3), measured=True)
        facts[f"{key}_error_velocity"] = Fact(fmt(float(row["error_velocity"]), 2))
        facts[f"{key}_error_time"] = Fact(fmt(float(row["error_time"]), 2))
        facts[f"{key}_ratio"] = Fact(fmt(float(row["wall_s"]) / float(exact["wall_s"]), 3), measured=True)
    exact_methods = ("exact", "closed-form cycles", "map16")
    worst_ivp = max(float(r["wall_s"]) for r in benchmark_rows if r["method"] not in exact_methods)
    facts["bench_slowest_ratio"] = Fact(fmt(worst_ivp / float(exact["wall_s"]), 3), measured=True)

    a = long_run.attrs
    facts["long_n_cycles"] = Fact(f"{int(a['n_cycles']):,}".replace(",", " "))
    facts["long_ivp_cycles"] = Fact(str(int(a["ivp_cycles"])))
    facts["long_velocity_deviation"] = Fact(fmt(float(long_run["max_velocity_deviation"]), 2))
    facts["long_period_deviation"] = Fact(fmt(float(long_run["max_period_deviation"]), 2))
    facts["long_converged_after"] = Fact(str(int(a["converged_after"])))
    facts["long_exact_wall"] = Fact(fmt(long_run_timings["exact_seconds"], 3), measured=True)
    facts["long_ivp_wall"] = Fact(fmt(long_run_timings["ivp_seconds"], 3), measured=True)
    facts["long_closed_form_wall"] = Fact(fmt(long_run_timings["closed_form_seconds"], 3), measured=True)
    facts["long_closed_form_difference"] = Fact(fmt(float(long_run["closed_form_difference"]), 2))
    facts["long_nan"] = Fact("none" if not a["any_nan"] else "some")
    for solver in ("exact", "closed_form", "ivp"):
        drift = long_run[f"drift_{solver}"].dropna("cycle")
        facts[f"long_{solver}_last_cycle"] = Fact(str(int(drift["cycle"].values[-1])))
        facts[f"long_{solver}_last_drift"] = Fact(fmt(abs(float(drift.values[-1])), 2))
        facts[f"long_{solver}_max_error_time"] = Fact(fmt(float(long_run[f"error_time_{solver}"].max()), 2))

    mu, mu21 = stability["multiplier"].values, stability["multiplier_eq21"].values
    meanings = stability["outcome"].attrs["flag_meanings"].split()
    outcome = stability["outcome"].values
    completed = outcome == meanings.index("completed")
    facts["stab_points"] = Fact(f"{outcome.size:,}".replace(",", " "))
    facts["stab_shape"] = Fact(f"{stability.sizes['b']} x {stability.sizes['F']}")
    facts["stab_max_deviation"] = Fact(fmt(float(np.nanmax(np.abs(mu - mu21))), 2))
    facts["stab_completed"] = Fact(str(int(completed.sum())))
    facts["stab_left"] = Fact(str(int((~completed).sum())))
    left_b = stability["b"].values[(~completed).any(axis=1)]
    facts["stab_left_b_min"] = Fact(fmt(float(left_b.min()), 4) if left_b.size else "none")
    t = stability_timings
    facts["stab_speedup"] = Fact(fmt(t["ensemble_speedup_per_trajectory"], 3), measured=True)
    facts["stab_ensemble_per_trajectory"] = Fact(fmt(t["ensemble_seconds_per_trajectory"], 2), measured=True)
    facts["stab_scalar_per_trajectory"] = Fact(fmt(t["scalar_seconds_per_trajectory"], 2), measured=True)
    return facts
