"""Writing and reading the netCDF files: compressed, checksummed, atomic, with clear errors."""

from __future__ import annotations

import os
from pathlib import Path

import netCDF4
import xarray as xr

from .atomic import atomic_path, write_failure

__all__ = ["DatasetError", "write_netcdf", "read_netcdf"]


class DatasetError(RuntimeError):
    """A netCDF file is missing, truncated, corrupted or lacks what it should hold."""


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically: to a temporary file beside it, then renamed.

    Data variables are compressed (zlib level 4); coordinates get no ``_FillValue``. Every variable
    carries a Fletcher-32 checksum, which :func:`read_netcdf` checks. HDF5 can neither chunk nor
    filter a variable with no dimension: a 0-d variable is stored without one.

    A failure of the file system raises :class:`~escapement.io.atomic.WriteError` naming ``path`` and
    the cause (no space left on device, permission denied, read-only file system), where netCDF
    reports only ``NetCDF: HDF error``; any other failure of netCDF, :class:`DatasetError`.
    """
    encoding = {name: {"zlib": True, "complevel": 4, "fletcher32": True} for name in ds.data_vars}
    encoding.update({name: {"_FillValue": None, "fletcher32": True} for name in ds.coords})
    with atomic_path(path) as tmp:
        try:
            ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
        except (OSError, RuntimeError) as err:  # what netCDF4 raises when the library fails
            # Found while the temporary still takes its space: a full disk shows no free byte.
            failure = write_failure(path, err, needed=ds.nbytes)
            if failure is not None:
                raise failure from err
            raise DatasetError(f"{path}: cannot write the netCDF file ({type(err).__name__}: {err})") from err
    return Path(path)


#: the filters of a variable that check its data on reading, and what their failure is called
_CHECKS = (("fletcher32", "Fletcher-32 checksum"), ("zlib", "decompression"))


def _damaged_variables(path: Path) -> str:
    """Which variables of ``path`` cannot be read, and which of their filters failed: a sentence to
    append to an error message, or nothing if that cannot be found."""
    try:
        nc = netCDF4.Dataset(path)
    except (OSError, RuntimeError):  # the file does not open: the first error says it
        return ""
    damaged = []
    with nc:
        for name, variable in nc.variables.items():  # one read of each variable of the file
            variable.set_auto_maskandscale(False)
            try:
                variable[...]
            except (OSError, RuntimeError):
                filters = variable.filters() or {}
                checks = [label for key, label in _CHECKS if filters.get(key)]
                damaged.append(f"{name} ({' or '.join(checks)} failed)" if checks else name)
    if not damaged:
        return ""
    return f"; the data of {', '.join(damaged)} is corrupted"


def read_netcdf(path: str | os.PathLike, required: tuple[str, ...] = ()) -> xr.Dataset:
    """Load a dataset fully into memory, checking the checksums; raise :class:`DatasetError` naming
    the file if it cannot be read, fails a checksum or lacks a ``required`` variable."""
    path = Path(path)
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            loaded = ds.load()
    except FileNotFoundError as err:
        raise DatasetError(f"{path}: no such netCDF file") from err
    except Exception as err:  # netCDF4 raises OSError or RuntimeError for damaged files
        detail = _damaged_variables(path)
        raise DatasetError(f"{path}: not a readable netCDF file ({type(err).__name__}: {err}){detail}") from err
    missing = [name for name in required if name not in loaded.variables]
    if missing:
        raise DatasetError(f"{path}: lacks the variable(s) {', '.join(missing)}")
    return loaded
