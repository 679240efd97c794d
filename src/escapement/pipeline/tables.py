"""The workflow's tables, read back with their columns checked, and the merge of the stability map's chunks."""

from __future__ import annotations

from collections.abc import Sequence

from ..io.netcdf import read_csv, read_netcdf, write_netcdf
from .logs import logged
from .simulate import TIMING_COLUMNS, write_timings

__all__ = ["SPEED_COLUMNS", "STRESS_COLUMNS", "WORK_PRECISION_COLUMNS", "merge_stability", "read_stress",
           "read_timings", "read_work_precision"]

WORK_PRECISION_COLUMNS = ["method", "setting", "wall_s", "repeats", "error_velocity", "error_time"]
#: the speed table: a ratio of two wall times (or of two peak memories) measured side by side
SPEED_COLUMNS = ["name", "n", "ratio", "time_s", "reference_s", "repeats", "bytes", "reference_bytes", "note"]
STRESS_COLUMNS = ["case", "regime", "outcome", "check", "passed", "detail"]


def read_work_precision(path: str) -> list[dict]:
    return read_csv(path, WORK_PRECISION_COLUMNS)


def read_stress(path: str) -> list[dict]:
    return read_csv(path, STRESS_COLUMNS)


def read_timings(path: str) -> dict[str, float]:
    return {row["measurement"]: float(row["seconds"]) for row in read_csv(path, TIMING_COLUMNS)}


def merge_stability(paths: Sequence[str], output: str, timing_output: str, log: str) -> None:
    """Concatenate the chunks along b (the constant parameters stay 0-d, the first chunk's attributes kept);
    the timings are the medians over the chunks, with the ensemble's speed-up per trajectory."""
    import numpy as np
    import xarray as xr

    with logged(log, "merge_stability") as logger:
        chunks = [read_netcdf(p, ("b", "F", "multiplier", "outcome")) for p in paths]
        merged = xr.concat(chunks, dim="b", data_vars="minimal", combine_attrs="override")
        merged.attrs["chunks"] = len(chunks)
        timings = [read_timings(p.removesuffix(".nc") + "_timing.csv") for p in paths]
        ensemble = [t["ensemble_seconds_per_trajectory"] for t in timings]
        scalar = [t["scalar_seconds_per_trajectory"] for t in timings]
        merged_timings = {"ensemble_seconds_per_trajectory": float(np.median(ensemble)),
                          "scalar_seconds_per_trajectory": float(np.median(scalar)),
                          "ensemble_speedup_per_trajectory": float(np.median(np.divide(scalar, ensemble)))}
        logger.info("ensemble speed-up per trajectory (median over chunks): %.1f",
                    merged_timings["ensemble_speedup_per_trajectory"])
        write_netcdf(merged, output, history=f"escapement workflow, merged from {len(chunks)} chunks: {output}")
        write_timings(merged_timings, timing_output)
