"""The three figures of a scene, drawn from its netCDF datasets. Given ``axes`` (:mod:`escapement.plotting.panel_axes`),
a panel is drawn with exactly those limits and tick step, else autoscaled; guides (a fixed point, the natural period)
are drawn only inside the axes, so that the legend lists only what a panel shows.
"""

from __future__ import annotations

import math
import string
from collections.abc import Mapping

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..paper.printed_axes import FIG3_PERIOD
from .captions import axis_label, changes_legend, outcome, panel_parameters, release, signed, unit
from .panel_axes import DrawnAxes, apply_axes
from .stylesheet import ACCENT, GUIDE, INK, MUTED, SERIES, WIDTH, legend_below, style, suptitle

__all__ = ["MAX_IMPACTS_LISTED", "broken", "phase_diagrams", "poincare_map", "shock_detail"]

#: the most impacts the shock detail's legend lists with their impulse and energy
MAX_IMPACTS_LISTED = 6
#: the rows of the Poincaré map: the key of its printed axes and the variable (None: the dataset's amplitude)
_ROWS = (("velocity", "velocity_before_impact"), ("period", "period"), ("amplitude", None))


def broken(t: np.ndarray, y: np.ndarray, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``t`` and ``y`` as floats with NaN inserted at each break time, so that a line is not drawn across a jump."""
    idx = np.searchsorted(t, breaks)
    return np.insert(t.astype(float), idx, np.nan), np.insert(y.astype(float), idx, np.nan)


def _panel_title(name: str, ds: xr.Dataset, datasets) -> str:
    """``(a) F = 1 N, K = 1 N/m`` / ``from rest at x(0) = -1 m`` / how the run ended, if it did not complete."""
    lines = [f"({name}) " + panel_parameters(ds, datasets), release(ds), outcome(ds)]
    return "\n".join(line for line in lines if line)


def _check(axes: DrawnAxes | None, keys) -> None:
    unknown = set(axes or ()) - set(keys)
    if unknown:
        raise ValueError(f"axes names no panel of this figure: {', '.join(sorted(map(repr, unknown)))}; its panels are "
                         f"{', '.join(sorted(keys))}")


def _axes(ax, axes: DrawnAxes | None, key: str) -> None:
    """The panel's given axes, else matplotlib's autoscaling; either way the limits are fixed from here on."""
    if axes and key in axes:
        apply_axes(ax, axes[key])
    ax.set(xlim=ax.get_xlim(), ylim=ax.get_ylim())


def _guide(ax, y: float, **look) -> None:
    low, high = ax.get_ylim()
    if low <= y <= high:
        ax.axhline(y, zorder=3, **look)


def poincare_map(cases: Mapping[str, xr.Dataset], title: str, axes: DrawnAxes | None = None) -> Figure:
    """The velocity before impact, the period and the amplitude against the cycle number, one column per case.
    ``axes`` keys: ``"<case>/velocity"``, ``".../period"`` (widened to the paper's period), ``".../amplitude"``."""
    datasets = list(cases.values())
    _check(axes, [f"{label}/{key}" for label in cases for key, _ in _ROWS])
    with style():
        fig, grid = plt.subplots(3, len(cases), figsize=(max(WIDTH, 2.2 * len(cases)), 7.4), squeeze=False,
                                 layout="constrained")
        for col, (label, ds) in enumerate(cases.items()):
            for row, (key, name) in enumerate(_ROWS):
                ax, values = grid[row, col], ds[name or ds.attrs["amplitude_variable"]]
                if values.size:
                    ax.plot(values[values.dims[0]], values, marker="o", markersize=2.5, lw=1.0, color=INK,
                            label="exact solution, per cycle")
                if values.size > ds.sizes["cycle"]:  # why its axis may run a tick further than the cycles'
                    ax.plot([], [], ls="none", label=f"amplitude: {values.size} values for {ds.sizes['cycle']} "
                            "cycles, one per impact at a\u2081, so its axis may run to the next tick")
                ax.set(xlabel="Number of cycles", ylabel=axis_label(values.name))
                _axes(ax, axes, f"{label}/{key}")
                if key == "velocity" and "fixed_point_19" in ds:
                    _guide(ax, float(ds["fixed_point_19"]), ls=(0, (5, 3)), lw=1.1, color=ACCENT,
                           label="fixed point of Eq. (19) as printed")
                if key == "period" and axes and f"{label}/period" in axes:  # the paper's scene, widened to its period
                    low, high, step = axes[f"{label}/period"]["y"]
                    below = step * (round(FIG3_PERIOD / step) - math.ceil(0.06 * (high - FIG3_PERIOD) / step))
                    apply_axes(ax, {"y": (min(low, below), high, step)})
                    ax.axhline(FIG3_PERIOD, ls="-.", lw=1.2, color=SERIES[2], zorder=3,
                               label=f"the period the paper prints for both cases, {FIG3_PERIOD:g} s")
                elif key == "period":
                    _guide(ax, 2 * math.pi * math.sqrt(float(ds["M"]) / float(ds["K"])), ls=":", lw=1.2,
                           color=GUIDE, label="natural period 2\u03c0/\u03c9")
            grid[0, col].set_title(_panel_title(label, ds, datasets))
        suptitle(fig, title)
        legend_below(fig, grid, ncols=1, **changes_legend(fig, datasets))
    return fig


def shock_detail(ds: xr.Dataset, title: str, axes: DrawnAxes | None = None) -> Figure:
    """The velocity and the acceleration around the impacts, an impulse as an arrow, each impact of the velocity window
    listed with its impulse and the energy it dissipates. ``axes`` keys: ``"velocity"``, ``"acceleration"``."""
    _check(axes, ("velocity", "acceleration"))
    t, impacts = ds["t"].values, ds["impact_time"].values
    impulse, energy = ds["impulse"].values, ds["energy_dissipated"].values
    with style():
        fig, (ax_v, ax_a) = plt.subplots(1, 2, figsize=(WIDTH, 3.6), layout="constrained")
        for ax, name, jumps, label in ((ax_v, "velocity", impacts, "velocity"),
                                       (ax_a, "acceleration", ds["event_time"].values, "acceleration between events")):
            lo, hi = ds[f"{name}_window"].values
            inside = (t >= lo) & (t <= hi)
            ax.plot(*broken(t[inside], ds[name].values[inside], jumps), color=INK, label=label)
            ax.set(xlim=(lo, hi), xlabel=axis_label("t"), ylabel=axis_label(name))
        lo, hi = ds["velocity_window"].values
        shown = (impacts >= lo) & (impacts <= hi)
        if shown.any():
            ax_v.plot(impacts[shown], ds["velocity_before"].values[shown], "o", mfc="white", color=ACCENT,
                      label="velocity just before an impact")
            ax_v.plot(impacts[shown], ds["velocity_after"].values[shown], "o", color=ACCENT,
                      label="velocity just after an impact")
        _axes(ax_v, axes, "velocity")
        _axes(ax_a, axes, "acceleration")
        # a Dirac impulse has no height: its arrow spans most of the panel, pointing the way it acts
        lo, hi = ds["acceleration_window"].values
        y_lo, y_hi = ax_a.get_ylim()
        arrows = [(ti, j) for ti, j in zip(impacts, impulse) if lo <= ti <= hi]
        for ti, j in arrows:
            base, tip = (y_lo + 0.85 * (y_hi - y_lo), y_lo + 0.12 * (y_hi - y_lo))[:: 1 if j < 0 else -1]
            ax_a.annotate("", xy=(ti, tip), xytext=(ti, base),
                          arrowprops={"arrowstyle": "-|>", "color": ACCENT, "lw": 1.4})
        if arrows:
            ax_a.plot([], [], color=ACCENT, lw=1.4, label="impulse M\u0394v at an impact (Dirac, not to scale)")
        # the legend: what each panel draws, then the impacts of the velocity window
        entries = [(label, h) for ax in (ax_v, ax_a) for h, label in zip(*ax.get_legend_handles_labels())]
        listed = np.flatnonzero(shown)
        entries += [(f"impact at t\u00a0=\u00a0{signed(impacts[i], '.5g')}\u00a0s: impulse {signed(impulse[i], '.3g')}"
                   f"\u00a0{unit('impulse')}, {signed(energy[i], '.3g')}\u00a0{unit('energy_dissipated')} dissipated",
                   None) for i in listed[:MAX_IMPACTS_LISTED]]
        if len(listed) > MAX_IMPACTS_LISTED:
            entries.append((f"and {len(listed) - MAX_IMPACTS_LISTED} more impacts in the velocity window", None))
        fig.legend([h or Line2D([], [], ls="none") for _, h in entries], [label for label, _ in entries],
                   loc="outside lower center", ncols=1, **changes_legend(fig, [ds]))
        suptitle(fig, title)
    return fig


def phase_diagrams(panels: Mapping[str, xr.Dataset], title: str, axes: DrawnAxes | None = None) -> Figure:
    """Phase diagrams, one panel per dataset, lettered (a), (b), ...: the trajectory from release in light colour, the
    last cycle in dark, the impacts as vertical jumps. ``axes`` keys: the panels' keys in ``panels``."""
    datasets = list(panels.values())
    _check(axes, panels)
    with style():
        fig, grid = plt.subplots(1, len(panels), figsize=(max(WIDTH, 1.8 * len(panels)), 3.4), squeeze=False,
                                 layout="constrained")
        for col, (ax, (label, ds)) in enumerate(zip(grid[0], panels.items())):
            impacts = ds["impact_time"].values
            t, x = broken(ds["t"].values, ds["displacement"].values, impacts)
            _, v = broken(ds["t"].values, ds["velocity"].values, impacts)
            ax.plot(x, v, color=MUTED, lw=0.7, label="trajectory from release")
            if ds.sizes.get("cycle", 0):
                last = t >= impacts[-1] - ds["period"].values[-1]
                ax.plot(x[last], v[last], color=INK, lw=1.4, label="last cycle")
            if impacts.size:
                ax.vlines(ds["impact_position"], ds["velocity_after"], ds["velocity_before"], color=ACCENT, lw=0.8,
                          label="impacts (velocity jumps)")
            ax.set(xlabel=axis_label("displacement"), ylabel=axis_label("velocity") if col == 0 else "")
            _axes(ax, axes, label)
            ax.set_title(_panel_title(string.ascii_lowercase[col] if col < 26 else str(col + 1), ds, datasets))
        suptitle(fig, title)
        legend_below(fig, grid, ncols=3, **changes_legend(fig, datasets))
    return fig
