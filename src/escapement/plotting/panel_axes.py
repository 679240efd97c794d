"""The axes of the printed panels as the claims score them and the figures draw them.

A printed panel's scored axis (:mod:`escapement.paper.printed_axes`) gets the limits matplotlib
gives the points the pipeline's own figure draws there, autoscaled with the printed tick step
imposed and rounded out to the ticks after a margin (:mod:`escapement.plotting.autoscale`). The
axis claims compare these limits with the printed ones, and the figures draw exactly these axes
(:func:`apply_printed_axes`), so that a figure shows what its claim says it shows.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import xarray as xr
from matplotlib.ticker import MultipleLocator

from ..paper.printed_axes import FIG5_PANEL_K, panel, panels_of
from .autoscale import autoscaled_limits

__all__ = [
    "MAX_LABELS", "PanelAxes", "scene_axes", "apply_printed_axes", "fig3_axes", "fig4_axes", "fig5_axes",
    "fig5_panel_of",
]

#: the most labelled tick intervals an axis gets; the multiples of the printed step labelled beyond that
MAX_LABELS = 12
_EVERY = (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10**4, 10**5, 10**6, 10**7, 10**8, 10**9)

#: the limits of each printed panel's scored axes, ``{(figure, panel): {"x": (low, high), "y": (low, high)}}``
PanelAxes = dict[tuple[str, str], dict[str, tuple[float, float]]]


def _completed(ds: xr.Dataset) -> bool:
    return ds.attrs.get("outcome", "completed") == "completed"


def _limits(figure: str, name: str, x: np.ndarray, y: np.ndarray, margin: float) -> dict[str, tuple[float, float]]:
    printed = panel(figure, name)
    return {axis_name: autoscaled_limits(values, axis.step, margin)
            for (axis_name, axis), values in zip(printed.axes.items(), (x, y)) if axis.scored}


def fig3_axes(cases: Mapping[str, xr.Dataset], margin: float) -> PanelAxes:
    """The scored axes of the Fig. 3 panels of each case whose label is a printed case (a run that
    left the regime is left out: its claims are not evaluated)."""
    found: PanelAxes = {}
    for p in panels_of("3"):
        case, quantity = p.name.split("/")
        if case not in cases or not _completed(cases[case]):
            continue
        ds = cases[case]
        variable = ds[{"velocity": "velocity_before_impact", "amplitude": ds.attrs["amplitude_variable"]}.get(quantity,
                                                                                                          quantity)]
        found[("3", p.name)] = _limits("3", p.name, variable[variable.dims[0]].values, variable.values, margin)
    return found


def fig4_axes(ds: xr.Dataset, margin: float) -> PanelAxes:
    """The scored axes of the two Fig. 4 panels: each quantity over its window."""
    if not _completed(ds):
        return {}
    found: PanelAxes = {}
    for p in panels_of("4"):
        lo, hi = ds[f"{p.name}_window"].values
        window = ds[p.name].sel(t=slice(lo, hi))
        found[("4", p.name)] = _limits("4", p.name, window["t"].values, window.values, margin)
    return found


def fig5_panel_of(ds: xr.Dataset) -> str | None:
    """The printed Fig. 5 panel of the dataset's spring constant, or None."""
    for name, K in FIG5_PANEL_K.items():
        if math.isclose(float(ds["K"]), K, rel_tol=1e-12):
            return name
    return None


def fig5_axes(panels: Mapping[str, xr.Dataset], margin: float) -> PanelAxes:
    """The scored axes of the Fig. 5 panels, each from the dataset of its spring constant."""
    found: PanelAxes = {}
    for ds in panels.values():
        name = fig5_panel_of(ds)
        if name is not None and _completed(ds):
            found[("5", name)] = _limits("5", name, ds["displacement"].values, ds["velocity"].values, margin)
    return found


def scene_axes(fig3: Mapping[str, xr.Dataset], fig4: xr.Dataset | None, fig5: Mapping[str, xr.Dataset],
               margin: float) -> PanelAxes:
    """The limits each printed panel's scored axes get when the pipeline's outputs (Fig. 3 by case
    label, Fig. 4, Fig. 5 by any label) are autoscaled with the printed tick step imposed and the
    margin ``margin``: ``{(figure, panel): {"x": (low, high), "y": (low, high)}}`` (scored axes only;
    a panel no output holds, or whose run left the regime, is left out)."""
    return {**fig3_axes(fig3, margin), **(fig4_axes(fig4, margin) if fig4 is not None else {}),
            **fig5_axes(fig5, margin)}


def apply_printed_axes(ax, figure: str, name: str, limits: Mapping[str, tuple[float, float]]) -> None:
    """Draw the scored axes of the printed panel ``name`` of Fig. ``figure`` on ``ax``: ticks at the
    printed step, limits ``limits`` (``{"x": (low, high), "y": ...}``, as :func:`fig3_axes` etc. give)."""
    printed = panel(figure, name)
    for axis_name, (low, high) in limits.items():
        if axis_name not in printed.axes:
            raise ValueError(f"limits has the axis {axis_name!r}; it must be one of {', '.join(printed.axes)}")
        axis = ax.xaxis if axis_name == "x" else ax.yaxis
        step = printed.axes[axis_name].step
        # an axis far wider than the printed one keeps its ticks at the printed step (minor) and
        # labels every few (major), at most MAX_LABELS intervals
        every = next(m for m in _EVERY if (high - low) / (step * m) <= MAX_LABELS + 1e-9) if step > 0 else 1
        axis.set_major_locator(MultipleLocator(step * every))
        if every > 1:
            axis.set_minor_locator(MultipleLocator(step))
        (ax.set_xlim if axis_name == "x" else ax.set_ylim)(low, high)
