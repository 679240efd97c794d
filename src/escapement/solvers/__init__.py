"""The solvers: one loop over the model's automaton, several integrators, one result type.

The names are imported on first use (PEP 562): a job that needs only the exact solver does not
load SciPy's integrators (the reference solver's ``solve_ivp``, about 0.7 s) or mpmath.
"""

from importlib import import_module

#: each public name and the module that defines it
_EXPORTS = {
    "ArcTable": "result",
    "CycleStream": "stream",
    "CycleTable": "result",
    "EnsembleSolution": "result",
    "Exit": "result",
    "Solution": "result",
    "StreamSummary": "stream",
    "iter_cycles": "stream",
    "solve_ensemble": "ensemble",
    "solve_exact": "exact",
    "solve_high_precision": "high_precision",
    "solve_naive": "naive",
    "solve_reference": "reference",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module 'escapement.solvers' has no attribute {name!r}")
    value = getattr(import_module(f".{_EXPORTS[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
