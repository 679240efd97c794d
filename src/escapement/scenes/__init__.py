"""The scenes: each from its checked settings (:mod:`.settings`) to a CF dataset in one function, the layer
between the solvers, the paper and the studies below and the files and figures above.
"""

from .._lazy import lazy_exports

_EXPORTS = {"run_dataset": "cf"}
__all__ = ["run_dataset"]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
