"""The project's own figures, beyond the paper's: the solvers' work-precision and long-run errors,
the stability and existence map over (b, F), the existence map of an asymmetric escapement over (a3, F),
and the escapement error against amplitude.

Drawn from the studies' tables and netCDF datasets, in the style and with the label placement of
the paper's figures. The long-run figure draws an adaptive integrator's errors per decade of cycles, as the
decade's largest error rounded up to 1, 2 or 5 times a power of ten: its steps amplify rounding, so that its
error at a given cycle moves by up to half with the BLAS kernels (OpenBLAS's Haswell or Sandy Bridge kernels
against its SkylakeX ones), and its largest over a decade by up to 2 %, which moves no level unless it lies
within 2 % of one.
"""

from __future__ import annotations

from decimal import Decimal

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.patches import Patch, PathPatch
from matplotlib.path import Path

from ..model.status import Status
from .captions import axis_label, quantity_value, release, unit
from .labels import finish, legend_below
from .style import ACCENT, GUIDE, INK, NO_CYCLE, SERIES, style

__all__ = ["ERROR_FLOOR", "escapement_error", "existence_map", "long_run", "stability_map", "work_precision"]


#: errors below this are drawn at it on log axes (an exact zero has no logarithm)
ERROR_FLOOR = 1e-17
#: the levels the long-run figure rounds the integrator's largest errors up to, times a power of ten: steps
#: of a factor 2 to 2.5, where the largest error over a decade moves by about 2 % with the BLAS kernels
STEPS = (Decimal(1), Decimal(2), Decimal(5), Decimal(10))
#: errors below this many units in the last place (of the impact time; of 1 for a relative error) are
#: rounding noise: the long-run figure draws them at that level
ROUNDING_ULPS = 16
EPS = float(np.finfo(float).eps)
MARKERS = {"exact": "*", "closed-form cycles": "X", "map16": "P", "naive-RK4": "x", "RK45": "o", "DOP853": "s",
           "LSODA": "^", "Radau": "v", "CVODE-Adams": "D", "CVODE-BDF": "d"}
#: the benchmark's methods in words, where their names are not words
#: the legend's entry for the ringed point: the first CVODE run, timed once, with SUNDIALS' loading
METHOD_LABELS = {"exact": "exact solver", "closed-form cycles": "per-cycle closed forms",
                 "map16": "map (16) + corrected period (23)",
                 "naive-RK4": "naive RK4, fixed step"}


def work_precision(rows: list[dict], case: str):
    """Relative error against wall time, one curve per method, for the velocity and the impact time, on the
    Fig. 3 case ``case`` (the benchmark's)."""
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
        fig.suptitle(f"Work-precision, Fig. 3 case ({case}): errors against 50 digits (exact zero drawn at "
                     f"{ERROR_FLOOR:.0e})\n"
                     "map (16) + corrected period (23): the closed-form Poincar\u00e9 map, no integration\n"
                     "each line joins a method's settings from the loosest rtol (or step) to the tightest; each "
                     "method ran one untimed cycle first,\nso that no time includes loading its modules (SciPy's, "
                     "SUNDIALS)",
                     fontsize=8.5)
        legend_below(fig, axes, ncols=5, fontsize=7)
        finish(fig, [])
    return fig


def _round_up(value: float) -> float:
    """``value`` (> 0) rounded up to 1, 2 or 5 times a power of ten, from its shortest decimal form (Python's
    ``repr``, so that 2e-12 stays 2e-12 whichever side of it its binary value lies): 2.01e-12 -> 5e-12."""
    printed = Decimal(repr(value))
    unit = Decimal(1).scaleb(printed.adjusted())
    return float(next(step for step in STEPS if step >= printed / unit) * unit)


def _decade_maxima(cycle: np.ndarray, values: np.ndarray, floor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A staircase over the decades of cycles [1, 10], (10, 100], ... that hold a finite value: on each,
    the largest of ``max(|values|, floor)`` at the cycles given, rounded up to 1, 2 or 5 times a power of ten
    (:func:`_round_up`); the step of decade k runs from cycle 10**(k - 1) to 10**k, clipped to the cycles given,
    so that the steps join; a decade without a finite value has no step, and the line runs across it."""
    level = np.maximum(np.abs(values), floor)
    kept = np.isfinite(level)
    cycle, level = np.asarray(cycle)[kept].astype(np.int64), level[kept]
    # decade k holds the cycles in (10**(k - 1), 10**k], in integers; cycle 1 joins decade 1
    decade = np.maximum(np.searchsorted(10 ** np.arange(19, dtype=np.int64), cycle, side="left"), 1)
    xs, ys = [], []
    for k in np.unique(decade):
        top = _round_up(float(level[decade == k].max()))
        xs += [max(10.0 ** (k - 1), float(cycle.min())), min(10.0**k, float(cycle.max()))]
        ys += [top, top]
    return np.array(xs), np.array(ys)


def long_run(ds: xr.Dataset):
    """Phase error (impact time minus the 50-digit reference) and velocity error against the number of cycles:
    the exact solver's at every sampled cycle, the integrator's as its largest per decade (:func:`_decade_maxima`)."""
    cycle = ds["cycle"].values
    ivp_label = f"{ds.attrs['ivp_label']}, largest sampled error per decade"
    # below a few ulps an error is rounding noise, whose last bits vary with the CPU's kernels: drawn at the
    # band's edge, so that no such bit changes the figure
    t = float(ds["fixed_point_period"]) * cycle.astype(float)
    floors = {"drift": ROUNDING_ULPS * np.spacing(t), "error_velocity": np.full(cycle.shape, ROUNDING_ULPS * EPS)}
    with style():
        fig, (ax_t, ax_v) = plt.subplots(1, 2, figsize=(8.4, 3.8), sharex=True, layout="constrained")
        for ax, key in ((ax_t, "drift"), (ax_v, "error_velocity")):
            ax.fill_between(cycle, ERROR_FLOOR, floors[key], color=NO_CYCLE, lw=0,
                            label="rounding level (errors below it drawn on its edge)")
            exact = np.abs(ds[f"{key}_exact"].values)
            ax.loglog(cycle, np.maximum(exact, floors[key]), color=INK, lw=1.2, marker=".", ms=3, label="exact solver")
            xs, ys = _decade_maxima(cycle, ds[f"{key}_ivp"].values, floors[key])
            ax.loglog(xs, ys, color=ACCENT, lw=1.6, label=ivp_label)
        ax_t.set_ylabel(f"|impact time − reference| ({unit('impact_time')})")
        ax_t.set_title("phase error of the impact at a1")
        ax_v.set_ylabel("Relative error")
        ax_v.set_title("velocity before impact")
        for ax in (ax_t, ax_v):
            ax.set_xlabel("Number of cycles")
        case = f"{quantity_value('F', float(ds['F']))}, {release(ds)}"
        fig.suptitle(f"Long run, {case}: errors against the 50-digit reference\n"
                     f"grey band: rounding level, {ROUNDING_ULPS} ulps of the impact time t (left) and "
                     f"{ROUNDING_ULPS} \u03b5 = {ROUNDING_ULPS * EPS:.1e} (right); an error below it is drawn on its "
                     "edge\n"
                     "the integrator's staircase: its largest error at the sampled cycles of 1-10, 11-100, ..., "
                     "rounded up to 1, 2 or 5 times a power of ten",
                     fontsize=8.5)
        legend_below(fig, (ax_t, ax_v), ncols=3)
        finish(fig, [])
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
    completed = meanings.index(Status.COMPLETED.value)
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
            ax.set_xlabel(axis_label("b"))
            ax.grid(False)  # grid lines over a map read as cell borders
        axes[0].set_ylabel(axis_label("F"))
        axes[0].set_title("Multiplier measured from the simulated return map")
        axes[1].set_title("Distance from Eq. (21)")
        constants = ", ".join(quantity_value(k, float(ds[k])) for k in ("M", "K", "a1", "a2", "a3", "a4") if k in ds)
        fig.suptitle(f"Stability and existence map over (b, F), Sec. 3.4 and Eq. (21) of the paper\n{constants}",
                     fontsize=8.5)
        if cells is not None:
            handle = Patch(facecolor=NO_CYCLE, edgecolor=GUIDE, hatch="////", lw=0, label=label)
            fig.legend(handles=[handle], loc="outside lower center")
        finish(fig, [])
    return fig


def escapement_error(ds: xr.Dataset):
    """The limit cycle's rate against its amplitude for each impulse zone, and its two parts: the
    impacts' phase jumps dT1 and the impulse zones' dT2 (Airy's escapement error)."""
    names = [str(n) for n in ds["zone_name"].values]
    sign = "\n> 0: gains (runs fast), < 0: loses"
    panels = (("rate", f"Rate (s/day){sign}", "rate: impacts and impulse"),
              ("rate_impacts", f"Rate from the impacts, dT1 (s/day){sign}", "impacts' phase jumps, Eq. (24)"),
              ("rate_zones", f"Rate from the impulse, dT2 (s/day){sign}", "impulse zones, Eq. (25)"))
    with style():
        fig, axes = plt.subplots(1, 3, figsize=(10.2, 3.9), sharex=True, layout="constrained")
        for i, name in enumerate(names):
            a1, a2 = float(ds["zone_a1"][i]), float(ds["zone_a2"][i])
            label = f"{name}: impact at {quantity_value('a1', a1)}, impulse to {quantity_value('a2', a2)}"
            for ax, (variable, _, _) in zip(axes, panels):
                ax.plot(ds["amplitude"][i], ds[variable][i], marker="o", ms=2.5, lw=1.1, color=SERIES[i % 4],
                        label=label)
        for ax, (_, ylabel, title) in zip(axes, panels):
            ax.axhline(0.0, color=GUIDE, lw=0.6, ls=":")
            ax.set_xlabel(f"Amplitude of the limit cycle ({unit('largest_displacement')})")
            ax.set_ylabel(ylabel)
            ax.set_title(title)
        model = ", ".join(quantity_value(k, float(ds[k])) for k in ("M", "K", "b"))
        fig.suptitle(
            "Escapement error (beyond the paper): rate of a clock counting 2\u03c0/\u03c9 per swing, against "
            "amplitude; a positive rate means the clock gains (runs fast)\n"
            f"{model}; F from {float(ds['F'][0]):g} to {float(ds['F'][-1]):g} {unit('F')}; the second half cycle "
            f"mirrors the first; exact solver, Eqs. (24)-(25) corrected agree to "
            f"{float(ds['max_period_difference']):.0e}",
            fontsize=8.5)
        legend_below(fig, axes, ncols=2, fontsize=7.5)
        finish(fig, [])
    return fig


#: fill of the cells where the run reached a limit cycle, and of those that neither converged nor stopped
LIMIT_CYCLE = "#cfe0f1"
UNSETTLED = "#f5cba7"
#: the impact positions' symbols, as the axis labels write them
A1, A2, A3, A4 = "a\u2081", "a\u2082", "a\u2083", "a\u2084"


def existence_map(ds: xr.Dataset):
    """Where the limit cycle of an asymmetric escapement exists over (a3, F), from simulation, with the
    closed-form forces F* and F*' below which the map (16), read at a1 or at a3, has no fixed point."""
    a3, F = ds["a3"].values, ds["F"].values
    outcome = ds["outcome"].values.T
    meanings = ds["outcome"].attrs["flag_meanings"].split()
    cycle = ds["converged"].values.T.astype(bool)
    stopped = outcome == meanings.index(Status.STOPPED.value)
    x_edges, y_edges = _cell_edges(a3), _cell_edges(F) * 1e3
    cycles = int(ds["n_cycles"])
    regions = (
        (cycle, dict(facecolor=LIMIT_CYCLE, edgecolor="none"),
         f"limit cycle: all {cycles} cycles completed, the last two velocities at {A1} within "
         f"{float(ds['tolerance']):.0e} (relative)"),
        (stopped & ~cycle, dict(facecolor=NO_CYCLE, edgecolor=GUIDE, hatch="////", lw=0),
         "no limit cycle: the escapement stops (a swing ends short of the next impact position)"),
        (~cycle & ~stopped, dict(facecolor=UNSETTLED, edgecolor=ACCENT, hatch="xx", lw=0),
         "neither: another outcome, or not settled within the cycles given"),
    )
    with style():
        fig, ax = plt.subplots(figsize=(7.6, 6.0), layout="constrained")
        handles = []
        for mask, look, label in regions:
            cells = _cells_path(mask, x_edges, y_edges)
            if cells is not None:
                ax.add_patch(PathPatch(cells, **look))
                handles.append(Patch(**look, label=label))
        lines = (("threshold", ACCENT, "-",
                  f"F*: C = 0, the map (16) read at the impact at {A1} (below it the swing falls short of {A1})"),
                 ("threshold_mirror", INK, "--",
                  f"F*': the same map read at the impact at {A3}, F* of the mirror image "
                  f"(below it the swing falls short of {A3})"))
        for name, colour, ls, label in lines:
            handles.append(ax.plot(a3, ds[name].values * 1e3, color=colour, ls=ls, lw=1.6, label=label)[0])
        symmetric = -float(ds["a1"])
        if x_edges[0] <= symmetric <= x_edges[-1]:
            handles.append(ax.axvline(symmetric, color=GUIDE, lw=0.8, ls=":",
                                      label=f"{A3} = \u2212{A1}: F* = F*' = 0, a limit cycle for every F > 0"))
        ax.set_xlim(x_edges[0], x_edges[-1])
        ax.set_ylim(y_edges[0], y_edges[-1])
        ax.set_xlabel(axis_label("a3"))
        ax.set_ylabel(axis_label("F").replace("(N)", "(mN)"))
        ax.grid(False)  # grid lines over a map read as cell borders
        constants = ", ".join(quantity_value(k, float(ds[k])) for k in ("M", "K", "b", "a1", "a2", "a4"))
        fig.suptitle(
            f"Existence of the limit cycle without {A1} = \u2212{A3}, {A2} = \u2212{A4} (Sec. 5 of the paper), exact "
            f"solver (vectorised ensemble)\n{constants}\neach cell {release(ds)} and run for {cycles} cycles; "
            f"a limit cycle needs F > max(F*, F*'):\nF* = (2b \u2212 b\u00b2) K ({A1}\u00b2 \u2212 {A3}\u00b2) / "
            f"(2 [(1 \u2212 b)\u00b2 ({A2} \u2212 {A1}) + ({A3} \u2212 {A4})]), F*' the same with "
            f"({A1}, {A2}, {A3}, {A4}) \u2192 (\u2212{A3}, \u2212{A4}, \u2212{A1}, \u2212{A2})",
            fontsize=8.5)
        fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=7.5)
        finish(fig, [])
    return fig
