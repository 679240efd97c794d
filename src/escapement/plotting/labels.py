"""Labels placed where they cover no data, and legends outside the axes.

A label inside an axes (the impulse of an impact, the outcome of a run that ended early) is
placed once the layout is fixed (:func:`finish`), at the free spot nearest to what it labels,
found on a grid of the axes with everything already drawn marked on it (:class:`Occupancy`); a
label placed away from its point is joined to it by a thin leader. :func:`legend_below` puts
one legend for a whole figure under its axes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

from .style import GUIDE

__all__ = ["CELL", "LABEL_PAD", "LEADER_AFTER", "Label", "Occupancy", "finish", "legend_below"]

#: side of a cell of the grid on which labels are placed (pixels at the figure's dpi)
CELL = 2.0
#: free space kept around a label (points)
LABEL_PAD = 3.0
#: a label farther than this from its point (points) is joined to it by a leader
LEADER_AFTER = 6.0


def _along(xy: np.ndarray, step: float) -> np.ndarray:
    """The vertices of a polyline in display coordinates and points every ``step`` pixels between
    them; a NaN vertex breaks the line."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    a, b = xy[:-1], xy[1:]
    ok = np.isfinite(a).all(axis=1) & np.isfinite(b).all(axis=1)
    a, b = a[ok], b[ok]
    n = np.maximum(1, np.ceil(np.hypot(*(b - a).T) / step)).astype(int)
    s = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)  # 0, 1/k, ..., (k-1)/k per segment
    start = np.repeat(a, n, axis=0)
    return np.vstack([start + s[:, None] * (np.repeat(b, n, axis=0) - start), xy[np.isfinite(xy).all(axis=1)]])


def _text_extent(text: Text, renderer) -> Bbox:
    """The box of a text on the canvas with its frame, without an annotation's arrow."""
    if isinstance(text, Annotation):
        text.update_positions(renderer)  # where its offset puts it
    box = Text.get_window_extent(text, renderer)
    if text.get_bbox_patch() is not None:
        text.update_bbox_position_size(renderer)
        box = Bbox.union([box, text.get_bbox_patch().get_window_extent(renderer)])
    return box


class Occupancy:
    """The cells of an axes that something drawn already covers: lines, markers, segments, offsets,
    patches, arrows, texts and legends.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, with its layout fixed.
    renderer : matplotlib.backend_bases.RendererBase
        The renderer that measures texts and patches.

    Attributes
    ----------
    grid : numpy.ndarray of bool
        One cell of :data:`CELL` pixels each, rows along y from the bottom of the axes: True where covered.
    """

    def __init__(self, ax, renderer):
        self.ax, self.renderer = ax, renderer
        self.x0, self.y0, width, height = ax.bbox.bounds
        self.grid = np.zeros((max(1, int(height // CELL)), max(1, int(width // CELL))), dtype=bool)
        px_per_pt = ax.figure.dpi / 72
        for line in ax.lines:
            if not line.get_visible():
                continue
            xy = line.get_transform().transform(line.get_xydata())
            if line.get_linestyle() not in ("None", "", " "):
                self.points(_along(xy, CELL / 2))
            if line.get_marker() not in (None, "None", "", " "):  # the square around each marker
                r = line.get_markersize() / 2 * px_per_pt
                steps = np.linspace(-r, r, max(2, math.ceil(4 * r / CELL) + 1))
                square = np.stack(np.meshgrid(steps, steps), axis=-1).reshape(-1, 2)
                self.points((xy[:, None, :] + square[None, :, :]).reshape(-1, 2))
        for coll in ax.collections:
            if isinstance(coll, LineCollection):
                for seg in coll.get_segments():
                    self.points(_along(coll.get_transform().transform(seg), CELL / 2))
            elif isinstance(coll, PathCollection):
                self.points(coll.get_offset_transform().transform(coll.get_offsets()))
            else:
                self.box(*coll.get_window_extent(renderer).extents)
        for patch in ax.patches:
            self.box(*patch.get_window_extent(renderer).extents)
        for text in ax.texts:
            if text.get_text():
                self.box(*_text_extent(text, renderer).padded(LABEL_PAD * px_per_pt).extents)
            elif isinstance(text, Annotation) and text.arrow_patch is not None:
                self.box(*text.arrow_patch.get_window_extent(renderer).extents)
        if ax.get_legend() is not None:
            self.box(*ax.get_legend().get_window_extent(renderer).extents)

    def _cells(self, x, y):
        i = np.floor((np.asarray(x) - self.x0) / CELL).astype(int)
        return i, np.floor((np.asarray(y) - self.y0) / CELL).astype(int)

    def points(self, xy: np.ndarray) -> None:
        """Mark the cells under the display points ``xy`` (one row per point; NaN rows skipped)."""
        xy = xy[np.isfinite(xy).all(axis=1)]
        i, j = self._cells(xy[:, 0], xy[:, 1])
        ok = (i >= 0) & (i < self.grid.shape[1]) & (j >= 0) & (j < self.grid.shape[0])
        self.grid[j[ok], i[ok]] = True

    def box(self, x0: float, y0: float, x1: float, y1: float) -> None:
        """Mark the cells under the display box from ``(x0, y0)`` to ``(x1, y1)``."""
        if not np.all(np.isfinite([x0, y0, x1, y1])):
            return
        (i0, i1), (j0, j1) = self._cells([x0, x1], [y0, y1])
        i0, j0 = max(i0, 0), max(j0, 0)
        self.grid[j0 : max(j1 + 1, 0), i0 : max(i1 + 1, 0)] = True

    def spot(self, width: float, height: float, anchor: tuple[float, float]) -> tuple[float, float, bool]:
        """Where a box of ``width`` x ``height`` pixels covers nothing, nearest to ``anchor``.

        Parameters
        ----------
        width, height : float
            The box's size (pixels).
        anchor : tuple of float
            The display point the box should be near.

        Returns
        -------
        tuple
            The box's centre (display x, y) and True; if no box is free, the least covered one's
            centre and False.
        """
        ny, nx = self.grid.shape
        bw, bh = min(nx, math.ceil(width / CELL)), min(ny, math.ceil(height / CELL))
        summed = np.zeros((ny + 1, nx + 1), dtype=np.int64)
        summed[1:, 1:] = self.grid.cumsum(axis=0).cumsum(axis=1)
        covered = summed[bh:, bw:] - summed[:-bh, bw:] - summed[bh:, :-bw] + summed[:-bh, :-bw]
        j, i = np.mgrid[0 : covered.shape[0], 0 : covered.shape[1]]
        cx, cy = self.x0 + (i + bw / 2) * CELL, self.y0 + (j + bh / 2) * CELL
        distance = np.hypot(cx - anchor[0], cy - anchor[1])
        best = np.lexsort((distance.ravel(), covered.ravel()))[0]
        fits = bw * CELL >= width and bh * CELL >= height
        return float(cx.ravel()[best]), float(cy.ravel()[best]), bool(fits and covered.ravel()[best] == 0)


@dataclass
class Label:
    """A text to place in an axes near the point it labels.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to place it in.
    text : str
        The label.
    xy : tuple of float
        The point it labels, in ``xycoords``.
    xycoords : {"data", "axes fraction"}
        The coordinates of ``xy``.
    style : dict
        Text properties (font size, colour, frame).
    leader : bool
        Join the label to its point by a thin line when it is placed away from it.
    """

    ax: object
    text: str
    xy: tuple[float, float]
    xycoords: str = "data"
    style: dict = field(default_factory=dict)
    leader: bool = True


def _make_room_below(ax, height: float) -> bool:
    """Lower the bottom of a linear y axis so that a band of ``height`` pixels under the data is free."""
    total = ax.bbox.height
    if ax.get_yscale() != "linear" or not 0 < height < total / 2:
        return False
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo - height * (hi - lo) / (total - height), hi)
    return True


def _size(label: Label, renderer) -> tuple[float, float, float, float]:
    """The text's width and height on the canvas, and with the free space around it (pixels)."""
    ax = label.ax
    probe = ax.text(0.5, 0.5, label.text, transform=ax.transAxes, ha="center", va="center", **label.style)
    box = _text_extent(probe, renderer)
    probe.remove()
    pad = 2 * LABEL_PAD * ax.figure.dpi / 72
    return box.width, box.height, box.width + pad, box.height + pad


def _anchor(label: Label) -> np.ndarray:
    """The point a label labels, on the canvas."""
    return {"data": label.ax.transData, "axes fraction": label.ax.transAxes}[label.xycoords].transform(label.xy)


def _place(label: Label, renderer) -> Annotation:
    """Draw ``label`` at the free spot nearest to its point."""
    ax, fig = label.ax, label.ax.figure
    px_per_pt = fig.dpi / 72
    w, h, width, height = _size(label, renderer)
    anchor = _anchor(label)
    cx, cy, _ = Occupancy(ax, renderer).spot(width, height, anchor)
    gap = math.hypot(max(abs(cx - anchor[0]) - w / 2, 0), max(abs(cy - anchor[1]) - h / 2, 0))
    arrow = {"arrowstyle": "-", "color": label.style.get("color", GUIDE), "lw": 0.6, "shrinkA": 1, "shrinkB": 2}
    placed = ax.annotate(
        label.text, label.xy, xycoords=label.xycoords,
        xytext=((cx - anchor[0]) / px_per_pt, (cy - anchor[1]) / px_per_pt), textcoords="offset points",
        ha="center", va="center", annotation_clip=False,
        arrowprops=arrow if label.leader and gap > LEADER_AFTER * px_per_pt else None, **label.style,
    )
    placed.set_in_layout(False)
    return placed


def finish(fig, labels: list[Label]) -> None:
    """Fix the layout (legends outside the axes, titles, colour bars), then place the labels in it.

    A label with no free spot in its axes gets room under the data (the bottom of a linear y axis
    lowered), and the layout is done again for the new tick labels before any label is placed.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, with everything but the labels drawn.
    labels : list of Label
        The labels, placed in this order (each sees those placed before it).
    """
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    moved = False
    for label in labels:
        _, _, width, height = _size(label, renderer)
        if not Occupancy(label.ax, renderer).spot(width, height, _anchor(label))[2]:
            moved |= _make_room_below(label.ax, 1.25 * height + CELL)
    if moved:
        fig.draw_without_rendering()
    fig.set_layout_engine("none")
    for label in labels:
        _place(label, renderer)


def legend_below(fig, axes, ncols: int, order: tuple[str, ...] = (), **kwargs):
    """One legend for the whole figure, below its axes.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    axes : matplotlib.axes.Axes or array of them
        The axes whose labelled artists the legend lists, each label once.
    ncols : int
        The legend's columns.
    order : tuple of str
        Labels to list first, in this order; the others follow as they come.
    **kwargs
        Passed to :meth:`matplotlib.figure.Figure.legend`.

    Returns
    -------
    matplotlib.legend.Legend
        The legend.
    """
    entries: dict[str, object] = {}
    for ax in np.ravel(axes):
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    labels = [k for k in order if k in entries] + [k for k in entries if k not in order]
    return fig.legend([entries[k] for k in labels], labels, loc="outside lower center", ncols=ncols, **kwargs)
