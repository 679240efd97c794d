"""Input and output: netCDF, CSV and text files written atomically with their digest and provenance, and read only
once checked whole. It imports nothing of the package but its version."""

from .._lazy import lazy_exports

_EXPORTS = {name: "netcdf" for name in ("DatasetError", "read_csv", "read_netcdf", "write_csv", "write_netcdf",
                                        "write_text")}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
