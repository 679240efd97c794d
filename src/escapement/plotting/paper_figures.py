"""The paper's Figs. 3-5, drawn from the netCDF datasets (never from the solver)."""

from __future__ import annotations

import math
import textwrap

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..model.quantities import INITIAL_STATE, PARAMETERS
from .style import ACCENT, GUIDE, INK, MUTED, style

__all__ = ["fig3", "fig4", "fig5", "long_run", "stability_map", "work_precision"]


def _broken(t: np.ndarray, y: np.ndarray, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Insert NaN at each break time, so that a line is not drawn across a jump."""
    idx = np.searchsorted(t, breaks)
    return np.insert(t.astype(float), idx, np.nan), np.insert(y.astype(float), idx, np.nan)


def _outcome_note(ax, ds: xr.Dataset) -> None:
    if ds.attrs.get("outcome", "completed") != "completed":
        text = "\n".join(textwrap.wrap(f"{ds.attrs['outcome']}: {ds.attrs['outcome_message']}", 48))
        ax.text(0.02, 0.02, text, transform=ax.transAxes, fontsize=6.5, va="bottom", color=ACCENT,
                bbox={"facecolor": "white", "edgecolor": ACCENT, "linewidth": 0.6})


def _value(name: str, value: float) -> str:
    """``F = 0.5 N``: the quantity's symbol, the value and its units, from the quantities table."""
    q = PARAMETERS[name] if name in PARAMETERS else INITIAL_STATE[name]
    return f"{q.symbol} = {value:g} {q.unit_label}"


def _case_title(ds: xr.Dataset, label: str) -> str:
    return f"({label}) {_value('F', float(ds['F']))}, {_value('x0', float(ds['x0']))}"


def natural_period(ds: xr.Dataset) -> float:
    """2 pi / omega with omega = sqrt(K/M), from the dataset's own K and M (s)."""
    return 2 * math.pi / math.sqrt(float(ds["K"]) / float(ds["M"]))


def fig3(cases: dict[str, xr.Dataset]):
    """Velocity before impact, period and amplitude against the cycle, one column per case."""
    rows = [
        ("velocity_before_impact", "Velocity before impact (m/s)"),
        ("period", "Period (s)"),
        ("amplitude", "Amplitude of oscillation (m)"),
    ]
    with style():
        fig, axes = plt.subplots(3, len(cases), figsize=(3.4 * len(cases), 7.2), squeeze=False, sharex="col")
        for col, (label, ds) in enumerate(cases.items()):
            period = natural_period(ds)
            for row, (name, ylabel) in enumerate(rows):
                ax = axes[row, col]
                ax.plot(ds["cycle"], ds[name], marker="o", markersize=2.5, color=INK, label="exact solution")
                if name == "velocity_before_impact" and "fixed_point_19" in ds:
                    ax.axhline(float(ds["fixed_point_19"]), ls="--", lw=0.8, color=GUIDE, label="fixed point, Eq. (19)")
                if name == "period":
                    ax.axhline(period, ls=":", lw=0.9, color=GUIDE, label=f"2\u03c0/\u03c9 = {period:.4f} s (paper)")
                ax.set_ylabel(ylabel)
                if row == 2:
                    ax.set_xlabel("Number of cycles")
                if row < 2:
                    ax.legend(loc="best")
            axes[0, col].set_title(_case_title(ds, label))
            _outcome_note(axes[0, col], ds)
        fig.tight_layout()
    return fig


def fig4(ds: xr.Dataset):
    """Velocity and acceleration around the impacts; jumps drawn as jumps, impulses marked."""
    t = ds["t"].values
    impacts = ds["impact_time"].values
    switches = ds["event_time"].values
    v_lo, v_hi = ds["velocity_window"].values
    a_lo, a_hi = ds["acceleration_window"].values
    with style():
        fig, (ax_v, ax_a) = plt.subplots(1, 2, figsize=(7.2, 3.0))
        sel = (t >= v_lo) & (t <= v_hi)
        ax_v.plot(*_broken(t[sel], ds["velocity"].values[sel], impacts), color=INK, label="velocity")
        ax_v.plot(impacts, ds["velocity_before"], "o", mfc="white", color=ACCENT, label="before impact")
        ax_v.plot(impacts, ds["velocity_after"], "o", color=ACCENT, label="after impact")
        ax_v.set_xlim(v_lo, v_hi)
        ax_v.set_xlabel("Time (s)")
        ax_v.set_ylabel("Velocity (m/s)")
        ax_v.legend(loc="lower left")

        sel = (t >= a_lo) & (t <= a_hi)
        ax_a.plot(*_broken(t[sel], ds["acceleration"].values[sel], switches), color=INK, label="acceleration between events")
        span = np.nanmax(np.abs(ds["acceleration"].values[sel])) if sel.any() else 1.0
        inside = (impacts >= a_lo) & (impacts <= a_hi)
        for ti, j, e in zip(impacts[inside], ds["impulse"].values[inside], ds["energy_dissipated"].values[inside]):
            ax_a.annotate(
                "", xy=(ti, 0.8 * span * np.sign(j)), xytext=(ti, 0.0),
                arrowprops={"arrowstyle": "-|>", "color": ACCENT, "lw": 1.4},
            )
            ax_a.text(ti, 0.85 * span * np.sign(j), f" impulse {j:+.4f} N s\n dissipated {e:.4f} J",
                      fontsize=6.5, color=ACCENT, va="bottom" if j > 0 else "top")
        ax_a.plot([], [], color=ACCENT, lw=1.4, label="impulse M \u0394v (Dirac, not to scale)")
        ax_a.set_xlim(a_lo, a_hi)
        ax_a.set_xlabel("Time (s)")
        ax_a.set_ylabel("Acceleration (m/s\u00b2)")
        ax_a.legend(loc="upper left")
        fig.suptitle(f"{_value('F', float(ds['F']))}, {_value('x0', float(ds['x0']))}, {_value('K', float(ds['K']))}",
                     fontsize=9)
        _outcome_note(ax_v, ds)
        fig.tight_layout()
    return fig


def fig5(panels: dict[str, xr.Dataset]):
    """Phase diagrams: the transient in light colour, the last cycle in dark, impacts as vertical jumps."""
    letters = "abcdefghij"
    with style():
        fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.1), squeeze=False)
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
                      label="impacts")
            ax.set_xlabel("Displacement (m)")
            ax.set_ylabel("Velocity (m/s)")
            ax.set_title(f"({letter}) {_value('K', float(ds['K']))}")
            _outcome_note(ax, ds)
        axes[0, 0].legend(loc="upper left")
        fig.tight_layout()
    return fig


#: errors below this are drawn at it on log axes (an exact zero has no logarithm)
ERROR_FLOOR = 1e-17
MARKERS = {"exact": "*", "map16": "P", "naive-RK4": "x", "RK45": "o", "DOP853": "s", "LSODA": "^", "Radau": "v",
           "CVODE-Adams": "D", "CVODE-BDF": "d"}


def work_precision(rows: list[dict]):
    """Relative error against wall time, one curve per method, for the velocity and the impact time."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(8.4, 3.6), sharex=True)
        colours = plt.get_cmap("tab10")
        for i, method in enumerate(methods):
            mine = [r for r in rows if r["method"] == method]
            wall = [float(r["wall_s"]) for r in mine]
            for ax, key in zip(axes, ("error_velocity", "error_time")):
                err = [max(float(r[key]), ERROR_FLOOR) for r in mine]
                ax.loglog(wall, err, marker=MARKERS.get(method, "o"), color=colours(i % 10), lw=1.0, ms=5,
                          label=method)
        for ax, title in zip(axes, ("velocity before impact, cycle 50", "impact time, cycle 50")):
            ax.set_xlabel("Wall time per run (s), median of repeats")
            ax.set_ylabel("Relative error")
            ax.set_title(title)
            ax.axhline(ERROR_FLOOR, color=GUIDE, lw=0.6, ls=":")
        axes[1].legend(loc="upper right", ncol=2, fontsize=6.5)
        fig.suptitle("Work-precision, Fig. 3 case (a): errors against 50 digits (exact zero drawn at 1e-17)",
                     fontsize=8.5)
        fig.tight_layout()
    return fig


def long_run(ds: xr.Dataset):
    """Phase error (impact time minus the 50-digit reference) and velocity error against the number of cycles."""
    cycle = ds["cycle"].values
    series = (("exact", INK, "exact solver"), ("ivp", ACCENT, ds.attrs["ivp_label"]))
    with style():
        fig, (ax_t, ax_v) = plt.subplots(1, 2, figsize=(8.4, 3.4), sharex=True)
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
        ax_t.legend(loc="upper left")
        fig.suptitle("Long run, Fig. 3 case (a): errors against the 50-digit reference", fontsize=8.5)
        fig.tight_layout()
    return fig


def stability_map(ds: xr.Dataset):
    """Measured multiplier over (b, F), its distance from (1 - b)**4, and where the regime ends."""
    from matplotlib.colors import LogNorm

    b, F = ds["b"].values, ds["F"].values
    mu = ds["multiplier"].values.T
    deviation = np.abs(ds["multiplier"].values - ds["multiplier_eq21"].values).T
    outcome = ds["outcome"].values.T
    meanings = ds["outcome"].attrs["flag_meanings"].split()
    completed = meanings.index("completed")
    with style():
        fig, axes = plt.subplots(1, 2, figsize=(8.4, 3.5), sharey=True)
        mesh = axes[0].pcolormesh(b, F, mu, shading="nearest", cmap="viridis", vmin=0, vmax=1)
        fig.colorbar(mesh, ax=axes[0], label="measured multiplier \u03bc\u2082")
        dev = np.where(deviation > 0, deviation, ERROR_FLOOR)
        mesh = axes[1].pcolormesh(b, F, dev, shading="nearest", cmap="magma", norm=LogNorm(vmin=1e-16, vmax=1e-8))
        fig.colorbar(mesh, ax=axes[1], label="|\u03bc\u2082 measured \u2212 (1 \u2212 b)\u2074|")
        for ax in axes:
            left = outcome != completed
            if left.any():
                ax.contourf(b, F, left.astype(float), levels=[0.5, 1.5], colors="none", hatches=["////"])
                names = sorted({meanings[c] for c in np.unique(outcome[left])})
                ax.text(0.98, 0.5, "\n".join(names).replace("_", " ") + "\n(Zeno: no cycle)", transform=ax.transAxes,
                        ha="right", va="center", fontsize=7, color=ACCENT,
                        bbox={"facecolor": "white", "edgecolor": ACCENT, "linewidth": 0.6})
            ax.set_xlabel("Impact coefficient b")
        axes[0].set_ylabel("Force F (N)")
        axes[0].set_title("Multiplier measured from the simulated return map")
        axes[1].set_title("Distance from Eq. (21)")
        fig.tight_layout()
    return fig
