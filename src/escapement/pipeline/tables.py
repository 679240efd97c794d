"""The workflow's tables, read back with their digests and columns checked (:func:`escapement.io.netcdf.read_csv`)."""

from __future__ import annotations

from ..io.netcdf import read_csv
from ..verdict.rule import COLUMNS

__all__ = ["LIMIT_COLUMNS", "SPEED_COLUMNS", "STRESS_COLUMNS", "TIMING_COLUMNS", "WORK_PRECISION_COLUMNS",
           "read_claims", "read_timings"]

#: wall times, kept apart from the datasets (which are deterministic): one row per measurement
TIMING_COLUMNS = ["measurement", "seconds"]
WORK_PRECISION_COLUMNS = ["method", "setting", "wall_s", "repeats", "error_velocity", "error_time"]
#: the speed table: a ratio of two wall times (or of two peak memories) measured side by side
SPEED_COLUMNS = ["name", "n", "ratio", "time_s", "reference_s", "repeats", "bytes", "reference_bytes", "note"]
STRESS_COLUMNS = ["case", "regime", "outcome", "check", "passed", "detail"]
#: beside the verdict's table, the limits each axis claim judged: the run's, autoscaled as printed, per scored axis
LIMIT_COLUMNS = ["claim_id", "figure", "panel", "axis", "low", "high"]


def read_claims(path: str) -> list[dict]:
    """The verdict's table, written by the claims job (:mod:`escapement.pipeline.claims`)."""
    return read_csv(path, COLUMNS)


def read_timings(path: str) -> dict[str, float]:
    return {row["measurement"]: float(row["seconds"]) for row in read_csv(path, TIMING_COLUMNS)}
