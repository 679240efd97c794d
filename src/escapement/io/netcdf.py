"""Writing and reading the netCDF files: compressed, atomic, with clear errors."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from .atomic import atomic_path

__all__ = ["DatasetError", "write_netcdf", "read_netcdf"]


class DatasetError(RuntimeError):
    """A netCDF file is missing, truncated, corrupted or lacks what it should hold."""


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically: to a temporary file beside it, then renamed.

    Data variables are compressed (zlib level 4); coordinates get no ``_FillValue``.
    """
    encoding = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars}
    encoding.update({name: {"_FillValue": None} for name in ds.coords})
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
    return Path(path)


def read_netcdf(path: str | os.PathLike, required: tuple[str, ...] = ()) -> xr.Dataset:
    """Load a dataset fully into memory; raise :class:`DatasetError` naming the file if it
    cannot be read or lacks a ``required`` variable."""
    path = Path(path)
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            loaded = ds.load()
    except FileNotFoundError as err:
        raise DatasetError(f"{path}: no such netCDF file") from err
    except Exception as err:  # netCDF4 raises OSError or RuntimeError for damaged files
        raise DatasetError(f"{path}: not a readable netCDF file ({type(err).__name__}: {err})") from err
    missing = [name for name in required if name not in loaded.variables]
    if missing:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")
    return loaded
