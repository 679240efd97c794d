"""Input and output: CF-1.11 datasets from runs (:mod:`.dataset`), the scenes each figure needs
(:mod:`.scenes`, imported on its own: it runs the solvers), netCDF files (:mod:`.netcdf`),
atomic writes (:mod:`.atomic`) and provenance (:mod:`.provenance`)."""

from .atomic import atomic_path, write_csv
from .netcdf import DatasetError, read_netcdf, write_netcdf

__all__ = ["DatasetError", "atomic_path", "read_netcdf", "write_csv", "write_netcdf"]
