"""The runs behind single claims of the register, beside the table of the ``checks`` dataset
(:func:`escapement.scenes.runs.checks`): each Fig. 3 case's first swing from either side of its release, the
slope of the return map of a Fig. 3 case at given speeds, and the runs from the section at the converged speed
and beside it. Each group of variables has its own dimension; the checks find in it the run their ``args`` in
the register name (:mod:`escapement.paper`), and never run one.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..solvers.exact import solve_exact
from ..studies.poincare import RELATIVE_STEP, return_map
from .cf import MODEL_INPUT, MODEL_RESULT
from .settings import positive_int

__all__ = ["probe_variables"]


def _variable(values, dims, units: str | None, long_name: str, content: str = MODEL_RESULT, **attrs) -> xr.DataArray:
    described = {"long_name": long_name, "coverage_content_type": content, **attrs}
    if units is not None:
        described["units"] = units
    return xr.DataArray(np.array(values, dtype=None if units is not None else object), dims=dims, attrs=described)


def _first_swings(runs: list[Mapping]) -> dict[str, xr.DataArray]:
    """Each run (a Fig. 3 case's parameters, its ``label`` and a release ``x0``) released from rest for one cycle:
    the velocity before its first impact at a1."""
    first = [float(solve_exact(Parameters.from_mapping(r), float(r["x0"]), n_cycles=1, record_trajectory=False)
                   .cycles.velocity_before_impact[0]) for r in runs]
    dims = "first_swing"
    return {"first_swing_case": _variable([r["label"] for r in runs], dims, None, "Fig. 3 case of the run",
                                          MODEL_INPUT),
            "first_swing_x0": _variable([float(r["x0"]) for r in runs], dims, "m", "released from rest at",
                                        MODEL_INPUT),
            "first_swing_velocity": _variable(first, dims, "m s-1", "velocity before the first impact at a1")}


def _return_map(spec: Mapping) -> dict[str, xr.DataArray]:
    """The slope of the return map of the case ``spec`` (parameters and ``label``) at each of its ``velocities``:
    central differences of one simulated cycle from the section."""
    p, slopes = Parameters.from_mapping(spec), []
    for v in spec["velocities"]:
        lo_in, lo_out = return_map(p, float(v) * (1 - RELATIVE_STEP))
        hi_in, hi_out = return_map(p, float(v) * (1 + RELATIVE_STEP))
        slopes.append((hi_out - lo_out) / (hi_in - lo_in))
    speeds = _variable([float(v) for v in spec["velocities"]], "map_velocity", "m s-1",
                       "velocity before the impact at a1 where the return map's slope is measured", MODEL_INPUT)
    return {"map_velocity": speeds, "map_slope": _variable(
        slopes, "map_velocity", "1", f"slope of the simulated return map of Fig. 3 case {spec['label']}, by "
        "central differences", case=str(spec["label"]), relative_step=RELATIVE_STEP)}


def _phase_shift(spec: Mapping) -> dict[str, xr.DataArray]:
    """The case ``spec`` (parameters, ``label``, release ``x0``) run ``n_release`` cycles as Fig. 3 runs it, then
    from the section at its last speed before impact and at ``1 + perturbation`` times it over ``n_cycles``: the
    times of the impacts at a1 and the last speed before impact of each run."""
    p, n_cycles = Parameters.from_mapping(spec), positive_int("n_cycles", spec["n_cycles"], 100_000)
    release = solve_exact(p, float(spec["x0"]), n_cycles=positive_int("n_release", spec["n_release"], 100_000),
                          record_trajectory=False)
    star = float(release.cycles.velocity_before_impact[-1])
    perturbations = [0.0, *(float(d) for d in spec["perturbations"])]
    runs = [solve_exact(p, p.a1, star * (1 + d), n_cycles=n_cycles, record_trajectory=False) for d in perturbations]
    times = [r.events.t[r.events.kind == int(EventKind.IMPACT_A1)] for r in runs]
    table = np.full((len(runs), max(len(t) for t in times)), np.nan)
    for row, t in zip(table, times):
        row[:len(t)] = t
    dims = ("perturbation", "impact")
    return {
        "perturbation": _variable(perturbations, "perturbation", "1", "relative perturbation of the speed at the "
                                  "section, from the converged speed", MODEL_INPUT),
        "perturbed_impact_time": _variable(table, dims, "s", f"time of each impact at a1 of Fig. 3 case "
                                           f"{spec['label']} started at the section (NaN after the last)",
                                           case=str(spec["label"]), n_cycles=n_cycles),
        "perturbed_speed": _variable([float(r.cycles.velocity_before_impact[-1]) for r in runs], "perturbation",
                                     "m s-1", "velocity before the last impact at a1 of the run from the section",
                                     converged_speed=star),
    }


def probe_variables(probes: Mapping) -> dict[str, xr.DataArray]:
    """The variables of the runs ``probes`` names: ``first_swings`` (a list of runs), ``return_map`` and
    ``phase_shift`` (one case each), whichever it holds."""
    found: dict[str, xr.DataArray] = {}
    if probes.get("first_swings"):
        found.update(_first_swings(list(probes["first_swings"])))
    if "return_map" in probes:
        found.update(_return_map(probes["return_map"]))
    if "phase_shift" in probes:
        found.update(_phase_shift(probes["phase_shift"]))
    return found
