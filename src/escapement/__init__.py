"""Replication of J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in
escapement mechanism", Shock and Vibration 20 (2013) 1001-1010, DOI 10.3233/SAV-130800.

Layers, each importing only those above it in this list:

* :mod:`escapement.model`: parameters, the hybrid automaton, closed-form kinematics, outcomes;
* :mod:`escapement.solvers`: the solver loop, its integrators and the one result type;
* :mod:`escapement.paper` and :mod:`escapement.studies`: the paper's equations (as printed and
  corrected), the Poincare measurement and the claims; the benchmark, long run, stress cases;
* :mod:`escapement.io`: CF datasets, netCDF files, atomic writes, provenance;
* :mod:`escapement.plotting`: the figures;
* :mod:`escapement.pipeline`: what the workflow's rules call, and :mod:`escapement.cli`, the
  command line ``python -m escapement solve`` (neither is imported here).
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("escapement")
except PackageNotFoundError:  # running from a source tree that is not installed
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
    "solve_high_precision": "solvers",
    "solve_naive": "solvers",
    "solve_reference": "solvers",
}

__all__ = ["__version__", *sorted(_EXPORTS)]


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module 'escapement' has no attribute {name!r}")
    value = getattr(import_module(f".{_EXPORTS[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
