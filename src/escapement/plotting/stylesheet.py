"""How every figure looks and is saved: the style sheet, the colours by role, the title, one legend below the axes
(text where the constrained layout puts it, outside the axes), and files byte-identical from run to run.
"""

from __future__ import annotations

import contextlib
import os
from importlib.resources import as_file, files

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..io.netcdf import replaced  # noqa: E402
from .thinning import bound  # noqa: E402

__all__ = ["ACCENT", "GUIDE", "INK", "MUTED", "NO_CYCLE", "POWER_LABELSIZE", "SERIES", "WIDTH", "legend_below",
           "power_ticks", "save_figure", "style", "suptitle"]

#: the width every figure is drawn at (in): the article's text column, A4's 21 cm less margins of 5.4 and 1.8 cm
WIDTH = (21.0 - 5.4 - 1.8) / 2.54
#: the size of a log axis' tick labels (pt): matplotlib's mathtext sets the exponent of 10\u207f at 0.7 of it, 7 pt
POWER_LABELSIZE = 10

#: colours of the figures, named by role
INK = "#1f4e79"
ACCENT = "#c0392b"
MUTED = "#b8b8b8"
GUIDE = "#666666"
#: fill of a map's cells where no cycle exists, and of the rounding band: a grey in neither viridis nor magma
NO_CYCLE = "#dcdcdc"
#: colours of up to four series of equal standing
SERIES = (INK, ACCENT, "#d68910", GUIDE)


@contextlib.contextmanager
def style():
    """Apply the project's style sheet inside the ``with`` block."""
    with as_file(files(__package__) / "escapement.mplstyle") as sheet, plt.style.context(str(sheet)):
        yield


def suptitle(fig, title: str) -> None:
    """The figure's title: ``title``, one or two lines saying what the figure shows."""
    if not title.strip() or title.count("\n") > 1:
        raise ValueError(f"title = {title!r} must be one or two lines of text")
    fig.suptitle(title, fontsize=8.5)


def power_ticks(fig) -> None:
    """The tick labels of every log axis of ``fig`` at :data:`POWER_LABELSIZE`: no exponent prints under 7 pt."""
    for axis in (axis for ax in fig.axes for axis in (ax.xaxis, ax.yaxis) if axis.get_scale() == "log"):
        axis.set_tick_params(labelsize=POWER_LABELSIZE)


def legend_below(fig, axes, ncols: int, **kwargs):
    """One legend below the axes: every labelled artist of ``axes``, each label once, in the order drawn."""
    entries: dict[str, object] = {}
    for ax in np.ravel(axes):
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    return fig.legend(list(entries.values()), list(entries), loc="outside lower center", ncols=ncols, **kwargs)


def save_figure(fig, png: str | os.PathLike, pdf: str | os.PathLike, svg: str | os.PathLike) -> None:
    """Save as PNG, PDF and SVG, thinned first (:mod:`escapement.plotting.thinning`), with no software stamp or date
    and the SVG's ids salted alike, so that the same figure gives the same bytes on every run."""
    with style(), matplotlib.rc_context({"svg.hashsalt": "escapement"}):
        bound(fig)
        for path, kind, stamps in ((png, "png", ("Software",)), (pdf, "pdf", ("Creator", "Producer", "CreationDate")),
                                   (svg, "svg", ("Creator", "Date"))):
            with replaced(path) as tmp:
                fig.savefig(tmp, format=kind, metadata=dict.fromkeys(stamps))
    plt.close(fig)
