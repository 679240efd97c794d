"""The axis claims: each printed panel of Figs. 3-5 against the pipeline's own outputs.

A printed axis is evidence of what the paper plotted: with limits rounded out to the ticks (the
default of the software the figures appear to be drawn in), the outermost tick labels are the
rounded extent of the data. So an axis claim is reproduced only when the pipeline's output,
autoscaled the same way with the printed tick step, gives exactly the printed limits, not when
its data merely lie inside them. The autoscaled limits are computed by the workflow (with
matplotlib, :func:`escapement.pipeline.readings.scene_axes`) and given to the check as
``Evidence.axes``; the printed limits come from :mod:`escapement.paper.printed_axes`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import xarray as xr

from .checks import NOT, PARTIAL, REPRODUCED, Evidence, Verdict, check, fig3_labelled, fmt
from .printed_axes import CYCLES, FIG5_PANEL_K, Panel, panel

__all__ = ["panel_scenes", "printed_axes"]


def _limits(lo: float, hi: float) -> str:
    return f"[{fmt(lo, 6)}, {fmt(hi, 6)}]"


def _fig5_dataset(ev: Evidence, name: str) -> tuple[str, xr.Dataset] | None:
    for label, ds in ev.fig5.items():
        if math.isclose(float(ds["K"]), FIG5_PANEL_K[name], rel_tol=1e-12):
            return label, ds
    return None


def panel_scenes(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The output that holds the printed panel of ``args: {figure, panel}``."""
    figure, name = str(claim["args"]["figure"]), str(claim["args"]["panel"])
    if figure == "3":
        case = name.split("/")[0]
        return {f"Fig. 3 case {case}": fig3_labelled(ev, case)}
    if figure == "4":
        return {"Fig. 4": ev.fig4}
    found = _fig5_dataset(ev, name)
    return {} if found is None else {f"Fig. 5 (K = {found[0]})": found[1]}


def _reading(figure: str, ds: xr.Dataset) -> str:
    """The reading of the paper's unstated choices that the output was made with."""
    parts = [f"F = {fmt(float(ds['F']), 4)} N", f"K = {fmt(float(ds['K']), 4)} N/m",
             f"released from rest at x0 = {fmt(float(ds['x0']), 4)} m"]
    if figure == "3" and "definition" in ds["amplitude"].attrs:
        parts.append(f"amplitude: {ds['amplitude'].attrs['definition']}")
    return ", ".join(parts)


@check("printed_axes", scenes=panel_scenes, args=("figure", "panel"))
def printed_axes(claim, ev: Evidence) -> Verdict:
    """Reproduced when every scored axis of the panel autoscales to the printed limits, partially
    when some limits of its quantities do (not only the cycle axis), not reproduced otherwise."""
    figure, name = str(claim["args"]["figure"]), str(claim["args"]["panel"])
    printed: Panel = panel(figure, name)
    scenes = panel_scenes(claim, ev)
    if not scenes:
        raise ValueError(f"no Fig. 5 output has the spring constant of panel ({name}), K = {FIG5_PANEL_K[name]:g} N/m")
    (ds,) = scenes.values()
    if (figure, name) not in ev.axes:
        raise ValueError(f"the evidence holds no autoscaled limits for Fig. {figure} panel {name!r}")
    limits = ev.axes[(figure, name)]
    scored = {axis_name: axis for axis_name, axis in printed.axes.items() if axis.scored}
    matched = sum(axis.matches(*limits[axis_name]) for axis_name, axis in scored.items())
    # the cycle axes follow from the number of cycles plotted: they alone cannot make a panel partly reproduced
    of_quantities = sum(axis.matches(*limits[axis_name]) for axis_name, axis in scored.items()
                        if axis.label != CYCLES)
    out_of = 2 * len(scored)
    status = REPRODUCED if matched == out_of else PARTIAL if of_quantities else NOT
    return Verdict(
        "; ".join(f"{axis.label}: {_limits(*limits[axis_name])}" for axis_name, axis in scored.items())
        + f" ({matched} of {out_of} printed limits)",
        status,
        note=(
            f"the output ({_reading(figure, ds)}) autoscaled with the printed tick steps "
            f"({', '.join(fmt(axis.step, 4) for axis in scored.values())}), limits rounded out to the ticks"
        ),
        paper_value="; ".join(f"{axis.label}: {_limits(axis.low, axis.high)}" for axis in scored.values()),
    )
