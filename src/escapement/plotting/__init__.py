"""Figures of the escapement model: the three kinds of scene figure (Poincaré map, shock detail, phase diagrams)
for the paper's parameters or a user's, and the project's own studies; one style sheet, deterministic files.

The names are imported on first use (PEP 562), so that a job needing only :mod:`escapement.plotting.autoscale`
(the axis claims) does not load the figures' code.
"""

from .._lazy import lazy_exports

_EXPORTS = {**dict.fromkeys(("escapement_error", "existence_map", "long_run", "stability_map", "work_precision"),
                            "study_figures"),
            **dict.fromkeys(("phase_diagrams", "poincare_map", "shock_detail"), "scene_figures"),
            "save_figure": "stylesheet", "style": "stylesheet"}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
