"""Figures of the replication: one style sheet, deterministic files."""

from .figures import fig3, fig4, fig5
from .style import save_figure, style

__all__ = ["fig3", "fig4", "fig5", "save_figure", "style"]
