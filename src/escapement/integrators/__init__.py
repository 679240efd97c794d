"""General-purpose integrators that check the exact solvers along an independent path: ``solve_ivp`` and CVODE,
50-digit arithmetic and fixed-step Runge-Kutta, each a stepper of one loop. The names are imported on first use, so
that a job that runs only the exact solver loads neither SciPy's integrators nor mpmath.
"""

from .._lazy import lazy_exports

#: each public name, solve_<module>, and the module that defines it
_EXPORTS = {f"solve_{module}": module for module in ("high_precision", "naive", "reference")}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
