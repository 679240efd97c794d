"""Replication of J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in
escapement mechanism", Shock and Vibration 20 (2013) 1001-1010, DOI 10.3233/SAV-130800.

Layers, each importing only those before it (``tests/test_layers.py`` checks it): ``model``, ``solvers``,
``integrators``, ``paper``, ``studies``, ``scenes``, ``io`` (which imports only the version), ``plotting``, then
``pipeline`` and the command line ``cli`` (neither imported here); the README's Layout says what each holds.
"""

import importlib.metadata as _metadata

from ._lazy import lazy_exports

try:
    __version__ = _metadata.version("escapement")
except _metadata.PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

#: the public names of each layer, re-exported and imported on first use (PEP 562): a job imports only the layers
#: it uses; run_dataset is a run of any solver as a CF dataset (the solvers' layer holds no xarray)
_LAYERS = {"model": ("EventKind", "EventLog", "ParameterError", "Parameters", "Status"),
           "solvers": ("EnsembleSolution", "Exit", "Solution", "iter_cycles", "solve_ensemble", "solve_exact"),
           "integrators": ("solve_high_precision", "solve_naive", "solve_reference"),
           "scenes": ("run_dataset",)}
_EXPORTS = {name: layer for layer, names in _LAYERS.items() for name in names}

__all__ = ["__version__", *sorted(_EXPORTS)]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
