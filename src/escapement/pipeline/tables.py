"""The workflow's tables and merged files that no solver is needed for: the variables each
figure reads, the work-precision and stress tables, and the merge of the stability chunks."""

from __future__ import annotations

import csv
from collections.abc import Sequence

from ..io.atomic import write_csv
from ..io.netcdf import DatasetError, read_netcdf, write_netcdf
from ..io.provenance import provenance_attributes
from .logs import logged

__all__ = [
    "CYCLE_VARIABLES",
    "ESCAPEMENT_ERROR_VARIABLES",
    "PHASE_VARIABLES",
    "SHOCK_VARIABLES",
    "SPEED_COLUMNS",
    "STRESS_COLUMNS",
    "TIMING_COLUMNS",
    "WORK_PRECISION_COLUMNS",
    "merge_stability",
    "read_stress",
    "read_timings",
    "write_timings",
    "read_work_precision",
]

CYCLE_VARIABLES = ("cycle", "velocity_before_impact", "period", "M", "K", "F", "x0")
#: what the escapement-error figure reads
ESCAPEMENT_ERROR_VARIABLES = ("amplitude", "rate", "rate_impacts", "rate_zones", "zone_name", "zone_a1", "zone_a2",
                              "max_period_difference", "M", "K", "b")
SHOCK_VARIABLES = ("t", "velocity", "acceleration", "impact_time", "impulse", "energy_dissipated", "event_time",
                   "velocity_window", "acceleration_window", "F", "K", "x0")
PHASE_VARIABLES = ("t", "displacement", "velocity", "impact_time", "impact_position", "velocity_after", "K")
WORK_PRECISION_COLUMNS = ["method", "setting", "wall_s", "repeats", "error_velocity", "error_time"]
#: the speed table: a ratio of two wall times (or of two peak memories) measured side by side
SPEED_COLUMNS = ["name", "n", "ratio", "time_s", "reference_s", "repeats", "bytes", "reference_bytes", "note"]
STRESS_COLUMNS = ["case", "regime", "outcome", "check", "passed", "detail"]
#: wall times, kept apart from the datasets (which are deterministic): one row per measurement
TIMING_COLUMNS = ["measurement", "seconds"]


def _read_csv(path: str, columns: list[str], what: str) -> list[dict]:
    try:
        with open(path, newline="") as handle:
            rows = list(csv.DictReader(handle))
    except OSError as err:
        raise DatasetError(f"{path}: cannot be read ({err})") from err
    if not rows or list(rows[0]) != columns:
        raise DatasetError(f"{path}: not a {what} with the columns {', '.join(columns)}")
    return rows


def read_work_precision(path: str) -> list[dict]:
    return _read_csv(path, WORK_PRECISION_COLUMNS, "work-precision table")


def read_stress(path: str) -> list[dict]:
    return _read_csv(path, STRESS_COLUMNS, "stress summary")


def read_timings(path: str) -> dict[str, float]:
    return {row["measurement"]: float(row["seconds"]) for row in _read_csv(path, TIMING_COLUMNS, "timing table")}


def write_timings(timings: dict[str, float], path: str) -> None:
    write_csv([{"measurement": k, "seconds": repr(float(v))} for k, v in timings.items()], TIMING_COLUMNS, path)


def merge_stability(
    paths: Sequence[str], timing_paths: Sequence[str], output: str, timing_output: str, log: str
) -> None:
    """Concatenate the chunks along b; the timings are the medians over the chunks, with the
    ensemble's speed-up per trajectory."""
    import numpy as np
    import xarray as xr

    with logged(log, "merge_stability") as logger:
        chunks = [read_netcdf(p, ("b", "F", "multiplier", "outcome")) for p in paths]
        # the constant parameters (0-d, equal in every chunk) stay 0-d; the first chunk's attributes...
        merged = xr.concat(chunks, dim="b", data_vars="minimal", combine_attrs="override")
        merged.attrs.update(  # ...with the provenance of this merge
            provenance_attributes(f"merged from {len(chunks)} chunks by escapement"), chunks=len(chunks),
        )
        timings = [read_timings(p) for p in timing_paths]
        ensemble = [t["ensemble_seconds_per_trajectory"] for t in timings]
        scalar = [t["scalar_seconds_per_trajectory"] for t in timings]
        merged_timings = {
            "ensemble_seconds_per_trajectory": float(np.median(ensemble)),
            "scalar_seconds_per_trajectory": float(np.median(scalar)),
            "ensemble_speedup_per_trajectory": float(np.median(np.divide(scalar, ensemble))),
        }
        logger.info("ensemble speed-up per trajectory (median over chunks): %.1f",
                    merged_timings["ensemble_speedup_per_trajectory"])
        write_netcdf(merged, output)
        write_timings(merged_timings, timing_output)
