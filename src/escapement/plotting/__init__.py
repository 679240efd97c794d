"""Figures of the replication: one style sheet, deterministic files.

The names are imported on first use (PEP 562), so that a job needing only
:mod:`escapement.plotting.autoscale` (the axis claims) does not load the figures' code.
"""

from importlib import import_module

#: each public name and the module that defines it
_EXPORTS = {
    "escapement_error": "paper_figures",
    "fig3": "paper_figures",
    "fig4": "paper_figures",
    "fig5": "paper_figures",
    "long_run": "paper_figures",
    "save_figure": "style",
    "stability_map": "paper_figures",
    "style": "style",
    "work_precision": "paper_figures",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module 'escapement.plotting' has no attribute {name!r}")
    value = getattr(import_module(f".{_EXPORTS[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
