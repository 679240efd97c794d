"""The rule that bounds what a figure draws, whatever the length of the run, applied just before it is saved
(:func:`escapement.plotting.save_figure`), which then says so on the figure: a line against increasing x of more
than 4 samples per column of 1/:data:`COLUMN_DPI` inch keeps each column's first, last, smallest and largest samples
(every extreme drawn); any other artist of more than :data:`VECTOR_LIMIT` vertices is drawn as a raster from every
vertex (Fig. 5's kind over 5,000 cycles: SVG 283 kB and PDF 117 kB, against 153 MB and 62 MB as vectors).
Hand-written because matplotlib's path simplification merges only nearly collinear segments: no noisy curve.
"""

from __future__ import annotations

import matplotlib
import numpy as np
from matplotlib.collections import Collection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from .captions import CHANGES_FONTSIZE, thinning

__all__ = ["COLUMN_DPI", "PER_COLUMN", "VECTOR_LIMIT", "bound", "decimate"]

#: the columns a thinned line is binned by, per inch of its axes' width
COLUMN_DPI = 600
#: the samples a column keeps: its first, last, smallest and largest
PER_COLUMN = 4
#: the vertices above which an artist is drawn as a raster: above every thinned line of axes up to 12.5 in wide
#: (4 x 600 x 12.5) and above the paper's phase diagrams (at most 24,626 samples a panel, its impacts' breaks too)
VECTOR_LIMIT = 30_000


def decimate(column: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The indices of the samples kept, in order: of each run of consecutive equal ``column`` values, its first
    and last samples and the first of its smallest and of its largest ``y`` (NaN ignored); every NaN ``y`` kept."""
    column, y = np.asarray(column), np.asarray(y, dtype=float)
    start = np.flatnonzero(np.concatenate(([True], column[1:] != column[:-1])))
    length = np.diff(np.append(start, column.size))
    kept = [start, start + length - 1, np.flatnonzero(np.isnan(y))]
    for extreme in (np.fmin, np.fmax):
        at = np.flatnonzero(y == np.repeat(extreme.reduceat(y, start), length))
        kept.append(at[np.diff(np.searchsorted(start, at, side="right"), prepend=0) != 0])  # the first of its run
    return np.unique(np.concatenate(kept))


def _vertices(artist) -> tuple[int, int]:
    """The vertices ``artist`` draws, and its weight against :data:`VECTOR_LIMIT`: a path of a collection, an SVG
    element of its own (150 bytes a segment of ``vlines``, measured, against 22 a vertex of a line), weighs 6 more."""
    if isinstance(artist, Collection):
        n = sum(len(p.vertices) for p in artist.get_paths())
        return n, n + 6 * len(artist.get_paths())
    n = len(artist.get_xdata()) if isinstance(artist, Line2D) else len(artist.get_path().vertices)
    return n, n


def _increasing(artist) -> bool:
    """Whether ``artist`` is a line against increasing x (NaN, a break, aside)."""
    if not isinstance(artist, Line2D):
        return False
    x = np.asarray(artist.get_xdata(), dtype=float)
    return bool(np.all(np.diff(x[np.isfinite(x)]) >= 0))


def _thin(ax, line: Line2D) -> int:
    """Thin ``line`` by the columns of its axes, if it has more than 4 samples a column; the samples it keeps."""
    box = ax.get_window_extent()
    columns = int(np.ceil(box.width / ax.figure.dpi * COLUMN_DPI))
    x, y = np.asarray(line.get_xdata(), dtype=float), np.asarray(line.get_ydata(), dtype=float)
    if x.size <= PER_COLUMN * columns:
        return x.size
    at = (ax.get_xaxis_transform().transform(np.column_stack([x, np.zeros_like(x)]))[:, 0] - box.x0) / box.width
    # a sample outside the axes joins the column beyond their edge, one at an undefined x (a break) a run of its own
    index = decimate(np.where(np.isfinite(at), np.clip(at * columns // 1, -1, columns), -2), y)
    line.set_data(x[index], y[index])
    return index.size


def bound(fig: Figure) -> str | None:
    """Thin and rasterize the artists of ``fig`` by the module's rule and say so in the title of the legend below its
    axes; the words, None if nothing was. Call within the style: a raster is drawn at its ``savefig.dpi``."""
    widest = PER_COLUMN * COLUMN_DPI * fig.get_figwidth()  # a line of fewer samples has at most 4 a column
    many = []
    for ax in fig.axes:
        for artist in (*ax.lines, *ax.collections, *ax.patches):
            n, weight = (0, 0) if artist.get_rasterized() else _vertices(artist)
            if (increasing := n > widest and _increasing(artist)) or weight > VECTOR_LIMIT:
                many.append((ax, artist, n, weight, increasing))
    if many:
        fig.draw_without_rendering()  # the axes' widths, once laid out
    samples = kept = rastered = 0
    for ax, artist, n, weight, increasing in many:
        if increasing and (drawn := _thin(ax, artist)) < n:
            samples, kept, n, weight = samples + n, kept + drawn, drawn, drawn
        if weight > VECTOR_LIMIT:
            artist.set_rasterized(True)
            rastered += n
    note = thinning(fig, samples, kept, rastered, COLUMN_DPI, matplotlib.rcParams["savefig.dpi"])
    if note:
        legend = fig.legends[-1] if fig.legends else fig.legend(handles=[], loc="outside lower center")
        title = legend.get_title().get_text()
        legend.set_title(f"{title}\n{note}" if title else note, prop={"size": CHANGES_FONTSIZE})
    return note
