"""Replication of J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in
escapement mechanism", Shock and Vibration 20 (2013) 1001-1010, DOI 10.3233/SAV-130800.

Layers, each importing only those above it in this list (``tests/test_layers.py`` checks every
import of the source):

* :mod:`escapement.model`: parameters, the hybrid automaton, closed-form kinematics, outcomes;
* :mod:`escapement.solvers`: the exact event loop, its streams, the ensemble, the per-cycle closed forms and
  the one result type;
* :mod:`escapement.integrators`: the general-purpose integrators that check them (SciPy, CVODE, mpmath, RK4);
* :mod:`escapement.paper`, then :mod:`escapement.studies`: the paper's equations (as printed and
  corrected), the Poincare measurement and the claims; the benchmark, long run, stress cases;
* :mod:`escapement.scenes`: each scene from its checked settings to its CF dataset, in one function;
* :mod:`escapement.io`: netCDF, CSV and text files written atomically, with their provenance (it imports
  nothing of the package but its version);
* :mod:`escapement.plotting`: the figures;
* :mod:`escapement.pipeline`: what the workflow's rules call, and :mod:`escapement.cli`, the
  command line ``escapement solve`` or ``python -m escapement solve`` (neither is imported here).
"""

import importlib.metadata as _metadata

from ._lazy import lazy_exports

try:
    __version__ = _metadata.version("escapement")
except _metadata.PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

#: the public names, each re-exported from the layer that defines it. They are imported on first
#: use (PEP 562), so that ``import escapement.io`` or a plotting job does not load the solvers and
#: SciPy: each of the workflow's jobs imports only the layers it uses.
_EXPORTS = {
    "EventKind": "model",
    "EventLog": "model",
    "ParameterError": "model",
    "Parameters": "model",
    "Status": "model",
    "EnsembleSolution": "solvers",
    "Exit": "solvers",
    "Solution": "solvers",
    "iter_cycles": "solvers",
    "solve_ensemble": "solvers",
    "solve_exact": "solvers",
    "solve_high_precision": "integrators",
    "solve_naive": "integrators",
    "solve_reference": "integrators",
    "run_dataset": "scenes",  # a run of any solver as a CF dataset (the solvers' layer holds no xarray)
}

__all__ = ["__version__", *sorted(_EXPORTS)]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
