"""The verdict's table, ``results/claims.csv``: written by the claims job, read back by the documents'.
Imports no solver and no plotting: the job that writes the documents reads the table only."""

from __future__ import annotations

import csv
import os

from ..io.netcdf import write_csv
from ..paper.claims import COLUMNS

__all__ = ["read_claims_csv", "write_claims_csv"]


def write_claims_csv(rows: list[dict[str, str]], path: str | os.PathLike) -> None:
    """Write the table atomically, with exactly the columns of ``COLUMNS``."""
    write_csv(rows, COLUMNS, path)


def read_claims_csv(path: str | os.PathLike) -> list[dict[str, str]]:
    """Read the table back; a file with other columns is rejected, naming it."""
    with open(path, newline="") as handle:
        reader = csv.DictReader(handle)
        if reader.fieldnames != COLUMNS:
            raise ValueError(f"{path}: columns {reader.fieldnames} are not {COLUMNS}")
        return list(reader)
