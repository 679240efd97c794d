"""Writing and reading the files: netCDF (compressed, checksummed, stamped with their provenance), CSV and
text, each written to a temporary file beside its target and renamed into place, so that a reader never
sees a partial file (Snakemake removes the outputs of a job that fails)."""

from __future__ import annotations

import csv
import os
import tempfile
from collections.abc import Iterable, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from .provenance import command_line, provenance_attributes

if TYPE_CHECKING:  # xarray is imported where a netCDF file is read or written: a CSV job does without it
    import xarray as xr

__all__ = ["DatasetError", "read_csv", "read_netcdf", "replaced", "write_csv", "write_netcdf", "write_text"]


class DatasetError(RuntimeError):
    """A file is missing, damaged, or lacks what it should hold; the message names it."""


@contextmanager
def replaced(path: str | os.PathLike):
    """A temporary path beside ``path`` (its folder made if missing), renamed to ``path`` when the block ends
    without an error (removed if it raises)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".partial")
    os.close(handle)
    try:
        yield Path(tmp)
        mask = os.umask(0)  # mkstemp makes a private file: give it the permissions a new file gets
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    finally:
        Path(tmp).unlink(missing_ok=True)


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike, history: str | None = None) -> Path:
    """Write ``ds`` to ``path`` with its provenance (``history``: what wrote it, by default this process's
    command line): data variables compressed (zlib level 4), every variable with a Fletcher-32 checksum that
    :func:`read_netcdf` checks, coordinates without ``_FillValue``."""
    ds = ds.copy()
    ds.attrs.update(provenance_attributes(history or command_line()))
    encoding = {name: {"zlib": True, "complevel": 4, "fletcher32": True} for name in ds.data_vars}
    encoding.update({name: {"_FillValue": None, "fletcher32": True} for name in ds.coords})
    with replaced(path) as tmp:
        try:
            ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
        except (OSError, RuntimeError) as err:  # what netCDF4 raises when the library fails
            raise DatasetError(f"{path}: cannot write the netCDF file ({type(err).__name__}: {err})") from err
    return Path(path)


def read_netcdf(path: str | os.PathLike, required: Iterable[str] = ()) -> xr.Dataset:
    """The dataset of ``path``, loaded into memory with its checksums checked; :class:`DatasetError` naming the
    file if it cannot be read or lacks a ``required`` variable."""
    import xarray as xr

    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            loaded = ds.load()
    except FileNotFoundError as err:
        raise DatasetError(f"{path}: no such netCDF file") from err
    except (OSError, RuntimeError, ValueError) as err:  # netCDF4 and xarray on a damaged file
        raise DatasetError(f"{path}: not a readable netCDF file ({type(err).__name__}: {err})") from err
    missing = [name for name in required if name not in loaded.variables]
    if missing:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")
    return loaded


def write_text(text: str, path: str | os.PathLike) -> None:
    with replaced(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def write_csv(rows: Iterable[Mapping], columns: list[str], path: str | os.PathLike) -> None:
    with replaced(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)


def read_csv(path: str | os.PathLike, columns: list[str]) -> list[dict[str, str]]:
    """The rows of ``path``, whose header must be ``columns``; :class:`DatasetError` naming the file if not."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            reader = csv.DictReader(handle)
            rows = list(reader)
    except OSError as err:
        raise DatasetError(f"{path}: cannot be read ({err})") from err
    if list(reader.fieldnames or ()) != columns:
        raise DatasetError(f"{path}: not a table with the columns {', '.join(columns)}")
    return rows
