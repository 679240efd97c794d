"""Numbers for the generated documents, read from the workflow's outputs, in two kinds: deterministic facts (an
error against 50 digits, a measured multiplier), which the tracked documents may show, and measured ones (a wall
time or a ratio of wall times, which varies from run to run and machine to machine), read from the timing
tables only and shown only in ``timings.md``, never in a tracked document."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..model.status import succeeded
from ..verdict.evidence import fmt

__all__ = ["collect_facts"]


def collect_facts(benchmark_rows: list[dict], long_run: xr.Dataset, stability: xr.Dataset,
                  long_run_timings: dict[str, float], stability_timings: dict[str, float]
                  ) -> tuple[dict[str, str], dict[str, str]]:
    """The deterministic facts and the measured ones, each by its name in the templates."""
    facts: dict[str, str] = {}
    measured: dict[str, str] = {}
    exact = next(float(row["wall_s"]) for row in benchmark_rows if row["method"] == "exact")
    for row in benchmark_rows:
        key = f"bench_{row['method']}_{row['setting'] or 'none'}".replace("-", "_").replace(".", "p")
        wall = float(row["wall_s"])
        measured.update({f"{key}_wall": fmt(wall, 3), f"{key}_ratio": fmt(wall / exact, 3)})
        facts.update({f"{key}_error_{of}": fmt(float(row[f"error_{of}"]), 2) for of in ("velocity", "time")})
    slowest = max(float(r["wall_s"]) for r in benchmark_rows if r["method"] not in ("exact", "map16"))
    measured["bench_slowest_ratio"] = fmt(slowest / exact, 3)

    a = long_run.attrs
    facts.update(
        long_n_cycles=f"{int(a['n_cycles']):,}".replace(",", " "), long_ivp_cycles=str(int(a["ivp_cycles"])),
        long_velocity_deviation=fmt(float(long_run["max_velocity_deviation"]), 2),
        long_period_deviation=fmt(float(long_run["max_period_deviation"]), 2),
        long_converged_after=str(int(a["converged_after"])),
        long_closed_form_difference=fmt(float(long_run["closed_form_difference"]), 2),
        long_nan="none" if not a["any_nan"] else "some",
    )
    for solver in ("exact", "closed_form", "ivp"):
        facts[f"long_{solver}_last_drift"] = fmt(abs(float(long_run[f"drift_{solver}"].dropna("cycle").values[-1])), 2)
        facts[f"long_{solver}_max_error_time"] = fmt(float(long_run[f"error_time_{solver}"].max()), 2)
        measured[f"long_{solver}_wall"] = fmt(long_run_timings[f"{solver}_seconds"], 3)

    mu, mu21 = stability["multiplier"].values, stability["multiplier_eq21"].values
    left_b = stability["b"].values[(~succeeded(stability["outcome"].values)).any(axis=1)]
    facts.update(stab_shape=f"{stability.sizes['b']} x {stability.sizes['F']}",
                 stab_max_deviation=fmt(float(np.nanmax(np.abs(mu - mu21))), 2),
                 stab_left_b_min=fmt(float(left_b.min()), 4) if left_b.size else "none")
    t = stability_timings
    measured.update(stab_speedup=fmt(t["ensemble_speedup_per_trajectory"], 3),
                    stab_ensemble_per_trajectory=fmt(t["ensemble_seconds_per_trajectory"], 2),
                    stab_scalar_per_trajectory=fmt(t["scalar_seconds_per_trajectory"], 2))
    return facts, measured
