"""The paper's Figs. 3-5, drawn from the netCDF datasets (never from the solver).

Each figure names the paper's figure it reproduces (the dataset's ``title``) and states the readings
it assumes where the paper is silent: the dataset's ``reading`` attribute if it has one, otherwise a
sentence composed from its parameters (F, K, x0, v0) and the definitions of its variables. Given
``axes`` (:mod:`escapement.plotting.panel_axes`), each printed panel is drawn with exactly the axes
its claim scores: the printed tick step, the limits given. ``caption`` adds what was imposed and
what the printed axes left undetermined. No label covers data (:mod:`escapement.plotting.labels`).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import xarray as xr

from .captions import (
    assumed_reading,
    axis_label,
    broken,
    initial_velocity,
    math_text,
    natural_period,
    outcome_note,
    paper_source,
    quantity_value,
    release,
    signed,
    unit,
    wrap,
)
from .labels import Label, finish, legend_below
from .panel_axes import PanelAxes, apply_printed_axes, fig5_panel_of
from .style import ACCENT, GUIDE, INK, MUTED, style

__all__ = ["fig3", "fig4", "fig5"]


def _heading(title: str, caption: str | None) -> str:
    """The suptitle: the dataset's title and the caption, with the datasets' plain-text formulas as mathtext."""
    return math_text(title if not caption else f"{title}\n{caption}")


def _printed(ax, axes: PanelAxes | None, figure: str, name: str | None) -> None:
    if axes and name is not None and (figure, name) in axes:
        apply_printed_axes(ax, figure, name, axes[(figure, name)])


def fig3(cases: dict[str, xr.Dataset], axes: PanelAxes | None = None, caption: str | None = None):
    """Velocity before impact, period and amplitude against the cycle, one column per case."""
    first = next(iter(cases.values()))
    amplitude = first.attrs["amplitude_variable"]
    rows = ("velocity_before_impact", "period", amplitude)
    panels = {"velocity_before_impact": "velocity", "period": "period", amplitude: "amplitude"}
    extra = 0.0 if not caption else 0.15 * (caption.count("\n") + 1)
    definitions = "\n".join(wrap(math_text(f"{name}: {first[name].attrs['long_name']}"), 100)
                             for name in ("period", amplitude) if "long_name" in first[name].attrs)
    notes = []
    with style():
        fig, grid = plt.subplots(3, len(cases), figsize=(3.4 * len(cases), 7.9 + extra), squeeze=False,
                                 layout="constrained")
        for col, (label, ds) in enumerate(cases.items()):
            period = natural_period(ds)
            for row, name in enumerate(rows):
                ax = grid[row, col]
                ax.plot(ds[ds[name].dims[0]], ds[name], marker="o", markersize=2.5, lw=1.0, color=INK, zorder=2,
                        label="exact solution, per cycle")
                # the guides are drawn over the points they are compared with, in colours of their own
                if name == "velocity_before_impact" and "fixed_point_19" in ds:
                    ax.axhline(float(ds["fixed_point_19"]), ls=(0, (5, 3)), lw=1.1, color=ACCENT, zorder=3,
                               label="fixed point of Eq. (19) as printed")
                if name == "period":
                    guide = ax.axhline(period, ls=":", lw=1.2, color=GUIDE, zorder=3,
                                       label=f"2\u03c0/\u03c9 = {period:.4f} s, the period the paper reports")
                ax.set_ylabel(axis_label(name))
                ax.set_xlabel("Number of cycles")
                _printed(ax, axes, "3", f"{label}/{panels[name]}")
                if name == "period" and not ax.get_ylim()[0] <= period <= ax.get_ylim()[1]:
                    guide.set_label(f"2\u03c0/\u03c9 = {period:.4f} s, the paper's period, below the axes")
            reading = assumed_reading(ds, f"{quantity_value('F', float(ds['F']))}, {release(ds)}")
            grid[0, col].set_title(f"({label}) {wrap(reading, 40)}")
            notes += outcome_note(grid[0, col], ds)
        fig.suptitle(_heading(f"{paper_source(first, 'Fig. 3')}\n{definitions}", caption), fontsize=8.5)
        legend_below(fig, grid, ncols=2)
        finish(fig, notes)
    return fig


def fig4(ds: xr.Dataset, axes: PanelAxes | None = None, caption: str | None = None):
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
        extra = 0.0 if not caption else 0.15 * (caption.count("\n") + 1)
        fig, (ax_v, ax_a) = plt.subplots(1, 2, figsize=(7.6, 3.9 + extra), layout="constrained")
        sel = (t >= v_lo) & (t <= v_hi)
        ax_v.plot(*broken(t[sel], ds["velocity"].values[sel], impacts), color=INK, label="velocity")
        ax_v.plot(impacts, before, "o", mfc="white", color=ACCENT, label="velocity just before an impact")
        ax_v.plot(impacts, after, "o", color=ACCENT, label="velocity just after an impact")
        ax_v.set_xlim(v_lo, v_hi)
        _printed(ax_v, axes, "4", "velocity")
        ax_v.set_xlabel(axis_label("t"))
        ax_v.set_ylabel(axis_label("velocity"))
        inside = (impacts >= v_lo) & (impacts <= v_hi)
        for ti, j, e, vb, va in zip(impacts[inside], impulse[inside], energy[inside], before[inside], after[inside]):
            text = f"impulse {signed(j, '+.4f')} {unit('impulse')}\ndissipated {e:.4f} {unit('energy_dissipated')}"
            labels.append(Label(ax_v, text, (ti, (vb + va) / 2), style={"fontsize": 6.5, "color": ACCENT}))

        sel = (t >= a_lo) & (t <= a_hi)
        ax_a.plot(*broken(t[sel], ds["acceleration"].values[sel], switches), color=INK,
                  label="acceleration between events")
        ax_a.set_xlim(a_lo, a_hi)
        _printed(ax_a, axes, "4", "acceleration")
        # a Dirac impulse has no height: its arrow spans most of the panel, pointing the way it acts,
        # inside the limits the smooth acceleration sets (which stay fixed)
        y_lo, y_hi = ax_a.get_ylim()
        ax_a.set_ylim(y_lo, y_hi)
        inside = (impacts >= a_lo) & (impacts <= a_hi)
        for ti, j in zip(impacts[inside], impulse[inside]):
            base, tip = (y_lo + 0.85 * (y_hi - y_lo), y_lo + 0.12 * (y_hi - y_lo))[:: 1 if j < 0 else -1]
            ax_a.annotate("", xy=(ti, tip), xytext=(ti, base), arrowprops={"arrowstyle": "-|>", "color": ACCENT,
                                                                          "lw": 1.4})
            labels.append(Label(ax_a, f"impulse {signed(j, '+.4f')} {unit('impulse')}", (ti, tip),
                                 style={"fontsize": 6.5, "color": ACCENT}))
        ax_a.plot([], [], color=ACCENT, lw=1.4, label="impulse M \u0394v at an impact (Dirac, not to scale)")
        ax_a.set_xlabel(axis_label("t"))
        ax_a.set_ylabel(axis_label("acceleration"))
        params = f"{quantity_value('F', float(ds['F']))}, {quantity_value('K', float(ds['K']))}, {release(ds)}"
        reading = assumed_reading(ds, f"case assumed (the paper does not say which it shows): {params}")
        fig.suptitle(_heading(f"{paper_source(ds, 'Fig. 4')}\n{wrap(reading, 110)}", caption), fontsize=8.5)
        legend_below(fig, (ax_v, ax_a), ncols=2)  # a column per panel
        finish(fig, labels + outcome_note(ax_v, ds))
    return fig


def fig5(panels: dict[str, xr.Dataset], axes: PanelAxes | None = None, caption: str | None = None):
    """Phase diagrams: the transient in light colour, the last cycle in dark, impacts as vertical jumps;
    each panel states the force and the release it assumes."""
    letters = "abcdefghij"
    notes = []
    with style():
        extra = 0.0 if not caption else 0.15 * (caption.count("\n") + 1)
        fig, grid = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.9 + extra), squeeze=False,
                                 layout="constrained")
        for ax, letter, (label, ds) in zip(grid[0], letters, panels.items()):
            t, x, v = ds["t"].values, ds["displacement"].values, ds["velocity"].values
            impacts = ds["impact_time"].values
            tb, xb = broken(t, x, impacts)
            _, vb = broken(t, v, impacts)
            ax.plot(xb, vb, color=MUTED, lw=0.7, label="transient")
            if ds.sizes.get("cycle", 0):
                start = ds["impact_time"].values[-1] - ds["period"].values[-1]
                last = tb >= start
                ax.plot(xb[last], vb[last], color=INK, lw=1.4, label="last cycle")
            ax.vlines(ds["impact_position"], ds["velocity_after"], ds["velocity_before"], color=ACCENT, lw=0.8,
                      label="impacts (velocity jumps)")
            ax.set_xlabel(axis_label("displacement"))
            ax.set_ylabel(axis_label("velocity"))
            _printed(ax, axes, "5", fig5_panel_of(ds))
            start = "from rest" if initial_velocity(ds) == 0 else quantity_value("v0", initial_velocity(ds))
            release = f"{quantity_value('F', float(ds['F']))}, {quantity_value('x0', float(ds['x0']))}, {start}"
            reading = assumed_reading(ds, release)
            ax.set_title(f"({letter}) {quantity_value('K', float(ds['K']))}\n{wrap(reading, 40)}")
            notes += outcome_note(ax, ds)
        first = next(iter(panels.values()))
        fig.suptitle(_heading(f"{paper_source(first, 'Fig. 5')}\nF and x(0) are not given by the paper: each panel "
                              "states those assumed", caption), fontsize=8.5)
        legend_below(fig, grid, ncols=3, order=("transient", "last cycle"))
        finish(fig, notes)
    return fig
