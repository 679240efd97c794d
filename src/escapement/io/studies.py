"""The datasets of the studies beyond the paper's figures, made from the experiments' results: the
escapement error (rate against amplitude, :mod:`escapement.experiments.escapement_error`) and the
existence map of the limit cycle of an asymmetric escapement (:mod:`escapement.experiments.existence`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.quantities import PARAMETERS
from ..model.status import flag_attributes
from .dataset import MODEL_INPUT, QUALITY, assemble, global_attributes, parameter_variables, scalar_variable

__all__ = ["ESCAPEMENT_ERROR_VARIABLES", "escapement_error_dataset", "existence_dataset"]

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


def existence_dataset(a3_values: np.ndarray, F_values: np.ndarray, status: np.ndarray, converged: np.ndarray,
                      threshold: np.ndarray, threshold_mirror: np.ndarray, constants: Mapping[str, float],
                      n_cycles: int, tolerance: float) -> xr.Dataset:
    """The existence map of the limit cycle over (a3, F).

    Parameters
    ----------
    a3_values, F_values : numpy.ndarray
        The axes: impact positions a3 (m) and forces (N).
    status : numpy.ndarray
        How each run ended (:attr:`~escapement.model.status.Status.code`), shape ``(len(a3_values), len(F_values))``.
    converged : numpy.ndarray
        Where the run reached its limit cycle, of the same shape.
    threshold, threshold_mirror : numpy.ndarray
        ``F*`` and ``F*'`` at each a3 (N).
    constants : mapping of str to float
        The other parameters and the release ``x0``, ``v0``.
    n_cycles : int
        Cycles each run was given.
    tolerance : float
        The relative tolerance of ``converged``.

    Returns
    -------
    xarray.Dataset
        The existence map's dataset.
    """
    dims = ("a3", "F")
    coords = {name: (name, np.asarray(values, dtype=float),
                     {"long_name": PARAMETERS[name].long_name, "units": PARAMETERS[name].units})
              for name, values in (("a3", a3_values), ("F", F_values))}
    along = {"a3": coords["a3"]}
    variables = {
        "outcome": xr.DataArray(np.asarray(status, dtype=np.int8), dims=dims, coords=coords,
                                attrs={"long_name": "how the run from the release ended", **flag_attributes()}),
        "converged": xr.DataArray(
            np.asarray(converged, dtype=np.int8), dims=dims, coords=coords,
            attrs={"long_name": "whether the run reached a limit cycle (completed, last two velocities before "
                                "the impact at a1 within the relative tolerance)",
                   "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no_limit_cycle limit_cycle"}),
        "threshold": xr.DataArray(
            np.asarray(threshold, dtype=float), dims="a3", coords=along,
            attrs={"units": "N", "long_name": "force F* at which the constant C of the map (16) read at a1 is zero"}),
        "threshold_mirror": xr.DataArray(
            np.asarray(threshold_mirror, dtype=float), dims="a3", coords=along,
            attrs={"units": "N", "long_name": "force F*' at which the constant of the map (16) read at a3 is zero "
                                              "(F* of the mirror-image escapement)"}),
        "n_cycles": scalar_variable(np.int32(n_cycles), "1", "complete cycles each run was given", MODEL_INPUT),
        "tolerance": scalar_variable(float(tolerance), "1", "relative tolerance on the last two velocities before "
                                     "the impact at a1 for a converged run", MODEL_INPUT),
    }
    variables.update(parameter_variables(constants))
    summary = (
        "This file holds, over a grid of the impact position a3 of the second half cycle and the force F (its "
        "coordinates; the other parameters and the release are constants), how a run of the exact solver "
        "(vectorised ensemble) from the release ended and whether it reached a limit cycle, beside the closed-form "
        "forces F* and F*' below which the map (16), read at a1 or at a3, has no fixed point."
    )
    attrs = global_attributes("Existence of the limit cycle of an asymmetric escapement over (a3, F)",
                              "existence_map", summary, solver="exact, vectorised ensemble")
    return assemble(variables, attrs)
