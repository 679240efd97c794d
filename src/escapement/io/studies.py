"""The datasets of the studies beyond the paper's figures: the escapement error (rate against
amplitude), made from the experiment's results (:mod:`escapement.experiments.escapement_error`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from .dataset import MODEL_INPUT, QUALITY, assemble, global_attributes, parameter_variables, scalar_variable

__all__ = ["ESCAPEMENT_ERROR_VARIABLES", "escapement_error_dataset"]

#: name (a field of escapement.studies.escapement_error.LimitCycleRate): (units, long name)
ESCAPEMENT_ERROR_VARIABLES = {
    "amplitude": ("m", "amplitude of the limit cycle (largest displacement)"),
    "velocity": ("m s-1", "velocity before the impact at a1 on the limit cycle (fixed point of the map (16))"),
    "period": ("s", "period of the limit cycle, exact solver"),
    "period_formula": ("s", "2 pi / omega + dT1 + dT2 by the corrected Eqs. (24)-(25)"),
    "rate": ("s day-1", "rate of a clock counting 2 pi / omega per swing: seconds gained per day"),
    "rate_impacts": ("s day-1", "part of the rate due to the impacts' phase jumps dT1, Eq. (24)"),
    "rate_zones": ("s day-1", "part of the rate due to the impulse zones dT2, Eq. (25)"),
}


def escapement_error_dataset(zones: Mapping[str, tuple[float, float]], forces: np.ndarray,
                             values: Mapping[str, np.ndarray], max_period_difference: float,
                             seconds_per_day: float, model: Mapping[str, float]) -> xr.Dataset:
    """The limit cycle's rate for every impulse zone and force.

    Parameters
    ----------
    zones : mapping of str to tuple of float
        Each zone's name and its ``(a1, a2)`` of the first half cycle, m (the second half cycle's is
        its mirror image).
    forces : numpy.ndarray
        The forces, N.
    values : mapping of str to numpy.ndarray
        Each name of :data:`ESCAPEMENT_ERROR_VARIABLES`, of shape ``(len(zones), len(forces))``.
    max_period_difference : float
        The largest relative difference between the corrected Eqs. (24)-(25) and the exact period.
    seconds_per_day : float
        The seconds in a day the rate counts.
    model : mapping of str to float
        The other parameters.

    Returns
    -------
    xarray.Dataset
        The escapement-error dataset.
    """
    names = list(zones)
    coords = {
        "zone": ("zone", np.arange(len(names), dtype=np.int32), {"long_name": "impulse zone number", "units": "1"}),
        "F": ("F", forces, {"long_name": "force of the escapement over an impulse zone", "units": "N"}),
    }
    variables = {
        name: xr.DataArray(values[name], dims=("zone", "F"), coords=coords, attrs={"units": u, "long_name": ln})
        for name, (u, ln) in ESCAPEMENT_ERROR_VARIABLES.items()
    }
    variables["zone_name"] = xr.DataArray(np.array(names, dtype=object), dims="zone", coords={"zone": coords["zone"]},
                                          attrs={"long_name": "name of the impulse zone",
                                                 "coverage_content_type": MODEL_INPUT})
    for index, end in enumerate(("a1", "a2")):
        variables[f"zone_{end}"] = xr.DataArray(
            np.array([zones[z][index] for z in names]), dims="zone",
            coords={"zone": coords["zone"]},
            attrs={"units": "m", "coverage_content_type": MODEL_INPUT,
                   "long_name": "impact position a1 of the first half cycle" if end == "a1"
                   else "end a2 of the first impulse zone"},
        )
    variables["max_period_difference"] = scalar_variable(
        max_period_difference, "1",
        "largest relative difference between the corrected Eqs. (24)-(25) and the exact solver's period", QUALITY,
    )
    variables["seconds_per_day"] = scalar_variable(seconds_per_day, "s day-1", "seconds in a day", MODEL_INPUT)
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
