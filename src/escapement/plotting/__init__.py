"""Figures of the replication: one style sheet, deterministic files."""

from .paper_figures import escapement_error, fig3, fig4, fig5, long_run, stability_map, work_precision
from .style import save_figure, style

__all__ = ["escapement_error", "fig3", "fig4", "fig5", "long_run", "save_figure", "stability_map", "style", "work_precision"]
