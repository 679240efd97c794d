"""The scenes over grids of parameters, each from its settings to its dataset. A map's rows are independent
trajectories: a map too large for one job runs in chunks over slices of its rows, which :func:`gather` joins.
"""

from __future__ import annotations

import timeit
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..model.parameters import Parameters
from ..model.status import Status, flag_attributes
from ..paper.corrected import existence_threshold
from ..paper.printed import multiplier_21_of
from ..solvers.ensemble import solve_ensemble
from ..studies.escapement_error import SECONDS_PER_DAY, rate_against_amplitude
from ..studies.poincare import ensemble_return_map, return_map, stability_grid
from .cf import MODEL_INPUT, QUALITY, assemble, described, global_attributes, parameter_variables, quantity_attrs, \
    scalar_variable
from .settings import EscapementErrorScene, ExistenceMapScene, StabilityMapScene

__all__ = ["escapement_error", "existence_map", "gather", "mirror_image", "stability_map"]

#: the cells the stability map times the scalar solver on (an even sample)
SPEED_SAMPLE = 100


def gather(parts: Sequence[xr.Dataset], timings: Sequence[Mapping[str, float]] = ()) -> tuple[xr.Dataset, dict]:
    """A map from its chunks' datasets, joined along its rows; and the stability map's costs per trajectory from the
    chunks' ``timings``, each weighted by the cells it timed (all for the ensemble, a sample for the scalar solver)."""
    axis = parts[0]["outcome"].dims[0]  # the rows, which the chunks split
    joined = xr.concat([ds.drop_encoding() for ds in parts], axis, data_vars="minimal", coords="minimal",
                       compat="equals", join="exact", combine_attrs="override")
    if not timings:
        return joined, {}
    cells = np.array([ds.sizes["b"] * ds.sizes["F"] for ds in parts])
    ensemble, scalar = (float(np.average([t[key] for t in timings], weights=weights)) for key, weights in (
        ("ensemble_seconds_per_trajectory", cells), ("scalar_seconds_per_trajectory", np.minimum(cells, SPEED_SAMPLE))))
    return joined, _costs(ensemble, scalar)


def _costs(ensemble: float, scalar: float) -> dict:
    return {"ensemble_seconds_per_trajectory": ensemble, "scalar_seconds_per_trajectory": scalar,
            "ensemble_speedup_per_trajectory": scalar / ensemble}


def _coords(**axes: np.ndarray) -> dict:
    return {name: (name, np.asarray(values, dtype=float), quantity_attrs(name)) for name, values in axes.items()}


def _grid(values, coords: dict, units: str | None, long_name: str, **attrs) -> xr.DataArray:
    attrs = described(units, long_name, **attrs)
    return xr.DataArray(np.asarray(values), dims=tuple(coords), coords=coords, attrs=attrs)


def stability_map(settings: Mapping | StabilityMapScene, speed_sample: int = SPEED_SAMPLE) -> tuple[xr.Dataset, dict]:
    """The stability map and, apart from it, the cost per trajectory of the ensemble and of the scalar solver
    looped over an even sample of ``speed_sample`` cells, both at the fixed points, and the ensemble's speed-up."""
    scene = settings if isinstance(settings, StabilityMapScene) else StabilityMapScene.from_mapping(settings)
    model = {k: v for k, v in scene.params.as_dict().items() if k not in ("b", "F")}
    bb, ff = np.meshgrid(np.array(scene.b_values), np.array(scene.F_values), indexing="ij")
    b_cells, F_cells = bb.ravel(), ff.ravel()
    grid = stability_grid(model, b_cells, F_cells)
    cells = {key: np.asarray(found).reshape(bb.shape) for key, found in grid.items()}
    v = np.where(np.isfinite(grid["fixed_point"]), grid["fixed_point"], 1.0)
    ensemble = timeit.timeit(lambda: ensemble_return_map(model, b_cells, F_cells, v), number=1) / bb.size
    pick = np.linspace(0, bb.size - 1, min(speed_sample, bb.size)).astype(int)
    scalar = timeit.timeit(lambda: [return_map(Parameters(**{**model, "F": F_cells[i], "b": b_cells[i]}), v[i],
                                               strict=False) for i in pick], number=1) / len(pick)
    coords = _coords(b=scene.b_values, F=scene.F_values)
    eq21 = np.array([[multiplier_21_of(float(b))] * len(scene.F_values) for b in scene.b_values])  # once per b
    variables = {
        "multiplier": _grid(cells["multiplier"], coords, "1", "multiplier mu_2 measured from the simulated return map"),
        "multiplier_eq21": _grid(eq21, coords, "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point": _grid(cells["fixed_point"], coords, "m s-1", "fixed point of the simulated return map"),
        "period": _grid(cells["period"], coords, "s", "period of the cycle at the fixed point"),
        "outcome": _grid(cells["status"].astype(np.int8), coords, None, "how the cycle from the fixed point ended",
                         **flag_attributes()),
    }
    variables.update(parameter_variables(model))  # the ensemble checked every cell
    attrs = global_attributes(
        scene.study.title("stability_map"), "stability_map",
        "This file holds, over a grid of the impact coefficient b and the force F (its coordinates; the other "
        "parameters are constants), the fixed point of the simulated return map of the velocity before the impact "
        "at a1, found by Newton's method, the period of the cycle there, the multiplier mu_2 measured by central "
        "differences of the map beside (1 - b)**4 of Eq. (21), and how the cycle from the fixed point ended.",
        solver="exact, vectorised ensemble", **scene.study.attributes())
    return assemble(variables, attrs), _costs(ensemble, scalar)


def mirror_image(p: Parameters) -> Parameters:
    """The escapement reflected by ``x -> -x``: the impact at a3 becomes the first half cycle's."""
    return Parameters(M=p.M, K=p.K, F=p.F, b=p.b, a1=-p.a3, a2=-p.a4, a3=-p.a1, a4=-p.a2)


def existence_map(settings: Mapping | ExistenceMapScene) -> xr.Dataset:
    """How every ``(a3, F)`` run from the release ended and whether it reached a limit cycle, beside F* and F*'."""
    scene = settings if isinstance(settings, ExistenceMapScene) else ExistenceMapScene.from_mapping(settings)
    p = scene.params
    aa, ff = np.meshgrid(np.array(scene.a3_values), np.array(scene.F_values), indexing="ij")
    run = solve_ensemble(p.M, p.K, ff.ravel(), p.b, p.a1, p.a2, aa.ravel(), p.a4, x0=scene.release.x0,
                         v0=scene.release.v0, n_cycles=scene.n_cycles, largest_displacement=False)
    status = np.asarray(run.status).reshape(aa.shape)
    v = run.cycles.velocity_before_impact
    settled = (np.abs(v[:, -1] - v[:, -2]) <= scene.tolerance * np.abs(v[:, -1])).reshape(aa.shape)
    converged = (status == Status.COMPLETED.code) & settled
    thresholds = np.array([(existence_threshold(q), existence_threshold(mirror_image(q)))
                           for q in (Parameters(**{**p.as_dict(), "a3": a3, "F": 0.0}) for a3 in scene.a3_values)])
    coords = _coords(a3=scene.a3_values, F=scene.F_values)
    along = {"a3": coords["a3"]}
    variables = {
        "outcome": _grid(status.astype(np.int8), coords, None, "how the run from the release ended",
                         **flag_attributes()),
        "converged": _grid(converged.astype(np.int8), coords, None, "whether the run reached a limit cycle (completed, "
                           "last two velocities before the impact at a1 within the relative tolerance)",
                           flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="no_limit_cycle limit_cycle"),
        "threshold": _grid(thresholds[:, 0], along, "N",
                           "force F* at which the constant C of the map (16) read at a1 is zero"),
        "threshold_mirror": _grid(thresholds[:, 1], along, "N", "force F*' at which the constant of the map (16) read "
                                  "at a3 is zero (F* of the mirror-image escapement)"),
        "n_cycles": scalar_variable(np.int32(scene.n_cycles), "1", "complete cycles each run was given", MODEL_INPUT),
        "tolerance": scalar_variable(scene.tolerance, "1", "relative tolerance on the last two velocities before "
                                     "the impact at a1 for a converged run", MODEL_INPUT),
    }
    constants = {k: getattr(p, k) for k in ("M", "K", "b", "a1", "a2", "a4")}
    variables.update(parameter_variables({**constants, "x0": scene.release.x0, "v0": scene.release.v0}))
    attrs = global_attributes(
        scene.study.title("existence_map"), "existence_map",
        "This file holds, over a grid of the impact position a3 of the second half cycle and the force F (its "
        "coordinates; the other parameters and the release are constants), how a run of the exact solver "
        "(vectorised ensemble) from the release ended and whether it reached a limit cycle, beside the closed-form "
        "forces F* and F*' below which the map (16), read at a1 or at a3, has no fixed point.",
        solver="exact, vectorised ensemble", **scene.study.attributes())
    return assemble(variables, attrs)


#: each field of a limit cycle's rate (escapement.studies.escapement_error.LimitCycleRate) kept: (units, long name)
RATE_VARIABLES = {
    "largest_displacement": ("m", "largest displacement of the limit cycle (its amplitude)"),
    "velocity": ("m s-1", "velocity before the impact at a1 on the limit cycle (fixed point of the map (16))"),
    "period": ("s", "period of the limit cycle, exact solver"),
    "period_formula": ("s", "2 pi / omega + dT1 + dT2 by the corrected Eqs. (24)-(25)"),
    "rate": ("s day-1", "rate of a clock counting 2 pi / omega per swing: seconds gained per day"),
    "rate_impacts": ("s day-1", "part of the rate due to the impacts' phase jumps dT1, Eq. (24)"),
    "rate_zones": ("s day-1", "part of the rate due to the impulse zones dT2, Eq. (25)"),
}


def escapement_error(settings: Mapping | EscapementErrorScene) -> xr.Dataset:
    """The limit cycle's rate for every impulse zone and force, with the largest relative difference between
    the corrected Eqs. (24)-(25) and the exact solver's period."""
    scene = settings if isinstance(settings, EscapementErrorScene) else EscapementErrorScene.from_mapping(settings)
    forces, shape = np.array(scene.forces), (len(scene.zones), len(scene.forces))
    cycles = [cycle for _, a1, a2 in scene.zones for cycle in rate_against_amplitude(
        Parameters(**{**scene.params.as_dict(), "a1": a1, "a2": a2, "a3": -a1, "a4": -a2}), forces)]
    values = {name: np.array([getattr(c, name) for c in cycles], dtype=float).reshape(shape) for name in RATE_VARIABLES}
    outcome = np.array([c.status.code for c in cycles], dtype=np.int8).reshape(shape)
    differences = np.abs(values["period_formula"] - values["period"]) / values["period"]
    worst = float(np.nanmax(differences)) if np.isfinite(differences).any() else float("nan")
    zone = ("zone", np.arange(len(scene.zones), dtype=np.int32), {"long_name": "impulse zone number", "units": "1"})
    coords = {"zone": zone, **_coords(F=forces)}
    variables = {name: _grid(values[name], coords, u, ln) for name, (u, ln) in RATE_VARIABLES.items()}
    variables["outcome"] = _grid(outcome, coords, None, "how the cycle from the fixed point of the map (16) ended: "
                                 "completed is a limit cycle, stopped is no fixed point (the variables above are NaN "
                                 "where it is not completed)", **flag_attributes())
    variables["zone_name"] = _grid(np.array([z[0] for z in scene.zones], dtype=object), {"zone": zone}, None,
                                   "name of the impulse zone", coverage_content_type=MODEL_INPUT)
    for index, (end, long_name) in enumerate((("a1", "impact position a1 of the first half cycle"),
                                              ("a2", "end a2 of the first impulse zone")), start=1):
        variables[f"zone_{end}"] = _grid([z[index] for z in scene.zones], {"zone": zone}, "m", long_name,
                                         coverage_content_type=MODEL_INPUT)
    variables["max_period_difference"] = scalar_variable(
        worst, "1", "largest relative difference between the corrected Eqs. (24)-(25) and the exact solver's period "
        "over the limit cycles", QUALITY)
    variables["seconds_per_day"] = scalar_variable(SECONDS_PER_DAY, "s day-1", "seconds in a day", MODEL_INPUT)
    variables.update(parameter_variables({k: getattr(scene.params, k) for k in ("M", "K", "b")}))
    attrs = global_attributes(
        scene.study.title("escapement_error"), "escapement_error",
        "This file holds the escapement error of the limit cycle: for each impulse zone (the first half cycle's "
        "impact position a1 and zone end a2; the second half cycle mirrors them) and each force F, the limit "
        "cycle's largest displacement, its period measured by the exact solver from the fixed point of the map "
        "(16), the period by the corrected Eqs. (24)-(25), and the rate of a clock counting the natural period per "
        "swing, split into the impacts' part dT1 and the impulse zones' part dT2.",
        solver="exact", **scene.study.attributes())
    return assemble(variables, attrs)
