"""Input and output: netCDF, CSV and text files written atomically, each table and dataset with its digest, and
read only once checked whole, with one-line errors (:mod:`.netcdf`), stamped with their provenance
(:mod:`.provenance`). It imports nothing of the package but its version: the datasets it writes are made by
:mod:`escapement.scenes`."""

from .._lazy import lazy_exports

_EXPORTS = {name: "netcdf" for name in ("DatasetError", "read_csv", "read_netcdf", "write_csv", "write_netcdf",
                                        "write_text")}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
