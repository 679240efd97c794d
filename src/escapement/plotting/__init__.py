"""Figures of the escapement model: the scene figures and the project's own studies, in one style, deterministic
files. The names are imported on first use (PEP 562): a job that needs only :mod:`.autoscale` loads no figure.
"""

from .._lazy import lazy_exports

_EXPORTS = {**dict.fromkeys(("escapement_error", "existence_map", "long_run", "stability_map", "work_precision"),
                            "study_figures"),
            **dict.fromkeys(("phase_diagrams", "poincare_map", "shock_detail"), "scene_figures"),
            "save_figure": "stylesheet", "style": "stylesheet"}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
