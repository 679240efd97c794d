"""The solvers: one loop over the model's automaton, several integrators, one result type."""

from .ensemble import solve_ensemble
from .exact import solve_exact
from .high_precision import solve_high_precision
from .naive import solve_naive
from .reference import solve_reference
from .result import ArcTable, CycleTable, EnsembleSolution, Exit, Solution
from .stream import CycleStream, StreamSummary, iter_cycles

__all__ = [
    "ArcTable",
    "CycleStream",
    "CycleTable",
    "EnsembleSolution",
    "Exit",
    "Solution",
    "StreamSummary",
    "iter_cycles",
    "solve_ensemble",
    "solve_exact",
    "solve_high_precision",
    "solve_naive",
    "solve_reference",
]
