"""General-purpose integrators that check the exact solvers: numerical integration of the same automaton
by SciPy's ``solve_ivp`` and SUNDIALS CVODE (:mod:`.reference`), in 50-digit arithmetic (:mod:`.high_precision`)
and by fixed-step Runge-Kutta (:mod:`.naive`), each a stepper of the one integrators' loop (:mod:`.driver`).
They share the model, the outcomes and the result type with :mod:`escapement.solvers`, none of its closed
forms of the arcs but what the 50-digit stepper writes out on its own.

The names are imported on first use (PEP 562): a job that runs only the exact solver loads neither
SciPy's integrators nor mpmath.
"""

from .._lazy import lazy_exports

#: each public name and the module that defines it
_EXPORTS = {
    "solve_high_precision": "high_precision",
    "solve_naive": "naive",
    "solve_reference": "reference",
}

__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
