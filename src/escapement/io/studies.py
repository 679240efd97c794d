"""Datasets of the studies beyond the paper's figures: the escapement error (rate against amplitude)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..model.parameters import Parameters
from ..studies.escapement_error import SECONDS_PER_DAY, rate_against_amplitude
from .dataset import MODEL_INPUT, QUALITY, assemble, global_attributes, parameter_variables, scalar_variable

__all__ = ["ESCAPEMENT_ERROR_VARIABLES", "escapement_error_scene"]

#: name: (field of escapement.studies.escapement_error.LimitCycleRate, units, long name)
ESCAPEMENT_ERROR_VARIABLES = {
    "amplitude": ("amplitude", "m", "amplitude of the limit cycle (largest displacement)"),
    "velocity": ("velocity", "m s-1", "velocity before the impact at a1 on the limit cycle (fixed point of the map (16))"),
    "period": ("period", "s", "period of the limit cycle, exact solver"),
    "period_formula": ("period_formula", "s", "2 pi / omega + dT1 + dT2 by the corrected Eqs. (24)-(25)"),
    "rate": ("rate", "s day-1", "rate of a clock counting 2 pi / omega per swing: seconds gained per day"),
    "rate_impacts": ("rate_impacts", "s day-1", "part of the rate due to the impacts' phase jumps dT1, Eq. (24)"),
    "rate_zones": ("rate_zones", "s day-1", "part of the rate due to the impulse zones dT2, Eq. (25)"),
}


def escapement_error_scene(base: Parameters, forces: Sequence[float], zones: Mapping[str, Sequence[float]]
                           ) -> xr.Dataset:
    """The limit cycle's rate for every force of ``forces`` (N) and every impulse zone of ``zones``
    (name: ``[a1, a2]`` of the first half cycle, m; the second half cycle's is its mirror image,
    ``a3 = -a1``, ``a4 = -a2``); the rest of the model is ``base``."""
    names = list(zones)
    forces = np.asarray(forces, dtype=float)
    values = {name: np.empty((len(names), len(forces))) for name in ESCAPEMENT_ERROR_VARIABLES}
    for i, zone in enumerate(names):
        a1, a2 = (float(a) for a in zones[zone])
        p = Parameters(**{**base.as_dict(), "a1": a1, "a2": a2, "a3": -a1, "a4": -a2})
        for j, cycle in enumerate(rate_against_amplitude(p, forces)):
            for name, (field, *_) in ESCAPEMENT_ERROR_VARIABLES.items():
                values[name][i, j] = getattr(cycle, field)
    coords = {
        "zone": ("zone", np.arange(len(names), dtype=np.int32), {"long_name": "impulse zone number", "units": "1"}),
        "F": ("F", forces, {"long_name": "force of the escapement over an impulse zone", "units": "N"}),
    }
    variables = {
        name: xr.DataArray(values[name], dims=("zone", "F"), coords=coords, attrs={"units": u, "long_name": ln})
        for name, (_, u, ln) in ESCAPEMENT_ERROR_VARIABLES.items()
    }
    variables["zone_name"] = xr.DataArray(np.array(names, dtype=object), dims="zone", coords={"zone": coords["zone"]},
                                          attrs={"long_name": "name of the impulse zone",
                                                 "coverage_content_type": MODEL_INPUT})
    for end in ("a1", "a2"):
        variables[f"zone_{end}"] = xr.DataArray(
            np.array([float(zones[z][0 if end == "a1" else 1]) for z in names]), dims="zone",
            coords={"zone": coords["zone"]},
            attrs={"units": "m", "coverage_content_type": MODEL_INPUT,
                   "long_name": "impact position a1 of the first half cycle" if end == "a1"
                   else "end a2 of the first impulse zone"},
        )
    variables["max_period_difference"] = scalar_variable(
        float(np.max(np.abs(values["period_formula"] - values["period"]) / values["period"])), "1",
        "largest relative difference between the corrected Eqs. (24)-(25) and the exact solver's period", QUALITY,
    )
    variables["seconds_per_day"] = scalar_variable(SECONDS_PER_DAY, "s day-1", "seconds in a day", MODEL_INPUT)
    model = {k: v for k, v in base.as_dict().items() if k not in ("F", "a1", "a2", "a3", "a4")}
    variables.update(parameter_variables(model))
    summary = (
        "This file holds the escapement error of the limit cycle: for each impulse zone (the first half "
        "cycle's impact position a1 and zone end a2; the second half cycle mirrors them) and each force F, "
        "the limit cycle's amplitude, its period measured by the exact solver from the fixed point of the "
        "map (16), the period by the corrected Eqs. (24)-(25), and the rate of a clock counting the natural "
        "period per swing, split into the impacts' part dT1 and the impulse zones' part dT2."
    )
    attrs = global_attributes("Escapement error of the escapement model: rate against amplitude",
                              "escapement_error", summary, solver="exact")
    return assemble(variables, attrs)
