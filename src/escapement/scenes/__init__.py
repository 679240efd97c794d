"""The scenes: each from its checked settings (:mod:`.settings`) to a CF dataset in one function, the layer
between the solvers, the paper and the studies below and the files and figures above.

* :mod:`.figures`: the paper's kinds of figure (Poincare map, shock detail, phase diagram);
* :mod:`.maps`: the grids (stability map, existence map, escapement error);
* :mod:`.runs`: the replication's own runs (the claims register's, the long run);
* :mod:`.cf`: the CF-1.11 / ACDD-1.3 parts every dataset is built of, and :func:`run_dataset` for one run.
"""

from .._lazy import lazy_exports

_EXPORTS = {"run_dataset": "cf"}
__all__ = ["run_dataset"]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
