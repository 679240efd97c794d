"""Figures of the escapement model: the three kinds of scene figure (Poincaré map, shock detail, phase
diagrams) for the paper's parameters or a user's, and the project's own studies; one style sheet,
deterministic files.

The names are imported on first use (PEP 562), so that a job needing only
:mod:`escapement.plotting.autoscale` (the axis claims) does not load the figures' code.
"""

from .._lazy import lazy_exports

#: each public name and the module that defines it
_EXPORTS = {
    "escapement_error": "study_figures",
    "existence_map": "study_figures",
    "long_run": "study_figures",
    "phase_diagrams": "scene_figures",
    "poincare_map": "scene_figures",
    "save_figure": "style",
    "shock_detail": "scene_figures",
    "stability_map": "study_figures",
    "style": "style",
    "work_precision": "study_figures",
}

__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
