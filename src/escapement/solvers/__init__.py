"""The exact solvers: one event loop over the model's automaton, its streams, the ensemble, the per-cycle closed
forms and the one result type. The names are imported on first use (PEP 562): a job that needs only the exact
solver does not load SciPy's integrators (about 0.7 s) or mpmath.
"""

from .._lazy import lazy_exports

#: each public name and the module that defines it
_EXPORTS = {
    "ArcTable": "result",
    "CycleChunks": "cycles",
    "CycleStream": "stream",
    "CycleTable": "result",
    "EnsembleSolution": "result",
    "Exit": "result",
    "Solution": "result",
    "StreamSummary": "stream",
    "iter_closed_form_cycles": "cycles",
    "iter_cycles": "stream",
    "solve_cycles": "cycles",
    "solve_ensemble": "ensemble",
    "solve_exact": "exact",
}

__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
