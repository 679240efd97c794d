"""Input and output: CF-1.11 datasets from runs (:mod:`.dataset`, :func:`run_dataset` for one run),
the datasets of the workflow's scenes built from the experiments' results (:mod:`.scenes`,
:mod:`.studies`), netCDF files (:mod:`.netcdf`), atomic writes (:mod:`.atomic`) and provenance
(:mod:`.provenance`). This layer converts and writes; it runs no solver and imports nothing above
:mod:`escapement.solvers`.

``run_dataset`` and the netCDF functions are imported on first use (PEP 562): a job that writes only
CSV or copies files (the work-precision table, ``publish``, Snakemake's own process) loads neither the
solvers' result types nor xarray and pandas (about 0.3 s of CPU time a process).
"""

from .._lazy import lazy_exports
from .atomic import atomic_path, write_csv

_EXPORTS = {"run_dataset": "dataset", "DatasetError": "netcdf", "read_netcdf": "netcdf", "write_netcdf": "netcdf"}

__all__ = ["DatasetError", "atomic_path", "read_netcdf", "run_dataset", "write_csv", "write_netcdf"]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
