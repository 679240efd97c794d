"""The project's own figures. In the long run an adaptive integrator's errors move by a few per cent from one BLAS
kernel to another, so they are drawn as their largest per decade rounded up to 1, 2 or 5 times a power of ten; the exact
solver's and the closed forms', bit-identical, at each sampled cycle.
"""

from __future__ import annotations

import itertools
from decimal import Decimal

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure
from matplotlib.patches import Patch, PathPatch
from matplotlib.path import Path

from ..model.status import Status, succeeded
from .captions import axis_label, changes_legend, quantity_value, release, unit
from .stylesheet import ACCENT, GUIDE, INK, NO_CYCLE, SERIES, WIDTH, legend_below, power_ticks, style, suptitle

__all__ = ["ERROR_FLOOR", "escapement_error", "existence_map", "long_run", "stability_map", "work_precision"]

#: errors below this are drawn at it on log axes (an exact zero has no logarithm)
ERROR_FLOOR = 1e-17
#: the levels the long-run figure rounds the integrator's largest errors up to, times a power of ten
STEPS = (Decimal(1), Decimal(2), Decimal(5), Decimal(10))
#: the long-run figure's legend for the rounding band and for the integrator's staircase
BAND = "rounding band: 1 ulp (the float64 spacing) of the impact time; of the velocity, relative"
STAIRCASE = "largest error per decade, rounded up to 1, 2 or 5 \u00d7 10\u207f"
MARKERS = {"exact": "*", "closed-form cycles": "o", "map16": "P", "naive-RK4": "x", "RK45": "p", "DOP853": "s",
           "LSODA": "^", "Radau": "v", "CVODE-Adams": "D", "CVODE-BDF": "d"}
#: where the exact solver and the closed forms take the same time to the same error: a star inside an open ring
LOOKS = {"exact": {"ms": 7, "zorder": 4}, "closed-form cycles": {"ms": 11, "mfc": "none", "mew": 1.2, "zorder": 3}}
#: the benchmark's methods in words, where their names are not words
METHOD_LABELS = {"exact": "exact solver", "closed-form cycles": "per-cycle closed forms",
                 "map16": "map (16) + corrected period (23)", "naive-RK4": "naive RK4, fixed step"}


def work_precision(rows: list[dict], title: str | None = None) -> Figure:
    """Relative error against wall time, one line per method (its settings from the loosest to the tightest), for
    the velocity before impact and the impact time; an exact zero is drawn at :data:`ERROR_FLOOR`."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(WIDTH, 4.1), sharex=True, layout="constrained")
        colours = plt.get_cmap("tab10")
        for i, method in enumerate(methods):
            mine = [r for r in rows if r["method"] == method]
            wall = [float(r["wall_s"]) for r in mine]
            for ax, key in zip(axes, ("error_velocity", "error_time")):
                err = [max(float(r[key]), ERROR_FLOOR) for r in mine]
                ax.loglog(wall, err, marker=MARKERS.get(method, "o"), color=colours(i % 10), lw=1.0,
                          **{"ms": 5, **LOOKS.get(method, {})}, label=METHOD_LABELS.get(method, method)
                          + (f", one setting ({mine[0]['setting']})" if len(mine) == 1 and mine[0]["setting"] else ""))
        for ax, name in zip(axes, ("velocity before impact", "impact time")):
            ax.set(xlabel="Wall time per run (s)", ylabel="Relative error", title=name)
            ax.axhline(ERROR_FLOOR, color=GUIDE, lw=0.6, ls=":")
        power_ticks(fig)
        suptitle(fig, title or "Work-precision of the solvers: relative error against a 50-digit reference")
        legend_below(fig, axes, ncols=3, **changes_legend(fig, [], "Each line a method from its loosest setting to "
                                                           f"its tightest; each time the median of repeated runs; an "
                                                           f"exact zero drawn at {ERROR_FLOOR:.0e}."))
    return fig


def _round_up(value: float) -> float:
    """``value`` (> 0) rounded up to 1, 2 or 5 times a power of ten from its ``repr``, so that 2e-12 stays 2e-12."""
    printed = Decimal(repr(value))
    power = Decimal(1).scaleb(printed.adjusted())
    return float(next(step for step in STEPS if step >= printed / power) * power)


def _decade_maxima(cycle: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A staircase over the decades of cycles [1, 10], (10, 100], ... that hold a finite value: on each, the largest
    of ``|values|`` (at least :data:`ERROR_FLOOR`) rounded up, over the decade clipped to the cycles given."""
    level = np.maximum(np.abs(values), ERROR_FLOOR)
    kept = np.isfinite(level)
    cycle, level = np.asarray(cycle)[kept].astype(np.int64), level[kept]
    # decade k holds the cycles in (10**(k - 1), 10**k]; cycle 1 joins decade 1
    decade = np.maximum(np.searchsorted(10 ** np.arange(19, dtype=np.int64), cycle, side="left"), 1)
    xs, ys = [], []
    for k in np.unique(decade):
        top = _round_up(float(level[decade == k].max()))
        xs += [max(10.0 ** (k - 1), float(cycle.min())), min(10.0**k, float(cycle.max()))]
        ys += [top, top]
    return np.array(xs), np.array(ys)


def long_run(ds: xr.Dataset, title: str | None = None) -> Figure:
    """The phase error (impact time minus the 50-digit reference, s) and the relative error of the velocity before
    impact against the number of cycles, over the band of float64 spacing."""
    cycle = ds["cycle"].values
    v_star = float(ds["fixed_point_velocity"])
    # the band on a fine grid of cycles, so that its steps (where the impact time passes a power of two) are steps
    fine = np.geomspace(cycle.min(), cycle.max(), 2000)
    bands = {"drift": np.spacing(float(ds["fixed_point_period"]) * fine),
             "error_velocity": np.full(fine.shape, np.spacing(v_star) / v_star)}
    bottom = ERROR_FLOOR / 2
    with style():
        fig, (ax_t, ax_v) = plt.subplots(1, 2, figsize=(WIDTH, 4.4), sharex=True, layout="constrained")
        for ax, key in ((ax_t, "drift"), (ax_v, "error_velocity")):
            ax.fill_between(fine, bottom, bands[key], color=NO_CYCLE, lw=0, label=BAND)
            if f"{key}_closed_form" in ds:
                ax.loglog(cycle, np.maximum(np.abs(ds[f"{key}_closed_form"].values), ERROR_FLOOR), "o", ms=4.5,
                          mfc="none", mew=0.7, color=SERIES[2], label="per-cycle closed forms, each sampled cycle")
            ax.loglog(cycle, np.maximum(np.abs(ds[f"{key}_exact"].values), ERROR_FLOOR), "o", ms=2.2, color=INK,
                      label="exact solver, each sampled cycle")
            xs, ys = _decade_maxima(cycle, ds[f"{key}_ivp"].values)
            if xs.size:
                ax.loglog(xs, ys, color=ACCENT, lw=1.6, label=f"{ds.attrs['ivp_label']}, run over "
                          f"{int(ds.attrs['ivp_cycles']):,} cycles only:\n{STAIRCASE}")
            ax.set(ylim=(bottom, None), xlabel="Number of cycles")
        ax_t.set(ylabel=f"|impact time \u2212 reference| ({unit('impact_time')})",
                 title="phase error of the impact at a\u2081")
        ax_v.set(ylabel="Relative error", title="velocity before impact")
        power_ticks(fig)
        suptitle(fig, title or "Long run: errors against a 50-digit reference")
        legend_below(fig, (ax_t, ax_v), ncols=1, **changes_legend(
            fig, [], f"{quantity_value('F', float(ds['F']))}, released {release(ds)}."))
    return fig


def _cell_edges(centres: np.ndarray) -> np.ndarray:
    """The edges of the cells of ``shading="nearest"`` around the centres: midway between them."""
    c = np.asarray(centres, dtype=float)
    if c.size == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = (c[:-1] + c[1:]) / 2
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def _cells_path(mask: np.ndarray, x_edges: np.ndarray, y_edges: np.ndarray) -> Path | None:
    """One path over the cells where ``mask`` (rows along y) holds, each block of cells one rectangle."""
    runs_of_rows = []
    for row in mask:
        change = np.flatnonzero(np.diff(np.concatenate([[False], row, [False]]).astype(np.int8)))
        runs_of_rows.append(tuple(zip(change[::2], change[1::2])))
    vertices, codes, j = [], [], 0
    for runs, rows in itertools.groupby(runs_of_rows):
        k = j + len(list(rows))
        for i0, i1 in runs:
            x0, y0, x1, y1 = x_edges[i0], y_edges[j], x_edges[i1], y_edges[k]
            vertices += [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]
            codes += [Path.MOVETO, Path.LINETO, Path.LINETO, Path.LINETO, Path.CLOSEPOLY]
        j = k
    return Path(vertices, codes) if vertices else None


def _constants(ds: xr.Dataset, names: tuple[str, ...]) -> str:
    return ", ".join(quantity_value(k, float(ds[k])) for k in names if k in ds and ds[k].ndim == 0)


def stability_map(ds: xr.Dataset, title: str | None = None) -> Figure:
    """The multiplier measured over (b, F), its distance from Eq. (21)'s (1 - b)**4, and where no cycle exists."""
    b, F = ds["b"].values, ds["F"].values
    mu = ds["multiplier"].values.T
    deviation = np.abs(ds["multiplier"].values - ds["multiplier_eq21"].values).T
    outcome = ds["outcome"].values.T
    no_cycle = ~succeeded(outcome) | ~np.isfinite(mu)
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(WIDTH, 4.0), sharey=True, layout="constrained")
        mesh = axes[0].pcolormesh(b, F, np.where(no_cycle, np.nan, mu), shading="nearest", cmap="viridis",
                                  vmin=0, vmax=1, rasterized=True)
        fig.colorbar(mesh, ax=axes[0], label="measured multiplier \u03bc\u2082")
        # an exact zero is drawn at the floor, below the scale: in the lowest colour, as perfect agreement
        dev = np.where(no_cycle, np.nan, np.where(deviation > 0, deviation, ERROR_FLOOR))
        mesh = axes[1].pcolormesh(b, F, dev, shading="nearest", cmap="magma", norm=LogNorm(vmin=1e-16, vmax=1e-8),
                                  rasterized=True)
        fig.colorbar(mesh, ax=axes[1], extend="min", label="|\u03bc\u2082 measured \u2212 (1 \u2212 b)\u2074|")
        cells = _cells_path(no_cycle, _cell_edges(b), _cell_edges(F))
        names = sorted({Status.from_code(c).value for c in np.unique(outcome[~succeeded(outcome)])})
        label = "no cycle" + (": " if names else "") + ", ".join(name.replace("_", " ") for name in names)
        if Status.CHATTERING.value in names:
            label += " (the impacts accumulate in finite time)"
        look = {"facecolor": NO_CYCLE, "edgecolor": GUIDE, "hatch": "////", "lw": 0}
        for ax in axes:
            if cells is not None:
                ax.add_patch(PathPatch(cells, **look, label=label))
            ax.set_xlabel(axis_label("b"))
            ax.grid(False)  # grid lines over a map read as cell borders
        axes[0].set(ylabel=axis_label("F"), title="measured on the return map")
        axes[1].set_title("distance from Eq. (21)")
        power_ticks(fig)
        suptitle(fig, title or "Stability of the limit cycle over (b, F): its multiplier and Eq. (21)")
        fig.legend(handles=[Patch(**look, label=label)] if cells is not None else [], loc="outside lower center",
                   **changes_legend(fig, [ds], _constants(ds, ("M", "K", "a1", "a2", "a3", "a4")) + "."))
    return fig


def escapement_error(ds: xr.Dataset, title: str | None = None) -> Figure:
    """The limit cycle's rate against its amplitude for each impulse zone, and its two parts, dT1 and dT2."""
    panels = (("rate", "the rate, both parts"), ("rate_impacts", "impacts, dT1, Eq. (24)"),
              ("rate_zones", "impulse, dT2, Eq. (25)"))
    with style():
        fig, axes = plt.subplots(1, 3, figsize=(WIDTH, 3.6), sharex=True, sharey=True, layout="constrained")
        for i, name in enumerate(str(n) for n in ds["zone_name"].values):
            a1, a2 = float(ds["zone_a1"][i]), float(ds["zone_a2"][i])
            label = f"{name}: impact at {quantity_value('a1', a1)}, impulse to {quantity_value('a2', a2)}"
            if not np.isfinite(ds["rate"][i]).any():  # no limit cycle at any force: the legend says how it ends
                ends = sorted({Status.from_code(int(c)).value.replace("_", " ") for c in ds["outcome"].values[i]})
                axes[0].plot([], [], ls="none", label=f"{label}: no limit cycle ({', '.join(ends)})")
                continue
            for ax, (variable, _) in zip(axes, panels):
                ax.plot(ds["largest_displacement"][i], ds[variable][i], marker="o", ms=2.5, lw=1.1, color=SERIES[i % 4],
                        label=label)
        for ax, (_, name) in zip(axes, panels):
            ax.axhline(0.0, color=GUIDE, lw=0.6, ls=":")
            ax.set_title(name)
        axes[0].set_ylabel("Rate (s/day)\n> 0: gains (runs fast), < 0: loses")
        axes[1].set_xlabel(f"Amplitude of the limit cycle ({unit('largest_displacement')})")
        forces = f"F from {float(ds['F'][0]):g} to {float(ds['F'][-1]):g} {unit('F')}"
        suptitle(fig, title or "Escapement error: the rate of a clock counting 2\u03c0/\u03c9 per swing")
        legend_below(fig, axes, ncols=1, **changes_legend(fig, [ds], f"{_constants(ds, ('M', 'K', 'b'))}, {forces}; "
                                                          "the second half cycle mirrors the first."))
    return fig


#: fill of the cells where the run reached a limit cycle, and of those that neither converged nor stopped
LIMIT_CYCLE, UNSETTLED = "#cfe0f1", "#f5cba7"
#: the impact positions' symbols, as the axis labels write them
A1, A2, A3, A4 = "a\u2081", "a\u2082", "a\u2083", "a\u2084"


def existence_map(ds: xr.Dataset, title: str | None = None) -> Figure:
    """Where the limit cycle of an asymmetric escapement exists over (a3, F), with the closed-form thresholds."""
    a3, F = ds["a3"].values, ds["F"].values
    outcome = ds["outcome"].values.T
    cycle = ds["converged"].values.T.astype(bool)
    stopped = outcome == Status.STOPPED.code
    x_edges, y_edges = _cell_edges(a3), _cell_edges(F) * 1e3
    regions = (
        (cycle, {"facecolor": LIMIT_CYCLE, "edgecolor": "none"},
         f"limit cycle: all {int(ds['n_cycles'])} cycles run, the last two velocities at {A1} within "
         f"{float(ds['tolerance']):.0e} (relative)"),
        (stopped & ~cycle, {"facecolor": NO_CYCLE, "edgecolor": GUIDE, "hatch": "////", "lw": 0},
         "no limit cycle: the escapement stops (a swing ends short of the next impact position)"),
        (~cycle & ~stopped, {"facecolor": UNSETTLED, "edgecolor": ACCENT, "hatch": "xx", "lw": 0},
         "neither: another outcome, or not settled within the cycles run"),
    )
    with style():
        fig, ax = plt.subplots(figsize=(WIDTH, 4.8), layout="constrained")
        handles = []
        for mask, look, label in regions:
            cells = _cells_path(mask, x_edges, y_edges)
            if cells is not None:
                ax.add_patch(PathPatch(cells, **look))
                handles.append(Patch(**look, label=label))
        for name, colour, ls, label in (
                ("threshold", ACCENT, "-", f"F*: below it the map (16) read at {A1} has no fixed point "
                 f"(the swing falls short of {A1})"),
                ("threshold_mirror", INK, "--", f"F*': the same read at {A3}, F* of the mirror image "
                 f"(the swing falls short of {A3})")):
            handles.append(ax.plot(a3, ds[name].values * 1e3, color=colour, ls=ls, lw=1.6, label=label)[0])
        symmetric = -float(ds["a1"])
        if x_edges[0] <= symmetric <= x_edges[-1]:
            handles.append(ax.axvline(symmetric, color=GUIDE, lw=0.8, ls=":",
                                      label=f"{A3} = \u2212{A1}: F* = F*' = 0, a limit cycle for every F > 0"))
        ax.set(xlim=(x_edges[0], x_edges[-1]), ylim=(y_edges[0], y_edges[-1]), xlabel=axis_label("a3"),
               ylabel=axis_label("F").replace(f"({unit('F')})", f"(m{unit('F')})"))
        ax.grid(False)  # grid lines over a map read as cell borders
        suptitle(fig, title or f"Existence of the limit cycle over ({A3}, F) with {A1} \u2260 \u2212{A3}")
        fig.legend(handles=handles, loc="outside lower center", ncols=1, **changes_legend(
            fig, [ds], f"Each run released {release(ds)}; {_constants(ds, ('M', 'K', 'b', 'a1', 'a2', 'a4'))}."))
    return fig
