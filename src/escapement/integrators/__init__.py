"""General-purpose integrators that check the exact solvers along an independent path, each a stepper of one loop
(:mod:`.driver`): SciPy's ``solve_ivp`` and SUNDIALS CVODE (:mod:`.reference`), 50-digit arithmetic
(:mod:`.high_precision`) and fixed-step Runge-Kutta (:mod:`.naive`). The names are imported on first use
(PEP 562): a job that runs only the exact solver loads neither SciPy's integrators nor mpmath.
"""

from .._lazy import lazy_exports

#: each public name, solve_<module>, and the module that defines it
_EXPORTS = {f"solve_{module}": module for module in ("high_precision", "naive", "reference")}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
