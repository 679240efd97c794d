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

from importlib.metadata import PackageNotFoundError, version

from .model import EventKind, EventLog, ParameterError, Parameters, Status
from .solvers import (
    EnsembleSolution,
    Exit,
    Solution,
    solve_ensemble,
    solve_exact,
    solve_high_precision,
    solve_naive,
    solve_reference,
)

try:
    __version__ = version("escapement")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = [
    "EnsembleSolution",
    "EventKind",
    "EventLog",
    "Exit",
    "ParameterError",
    "Parameters",
    "Solution",
    "Status",
    "__version__",
    "solve_ensemble",
    "solve_exact",
    "solve_high_precision",
    "solve_naive",
    "solve_reference",
]
