"""The paper's Figs. 3-5 and the project's own figures, drawn from the netCDF datasets (never from the solver).

Each figure names the paper's figure it reproduces (the dataset's ``title``) and states the readings
it assumes where the paper is silent: the dataset's ``reading`` attribute if it has one, otherwise a
sentence composed from its parameters (F, K, x0, v0) and the definitions of its variables.

No label covers data. Legends sit outside the axes, below them; a label inside an axes (the impulse
of an impact, the outcome of a run that ended early) is placed once the layout is fixed, at the free
spot nearest to what it labels, found on a grid of the axes with everything already drawn marked on
it (:class:`_Occupancy`); a label placed away from its point is joined to it by a thin leader.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.patches import Patch, PathPatch
from matplotlib.path import Path
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

from ..model.quantities import INITIAL_STATE, PARAMETERS
from .style import ACCENT, GUIDE, INK, MUTED, NO_CYCLE, SERIES, style

__all__ = ["escapement_error", "fig3", "fig4", "fig5", "long_run", "stability_map", "work_precision"]


def _broken(t: np.ndarray, y: np.ndarray, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Insert NaN at each break time, so that a line is not drawn across a jump."""
    idx = np.searchsorted(t, breaks)
    return np.insert(t.astype(float), idx, np.nan), np.insert(y.astype(float), idx, np.nan)


def _value(name: str, value: float) -> str:
    """``F = 0.5 N``: the quantity's symbol, the value and its units, from the quantities table (joined
    by no-break spaces, so that a wrapped line never splits a quantity)."""
    q = PARAMETERS[name] if name in PARAMETERS else INITIAL_STATE[name]
    unit = "" if q.units == "1" else f"\u00a0{q.unit_label}"  # a dimensionless quantity has no unit to show
    return f"{q.symbol}\u00a0=\u00a0{_signed(value, 'g')}{unit}"


def _signed(value: float, spec: str) -> str:
    """``value`` formatted by ``spec``, with the minus sign of the axes' tick labels."""
    return format(value, spec).replace("-", "\u2212")


def _v0(ds: xr.Dataset) -> float:
    """The initial velocity; a dataset without one was released from rest."""
    return float(ds["v0"]) if "v0" in ds else 0.0


def _release(ds: xr.Dataset) -> str:
    """``released from rest at x(0) = 3 m``, or with the initial velocity if it is not zero."""
    x0 = _value("x0", float(ds["x0"]))
    return f"released from rest at {x0}" if _v0(ds) == 0 else f"released at {x0} with {_value('v0', _v0(ds))}"


def _reading(ds: xr.Dataset, composed: str) -> str:
    """The readings a figure assumes where the paper is silent: the dataset's own sentence if it has
    one (global attribute ``reading``), else ``composed`` from its variables."""
    return str(ds.attrs.get("reading") or composed)


def _source(ds: xr.Dataset, figure: str) -> str:
    """The paper's figure a dataset reproduces: its ``title``, which names it."""
    return str(ds.attrs.get("title") or f"Mao, Fu & Li (2013), {figure}")


def _wrap(text: str, width: int) -> str:
    """``text`` in lines of at most ``width`` characters."""
    return "\n".join(textwrap.wrap(text, width, break_on_hyphens=False))


def natural_period(ds: xr.Dataset) -> float:
    """2 pi / omega with omega = sqrt(K/M), from the dataset's own K and M (s)."""
    return 2 * math.pi / math.sqrt(float(ds["K"]) / float(ds["M"]))


# ---- labels placed where they cover nothing

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


class _Occupancy:
    """The cells of an axes that something drawn already covers: lines, markers, segments, offsets,
    patches, arrows, texts and legends."""

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
        xy = xy[np.isfinite(xy).all(axis=1)]
        i, j = self._cells(xy[:, 0], xy[:, 1])
        ok = (i >= 0) & (i < self.grid.shape[1]) & (j >= 0) & (j < self.grid.shape[0])
        self.grid[j[ok], i[ok]] = True

    def box(self, x0: float, y0: float, x1: float, y1: float) -> None:
        if not np.all(np.isfinite([x0, y0, x1, y1])):
            return
        (i0, i1), (j0, j1) = self._cells([x0, x1], [y0, y1])
        i0, j0 = max(i0, 0), max(j0, 0)
        self.grid[j0 : max(j1 + 1, 0), i0 : max(i1 + 1, 0)] = True

    def spot(self, width: float, height: float, anchor: tuple[float, float]) -> tuple[float, float, bool]:
        """The centre (display) of the free box of ``width`` x ``height`` pixels nearest to ``anchor``,
        and True; if no box is free, the least covered one, and False."""
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
class _Label:
    """A text to place in ``ax`` near ``xy`` (in ``xycoords``), drawn with ``style``; joined to ``xy`` by
    a leader if placed away from it (``leader``)."""

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


def _size(label: _Label, renderer) -> tuple[float, float, float, float]:
    """The text's width and height on the canvas, and with the free space around it (pixels)."""
    ax = label.ax
    probe = ax.text(0.5, 0.5, label.text, transform=ax.transAxes, ha="center", va="center", **label.style)
    box = _text_extent(probe, renderer)
    probe.remove()
    pad = 2 * LABEL_PAD * ax.figure.dpi / 72
    return box.width, box.height, box.width + pad, box.height + pad


def _anchor(label: _Label) -> np.ndarray:
    """The point a label labels, on the canvas."""
    return {"data": label.ax.transData, "axes fraction": label.ax.transAxes}[label.xycoords].transform(label.xy)


def _place(label: _Label, renderer) -> Annotation:
    """Draw ``label`` at the free spot nearest to its point."""
    ax, fig = label.ax, label.ax.figure
    px_per_pt = fig.dpi / 72
    w, h, width, height = _size(label, renderer)
    anchor = _anchor(label)
    cx, cy, _ = _Occupancy(ax, renderer).spot(width, height, anchor)
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


def _finish(fig, labels: list[_Label]) -> None:
    """Fix the layout (legends outside the axes, titles, colour bars), then place the labels in it.

    A label with no free spot in its axes gets room under the data (the bottom of a linear y axis
    lowered), and the layout is done again for the new tick labels before any label is placed."""
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    moved = False
    for label in labels:
        _, _, width, height = _size(label, renderer)
        if not _Occupancy(label.ax, renderer).spot(width, height, _anchor(label))[2]:
            moved |= _make_room_below(label.ax, 1.25 * height + CELL)
    if moved:
        fig.draw_without_rendering()
    fig.set_layout_engine("none")
    for label in labels:
        _place(label, renderer)


def _outcome_note(ax, ds: xr.Dataset) -> list[_Label]:
    """How a run that did not complete ended, in the free corner of its panel nearest the lower left."""
    if ds.attrs.get("outcome", "completed") == "completed":
        return []
    text = _wrap(f"{ds.attrs['outcome']}: {ds.attrs['outcome_message']}", 40)
    frame = {"facecolor": "white", "edgecolor": ACCENT, "linewidth": 0.6}
    return [_Label(ax, text, (0.0, 0.0), "axes fraction", {"fontsize": 6.5, "color": ACCENT, "bbox": frame},
                   leader=False)]


def _legend_below(fig, axes, ncols: int, order: tuple[str, ...] = (), **kwargs):
    """One legend for the whole figure, below its axes: every labelled line once, those named in
    ``order`` first, in that order, then the others as they come."""
    entries: dict[str, object] = {}
    for ax in np.ravel(axes):
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    labels = [k for k in order if k in entries] + [k for k in entries if k not in order]
    return fig.legend([entries[k] for k in labels], labels, loc="outside lower center", ncols=ncols, **kwargs)


# ---- the paper's figures


def fig3(cases: dict[str, xr.Dataset]):
    """Velocity before impact, period and amplitude against the cycle, one column per case."""
    rows = [
        ("velocity_before_impact", "Velocity before impact (m/s)"),
        ("period", "Period (s)"),
        ("amplitude", "Amplitude of oscillation (m)"),
    ]
    first = next(iter(cases.values()))
    definitions = "\n".join(_wrap(f"{name}: {first[name].attrs['long_name']}", 100) for name in ("period", "amplitude")
                             if "long_name" in first[name].attrs)
    notes = []
    with style():
        fig, axes = plt.subplots(3, len(cases), figsize=(3.4 * len(cases), 7.9), squeeze=False, sharex="col",
                                 layout="constrained")
        for col, (label, ds) in enumerate(cases.items()):
            period = natural_period(ds)
            for row, (name, ylabel) in enumerate(rows):
                ax = axes[row, col]
                ax.plot(ds[ds[name].dims[0]], ds[name], marker="o", markersize=2.5, lw=1.0, color=INK, zorder=2,
                        label="exact solution, per cycle")
                # the guides are drawn over the points they are compared with, in colours of their own
                if name == "velocity_before_impact" and "fixed_point_19" in ds:
                    ax.axhline(float(ds["fixed_point_19"]), ls=(0, (5, 3)), lw=1.1, color=ACCENT, zorder=3,
                               label="fixed point of Eq. (19) as printed")
                if name == "period":
                    ax.axhline(period, ls=":", lw=1.2, color=GUIDE, zorder=3,
                               label=f"2\u03c0/\u03c9 = {period:.4f} s, the period the paper reports")
                ax.set_ylabel(ylabel)
                if row == 2:
                    ax.set_xlabel("Number of cycles")
            reading = _reading(ds, f"{_value('F', float(ds['F']))}, {_release(ds)}")
            axes[0, col].set_title(f"({label}) {_wrap(reading, 40)}")
            notes += _outcome_note(axes[0, col], ds)
        fig.suptitle(f"{_source(first, 'Fig. 3')}\n{definitions}", fontsize=8.5)
        _legend_below(fig, axes, ncols=2)
        _finish(fig, notes)
    return fig


def fig4(ds: xr.Dataset):
    """Velocity and acceleration around the impacts; jumps drawn as jumps, each impact labelled with
    its impulse and the energy it dissipates."""
    t = ds["t"].values
    impacts = ds["impact_time"].values
    switches = ds["event_time"].values
    v_lo, v_hi = ds["velocity_window"].values
    a_lo, a_hi = ds["acceleration_window"].values
    impulse, energy = ds["impulse"].values, ds["energy_dissipated"].values
    before, after = ds["velocity_before"].values, ds["velocity_after"].values
    labels = []
    with style():
        fig, (ax_v, ax_a) = plt.subplots(1, 2, figsize=(7.6, 3.9), layout="constrained")
        sel = (t >= v_lo) & (t <= v_hi)
        ax_v.plot(*_broken(t[sel], ds["velocity"].values[sel], impacts), color=INK, label="velocity")
        ax_v.plot(impacts, before, "o", mfc="white", color=ACCENT, label="velocity just before an impact")
        ax_v.plot(impacts, after, "o", color=ACCENT, label="velocity just after an impact")
        ax_v.set_xlim(v_lo, v_hi)
        ax_v.set_xlabel("Time (s)")
        ax_v.set_ylabel("Velocity (m/s)")
        inside = (impacts >= v_lo) & (impacts <= v_hi)
        for ti, j, e, vb, va in zip(impacts[inside], impulse[inside], energy[inside], before[inside], after[inside]):
            labels.append(_Label(ax_v, f"impulse {_signed(j, '+.4f')} N s\ndissipated {e:.4f} J", (ti, (vb + va) / 2),
                                 style={"fontsize": 6.5, "color": ACCENT}))

        sel = (t >= a_lo) & (t <= a_hi)
        ax_a.plot(*_broken(t[sel], ds["acceleration"].values[sel], switches), color=INK,
                  label="acceleration between events")
        # a Dirac impulse has no height: its arrow spans most of the panel, pointing the way it acts,
        # inside the limits the smooth acceleration sets (which stay fixed)
        y_lo, y_hi = ax_a.get_ylim()
        ax_a.set_ylim(y_lo, y_hi)
        inside = (impacts >= a_lo) & (impacts <= a_hi)
        for ti, j in zip(impacts[inside], impulse[inside]):
            base, tip = (y_lo + 0.85 * (y_hi - y_lo), y_lo + 0.12 * (y_hi - y_lo))[:: 1 if j < 0 else -1]
            ax_a.annotate("", xy=(ti, tip), xytext=(ti, base), arrowprops={"arrowstyle": "-|>", "color": ACCENT,
                                                                          "lw": 1.4})
            labels.append(_Label(ax_a, f"impulse {_signed(j, '+.4f')} N s", (ti, tip),
                                 style={"fontsize": 6.5, "color": ACCENT}))
        ax_a.plot([], [], color=ACCENT, lw=1.4, label="impulse M \u0394v at an impact (Dirac, not to scale)")
        ax_a.set_xlim(a_lo, a_hi)
        ax_a.set_xlabel("Time (s)")
        ax_a.set_ylabel("Acceleration (m/s\u00b2)")
        params = f"{_value('F', float(ds['F']))}, {_value('K', float(ds['K']))}, {_release(ds)}"
        reading = _reading(ds, f"case assumed (the paper does not say which it shows): {params}")
        fig.suptitle(f"{_source(ds, 'Fig. 4')}\n{_wrap(reading, 110)}", fontsize=8.5)
        _legend_below(fig, (ax_v, ax_a), ncols=2)  # a column per panel
        _finish(fig, labels + _outcome_note(ax_v, ds))
    return fig


def fig5(panels: dict[str, xr.Dataset]):
    """Phase diagrams: the transient in light colour, the last cycle in dark, impacts as vertical jumps;
    each panel states the force and the release it assumes."""
    letters = "abcdefghij"
    notes = []
    with style():
        fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.9), squeeze=False,
                                 layout="constrained")
        for ax, letter, (label, ds) in zip(axes[0], letters, panels.items()):
            t, x, v = ds["t"].values, ds["displacement"].values, ds["velocity"].values
            impacts = ds["impact_time"].values
            tb, xb = _broken(t, x, impacts)
            _, vb = _broken(t, v, impacts)
            ax.plot(xb, vb, color=MUTED, lw=0.7, label="transient")
            if ds.sizes.get("cycle", 0):
                start = ds["impact_time"].values[-1] - ds["period"].values[-1]
                last = tb >= start
                ax.plot(xb[last], vb[last], color=INK, lw=1.4, label="last cycle")
            ax.vlines(ds["impact_position"], ds["velocity_after"], ds["velocity_before"], color=ACCENT, lw=0.8,
                      label="impacts (velocity jumps)")
            ax.set_xlabel("Displacement (m)")
            ax.set_ylabel("Velocity (m/s)")
            start = "from rest" if _v0(ds) == 0 else _value("v0", _v0(ds))
            reading = _reading(ds, f"{_value('F', float(ds['F']))}, {_value('x0', float(ds['x0']))}, {start}")
            ax.set_title(f"({letter}) {_value('K', float(ds['K']))}\n{_wrap(reading, 40)}")
            notes += _outcome_note(ax, ds)
        first = next(iter(panels.values()))
        fig.suptitle(f"{_source(first, 'Fig. 5')}\nF and x(0) are not given by the paper: each panel states those "
                     "assumed", fontsize=8.5)
        _legend_below(fig, axes, ncols=3, order=("transient", "last cycle"))
        _finish(fig, notes)
    return fig


# ---- the project's own figures

#: errors below this are drawn at it on log axes (an exact zero has no logarithm)
ERROR_FLOOR = 1e-17
MARKERS = {"exact": "*", "closed-form cycles": "X", "map16": "P", "naive-RK4": "x", "RK45": "o", "DOP853": "s", "LSODA": "^", "Radau": "v",
           "CVODE-Adams": "D", "CVODE-BDF": "d"}
#: the benchmark's methods in words, where their names are not words
METHOD_LABELS = {"exact": "exact solver", "closed-form cycles": "per-cycle closed forms",
                 "map16": "map (16) + corrected period (23)",
                 "naive-RK4": "naive RK4, fixed step"}


def work_precision(rows: list[dict]):
    """Relative error against wall time, one curve per method, for the velocity and the impact time."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(8.4, 4.1), sharex=True, layout="constrained")
        colours = plt.get_cmap("tab10")
        for i, method in enumerate(methods):
            mine = [r for r in rows if r["method"] == method]
            wall = [float(r["wall_s"]) for r in mine]
            for ax, key in zip(axes, ("error_velocity", "error_time")):
                err = [max(float(r[key]), ERROR_FLOOR) for r in mine]
                ax.loglog(wall, err, marker=MARKERS.get(method, "o"), color=colours(i % 10), lw=1.0, ms=5,
                          label=METHOD_LABELS.get(method, method))
        for ax, title in zip(axes, ("velocity before impact, cycle 50", "impact time, cycle 50")):
            ax.set_xlabel("Wall time per run (s), median of repeats")
            ax.set_ylabel("Relative error")
            ax.set_title(title)
            ax.axhline(ERROR_FLOOR, color=GUIDE, lw=0.6, ls=":")
        fig.suptitle("Work-precision, Fig. 3 case (a): errors against 50 digits (exact zero drawn at 1e-17)\n"
                     "map (16) + corrected period (23): the closed-form Poincar\u00e9 map, no integration",
                     fontsize=8.5)
        _legend_below(fig, axes, ncols=5, fontsize=7)
        _finish(fig, [])
    return fig


def long_run(ds: xr.Dataset):
    """Phase error (impact time minus the 50-digit reference) and velocity error against the number of cycles."""
    cycle = ds["cycle"].values
    series = (("exact", INK, "exact solver"), ("ivp", ACCENT, ds.attrs["ivp_label"]))
    with style():
        fig, (ax_t, ax_v) = plt.subplots(1, 2, figsize=(8.4, 3.8), sharex=True, layout="constrained")
        for solver, colour, label in series:
            drift = np.maximum(np.abs(ds[f"drift_{solver}"].values), 1e-17)
            ax_t.loglog(cycle, drift, color=colour, lw=1.2, marker=".", ms=3, label=label)
            error = np.maximum(ds[f"error_velocity_{solver}"].values, ERROR_FLOOR)
            ax_v.loglog(cycle, error, color=colour, lw=1.2, marker=".", ms=3, label=label)
        ulp = np.spacing(float(ds["fixed_point_period"]) * cycle.astype(float))
        ax_t.loglog(cycle, ulp, color=GUIDE, lw=0.8, ls=":", label="spacing of float64 at t")
        ax_t.set_ylabel("|impact time − reference| (s)")
        ax_t.set_title("phase error of the impact at a1")
        ax_v.set_ylabel("Relative error")
        ax_v.set_title("velocity before impact")
        for ax in (ax_t, ax_v):
            ax.set_xlabel("Number of cycles")
        case = (f"{_value('F', float(ds['F']))}, {_release(ds)}" if {"F", "x0"} <= set(ds.variables)
                else "Fig. 3 case (a)")
        fig.suptitle(f"Long run, {case}: errors against the 50-digit reference", fontsize=8.5)
        _legend_below(fig, (ax_t, ax_v), ncols=3)
        _finish(fig, [])
    return fig


def _cell_edges(centres: np.ndarray) -> np.ndarray:
    """The edges of the cells of ``shading="nearest"`` around the centres: midway between them."""
    c = np.asarray(centres, dtype=float)
    if c.size == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = (c[:-1] + c[1:]) / 2
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def _cells_path(mask: np.ndarray, x_edges: np.ndarray, y_edges: np.ndarray) -> Path | None:
    """One path over the cells where ``mask`` (rows along y) holds: the runs of each row as rectangles,
    consecutive rows with the same runs merged, so that a block of cells is one rectangle."""
    runs_of_rows = []
    for row in mask:
        padded = np.concatenate([[False], row, [False]]).astype(np.int8)
        change = np.flatnonzero(np.diff(padded))
        runs_of_rows.append(tuple(zip(change[::2], change[1::2])))
    rectangles = []
    j = 0
    while j < len(runs_of_rows):
        k = j
        while k + 1 < len(runs_of_rows) and runs_of_rows[k + 1] == runs_of_rows[j]:
            k += 1
        for i0, i1 in runs_of_rows[j]:
            rectangles.append((x_edges[i0], y_edges[j], x_edges[i1], y_edges[k + 1]))
        j = k + 1
    if not rectangles:
        return None
    vertices, codes = [], []
    for x0, y0, x1, y1 in rectangles:
        vertices += [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]
        codes += [Path.MOVETO, Path.LINETO, Path.LINETO, Path.LINETO, Path.CLOSEPOLY]
    return Path(vertices, codes)


def stability_map(ds: xr.Dataset):
    """Measured multiplier over (b, F), its distance from (1 - b)**4, and where no cycle exists."""
    from matplotlib.colors import LogNorm

    b, F = ds["b"].values, ds["F"].values
    mu = ds["multiplier"].values.T
    deviation = np.abs(ds["multiplier"].values - ds["multiplier_eq21"].values).T
    outcome = ds["outcome"].values.T
    meanings = ds["outcome"].attrs["flag_meanings"].split()
    completed = meanings.index("completed")
    no_cycle = (outcome != completed) | ~np.isfinite(mu)
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(8.4, 4.0), sharey=True, layout="constrained")
        mesh = axes[0].pcolormesh(b, F, np.where(no_cycle, np.nan, mu), shading="nearest", cmap="viridis",
                                  vmin=0, vmax=1, rasterized=True)
        fig.colorbar(mesh, ax=axes[0], label="measured multiplier \u03bc\u2082")
        # an exact zero is drawn at the floor, below the scale: in the lowest colour, as perfect agreement;
        # where there is no cycle there is nothing to compare, and the cell is left to the mark below
        dev = np.where(no_cycle, np.nan, np.where(deviation > 0, deviation, ERROR_FLOOR))
        mesh = axes[1].pcolormesh(b, F, dev, shading="nearest", cmap="magma", norm=LogNorm(vmin=1e-16, vmax=1e-8),
                                  rasterized=True)
        fig.colorbar(mesh, ax=axes[1], extend="min", label="|\u03bc\u2082 measured \u2212 (1 \u2212 b)\u2074|")
        cells = _cells_path(no_cycle, _cell_edges(b), _cell_edges(F))
        names = sorted({meanings[c] for c in np.unique(outcome[no_cycle & (outcome != completed)])})
        label = "no cycle" + (f": {', '.join(names).replace('_', ' ')} (the impacts accumulate in finite time)"
                              if names else "")
        for ax in axes:
            if cells is not None:
                ax.add_patch(PathPatch(cells, facecolor=NO_CYCLE, edgecolor=GUIDE, hatch="////", lw=0,
                                       label=label))
            ax.set_xlabel("Impact coefficient b")
            ax.grid(False)  # grid lines over a map read as cell borders
        axes[0].set_ylabel("Force F (N)")
        axes[0].set_title("Multiplier measured from the simulated return map")
        axes[1].set_title("Distance from Eq. (21)")
        constants = ", ".join(_value(k, float(ds[k])) for k in ("M", "K", "a1", "a2", "a3", "a4") if k in ds)
        fig.suptitle(f"Stability and existence map over (b, F), Sec. 3.4 and Eq. (21) of the paper\n{constants}",
                     fontsize=8.5)
        if cells is not None:
            handle = Patch(facecolor=NO_CYCLE, edgecolor=GUIDE, hatch="////", lw=0, label=label)
            fig.legend(handles=[handle], loc="outside lower center")
        _finish(fig, [])
    return fig


def escapement_error(ds: xr.Dataset):
    """The limit cycle's rate against its amplitude for each impulse zone, and its two parts: the
    impacts' phase jumps dT1 and the impulse zones' dT2 (Airy's escapement error)."""
    names = [str(n) for n in ds["zone_name"].values]
    panels = (("rate", "Rate (s/day)", "rate: impacts and impulse"),
              ("rate_impacts", "Rate from the impacts, dT1 (s/day)", "impacts' phase jumps, Eq. (24)"),
              ("rate_zones", "Rate from the impulse, dT2 (s/day)", "impulse zones, Eq. (25)"))
    with style():
        fig, axes = plt.subplots(1, 3, figsize=(10.2, 3.9), sharex=True, layout="constrained")
        for i, name in enumerate(names):
            a1, a2 = float(ds["zone_a1"][i]), float(ds["zone_a2"][i])
            label = f"{name}: impact at a1 = {a1:g} m, impulse to a2 = {a2:g} m"
            for ax, (variable, _, _) in zip(axes, panels):
                ax.plot(ds["amplitude"][i], ds[variable][i], marker="o", ms=2.5, lw=1.1, color=SERIES[i % 4],
                        label=label)
        for ax, (_, ylabel, title) in zip(axes, panels):
            ax.axhline(0.0, color=GUIDE, lw=0.6, ls=":")
            ax.set_xlabel("Amplitude of the limit cycle (m)")
            ax.set_ylabel(ylabel)
            ax.set_title(title)
        model = ", ".join(_value(k, float(ds[k])) for k in ("M", "K", "b"))
        fig.suptitle(
            "Escapement error (beyond the paper): rate of a clock counting 2\u03c0/\u03c9 per swing, against amplitude\n"
            f"{model}; F from {float(ds['F'][0]):g} to {float(ds['F'][-1]):g} N; the second half cycle mirrors the "
            f"first; exact solver, Eqs. (24)-(25) corrected agree to {float(ds['max_period_difference']):.0e}",
            fontsize=8.5)
        _legend_below(fig, axes, ncols=2, fontsize=7.5)
        _finish(fig, [])
    return fig
