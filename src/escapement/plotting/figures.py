"""The paper's Figs. 3-5, drawn from the netCDF datasets (never from the solver)."""

from __future__ import annotations

import math
import textwrap

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .style import ACCENT, GUIDE, INK, MUTED, style

__all__ = ["fig3", "fig4", "fig5"]


def _broken(t: np.ndarray, y: np.ndarray, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Insert NaN at each break time, so that a line is not drawn across a jump."""
    idx = np.searchsorted(t, breaks)
    return np.insert(t.astype(float), idx, np.nan), np.insert(y.astype(float), idx, np.nan)


def _outcome_note(ax, ds: xr.Dataset) -> None:
    if ds.attrs.get("outcome", "completed") != "completed":
        text = "\n".join(textwrap.wrap(f"{ds.attrs['outcome']}: {ds.attrs['outcome_message']}", 48))
        ax.text(0.02, 0.02, text, transform=ax.transAxes, fontsize=6.5, va="bottom", color=ACCENT,
                bbox={"facecolor": "white", "edgecolor": ACCENT, "linewidth": 0.6})


def _case_title(ds: xr.Dataset, label: str) -> str:
    return f"({label}) F = {ds.attrs['F']:g} N, x(0) = {ds.attrs['x0']:g} m"


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
            omega = math.sqrt(ds.attrs["K"] / ds.attrs["M"])
            for row, (name, ylabel) in enumerate(rows):
                ax = axes[row, col]
                ax.plot(ds["cycle"], ds[name], marker="o", markersize=2.5, color=INK, label="exact solution")
                if name == "velocity_before_impact" and "fixed_point_19" in ds.attrs:
                    ax.axhline(ds.attrs["fixed_point_19"], ls="--", lw=0.8, color=GUIDE, label="fixed point, Eq. (19)")
                if name == "period":
                    ax.axhline(2 * math.pi / omega, ls=":", lw=0.9, color=GUIDE, label="2\u03c0/\u03c9 = 6.2832 s (paper)")
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
    v_lo, v_hi = ds.attrs["velocity_window"]
    a_lo, a_hi = ds.attrs["acceleration_window"]
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
        fig.suptitle(_case_title(ds, "b").replace("(b) ", "") + f", K = {ds.attrs['K']:g} N/m", fontsize=9)
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
            ax.set_title(f"({letter}) K = {label} N/m")
            _outcome_note(ax, ds)
        axes[0, 0].legend(loc="upper left")
        fig.tight_layout()
    return fig
