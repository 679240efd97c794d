"""The axis claims: each printed panel of Figs. 3-5 against the outputs autoscaled with the printed tick step; the
readings the paper leaves open were fitted to these axes, so a match is only consistent.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import xarray as xr

from ..paper.printed_axes import FIG5_PANEL_K, limits_match, panel
from .evidence import Evidence, Verdict, check, fig3_scenes, fig4_scene, fmt


def _limits(lo: float, hi: float) -> str:
    return f"[{fmt(lo, 6)}, {fmt(hi, 6)}]"


def panel_scenes(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The output that holds the printed panel of ``args: {figure, panel}``."""
    figure, name = str(claim["args"]["figure"]), str(claim["args"]["panel"])
    if figure == "3":
        return fig3_scenes({"args": {"case": name.split("/")[0]}}, ev)
    if figure == "4":
        return fig4_scene(claim, ev)
    return {f"Fig. 5 (K = {label})": ds for label, ds in ev.fig5.items()
            if math.isclose(float(ds["K"]), FIG5_PANEL_K[name], rel_tol=1e-12)}


@check(scenes=panel_scenes, args=("figure", "panel"),
       fitted="the readings of the paper's open choices, fitted to the printed axes")
def printed_axes(claim, ev: Evidence) -> Verdict:
    """Some candidate reading of the grid gives every printed limit of the panel; the best is named, with its ties."""
    figure, name = str(claim["args"]["figure"]), str(claim["args"]["panel"])
    printed = panel(figure, name)
    if not (scenes := panel_scenes(claim, ev)):
        raise ValueError(f"no Fig. 5 output has the spring constant of panel ({name}), K = {FIG5_PANEL_K[name]:g} N/m")
    (ds,) = scenes.values()
    if (figure, name) not in ev.axes:
        raise ValueError(f"the evidence holds no autoscaled limits for Fig. {figure} panel {name!r}")
    if (figure, name) not in ev.readings:
        raise ValueError(f"the evidence holds no scored candidate readings for Fig. {figure} panel {name!r}")
    limits, candidates = ev.axes[(figure, name)], ev.readings[(figure, name)]
    scored = {axis_name: axis for axis_name, axis in printed.axes.items() if axis.scored}
    out_of = 2 * len(scored)
    if candidates.out_of != out_of:
        raise ValueError(f"the candidate readings of Fig. {figure} panel {name!r} are scored out of "
                         f"{candidates.out_of} limits; the panel has {out_of}")
    matched = sum(limits_match(*limits[key], axis.low, axis.high, axis.step) for key, axis in scored.items())
    best, groups = candidates.tied()
    named = ", ".join("[" + " = ".join(group) + "]" for group in groups)  # names may hold "; "
    ties = (f"by one reading {named}" if len(groups) == 1 else f"a tie of {len(groups)} readings that plot different "
            f"values, so the reading is undetermined: {named}")
    # the reading of the paper's unstated choices that the output was made with
    reading = ", ".join([f"F = {fmt(float(ds['F']), 4)} N", f"K = {fmt(float(ds['K']), 4)} N/m",
                         f"released from rest at x0 = {fmt(float(ds['x0']), 4)} m"]
                        + ([f"amplitude: {ds.attrs['amplitude_variable']}"] if figure == "3" else []))
    default = (f"; with the plotting program's own tick step the best is {max(candidates.default_scores.values())} "
               f"of {out_of}" if candidates.default_scores else "")
    return Verdict(
        "; ".join(f"{axis.label}: {_limits(*limits[axis_name])}" for axis_name, axis in scored.items())
        + f" ({matched} of {out_of} printed limits); best of the {len(candidates.scores)} candidate readings: {best} "
        f"of {out_of}, {ties}", best == out_of,
        note=(f"the output ({reading}) autoscaled with the printed tick steps imposed "
              f"({', '.join(fmt(axis.step, 4) for axis in scored.values())}), limits rounded out to the ticks, no "
              f"margin{default}; the readings were chosen by fitting these axes, so a match shows consistency only"),
        paper_value="; ".join(f"{axis.label}: {_limits(axis.low, axis.high)}" for axis in scored.values()))
