"""The axes of the paper's printed panels, as the claims score them and as the figures draw them: the values a
panel draws autoscaled with the printed tick step (:mod:`escapement.plotting.autoscale`), by printed panel for the
claims (:func:`scene_axes`) and keyed as the figure functions name their panels, so that both show the same limits.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import xarray as xr
from matplotlib.ticker import AutoMinorLocator, MultipleLocator

from ..paper.printed_axes import FIG5_PANEL_K, panel, panels_of
from .autoscale import autoscaled_limits
from .captions import outcome

__all__ = ["MAX_LABELS", "DrawnAxes", "PanelAxes", "apply_axes", "phase_axes", "poincare_axes", "scene_axes",
           "shock_axes"]

#: the most labelled tick intervals an axis gets; beyond that, every few multiples of the step are labelled
MAX_LABELS = 12
_EVERY = (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10**4, 10**5, 10**6, 10**7, 10**8, 10**9)

#: the limits of each printed panel's scored axes, ``{(figure, panel): {"x": (low, high), "y": (low, high)}}``
PanelAxes = dict[tuple[str, str], dict[str, tuple[float, float]]]
#: the axes a figure function draws, by the key of its panel: ``{key: {"y": (low, high, tick step)}}``
DrawnAxes = dict[str, dict[str, tuple[float, float, float]]]


def _drawn(figure: str, name: str, x: np.ndarray, y: np.ndarray, margin: float) -> dict[str, tuple[float, ...]]:
    printed = panel(figure, name)
    return {axis_name: (*autoscaled_limits(values, axis.step, margin), axis.step)
            for (axis_name, axis), values in zip(printed.axes.items(), (x, y)) if axis.scored}


def poincare_axes(cases: Mapping[str, xr.Dataset], margin: float) -> DrawnAxes:
    """The printed axes of each Fig. 3 panel whose case label is a printed case, keyed ``"a/velocity"``,
    ``"a/period"``, ``"a/amplitude"`` (a run that did not complete is left out: its claims are not scored)."""
    found: DrawnAxes = {}
    for p in panels_of("3"):
        case, quantity = p.name.split("/")
        if case not in cases or outcome(cases[case]):
            continue
        ds = cases[case]
        names = {"velocity": "velocity_before_impact", "amplitude": ds.attrs["amplitude_variable"]}
        variable = ds[names.get(quantity, quantity)]
        found[p.name] = _drawn("3", p.name, variable[variable.dims[0]].values, variable.values, margin)
    return found


def shock_axes(ds: xr.Dataset, margin: float) -> DrawnAxes:
    """The printed axes of the two Fig. 4 panels, keyed ``"velocity"`` and ``"acceleration"``."""
    if outcome(ds):
        return {}
    windows = {p.name: ds[p.name].sel(t=slice(*ds[f"{p.name}_window"].values)) for p in panels_of("4")}
    return {name: _drawn("4", name, w["t"].values, w.values, margin) for name, w in windows.items()}


def _fig5_panel(ds: xr.Dataset) -> str | None:
    return next((name for name, K in FIG5_PANEL_K.items() if math.isclose(float(ds["K"]), K, rel_tol=1e-12)), None)


def phase_axes(panels: Mapping[str, xr.Dataset], margin: float) -> DrawnAxes:
    """The printed axes of the Fig. 5 panel of each dataset's spring constant, keyed by the dataset's label
    in ``panels`` (a dataset of no printed spring constant, or whose run did not complete, is left out)."""
    return {label: _drawn("5", name, ds["displacement"].values, ds["velocity"].values, margin)
            for label, ds in panels.items() if (name := _fig5_panel(ds)) is not None and not outcome(ds)}


def scene_axes(fig3: Mapping[str, xr.Dataset], fig4: xr.Dataset | None, fig5: Mapping[str, xr.Dataset],
               margin: float) -> PanelAxes:
    """The limits of each printed panel's scored axes (:data:`PanelAxes`) from the outputs of Figs. 3, 4 and 5."""
    drawn = {("3", name): axes for name, axes in poincare_axes(fig3, margin).items()}
    if fig4 is not None:
        drawn |= {("4", name): axes for name, axes in shock_axes(fig4, margin).items()}
    drawn |= {("5", _fig5_panel(fig5[label])): axes for label, axes in phase_axes(fig5, margin).items()}
    return {key: {axis: (low, high) for axis, (low, high, _) in axes.items()} for key, axes in drawn.items()}


def apply_axes(ax, axes: Mapping[str, tuple[float, float, float]]) -> None:
    """Draw ``axes`` (``{"x": (low, high, step), "y": ...}``) on ``ax``; an axis far wider than its step labels
    every few steps (at most :data:`MAX_LABELS`), minor ticks at the step if that is every 2 or 5, else midway."""
    for axis_name, (low, high, step) in axes.items():
        axis = {"x": ax.xaxis, "y": ax.yaxis}[axis_name]
        every = next(m for m in _EVERY if (high - low) / (step * m) <= MAX_LABELS + 1e-9)
        axis.set_major_locator(MultipleLocator(step * every))
        if every > 1:
            axis.set_minor_locator(AutoMinorLocator(every if every in (2, 5) else 2))
        (ax.set_xlim if axis_name == "x" else ax.set_ylim)(low, high)
