"""Input and output: CF-1.11 datasets from runs (:mod:`.dataset`, :func:`run_dataset` for one run),
the datasets of the workflow's scenes built from the experiments' results (:mod:`.scenes`,
:mod:`.studies`), netCDF files (:mod:`.netcdf`), atomic writes (:mod:`.atomic`) and provenance
(:mod:`.provenance`). This layer converts and writes; it runs no solver and imports nothing above
:mod:`escapement.solvers`.

``run_dataset`` is imported on first use (PEP 562), so that a job that only reads and writes files
does not load the solvers' result types.
"""

from .._lazy import lazy_exports
from .atomic import atomic_path, write_csv
from .netcdf import DatasetError, read_netcdf, write_netcdf

_EXPORTS = {"run_dataset": "dataset"}

__all__ = ["DatasetError", "atomic_path", "read_netcdf", "run_dataset", "write_csv", "write_netcdf"]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
