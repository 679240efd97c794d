"""What each of the paper's figures needs, and only that.

* Fig. 3 (Poincare map): events only (per cycle, and the event log); no trajectory is kept or sampled.
* Fig. 4 (shock detail): one run up to the end of its window, sampled only inside it.
* Fig. 5 (phase diagrams): one run of ``n_cycles``, sampled at a rate set by the plot.
* Checks for the claims register: per case, the measured fixed point, period and multiplier.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from ..model.parameters import ParameterError, Parameters, check_initial_state
from ..model.quantities import MODEL_KEYS, PARAMETERS
from ..model.status import Status, flag_attributes
from ..paper.corrected import fixed_point
from ..paper.poincare import ensemble_return_map, measure_cycle, return_map, stability_grid
from ..paper.printed import fixed_point_19
from ..solvers.exact import solve_exact
from ..studies.long_run import long_run
from .dataset import (
    cycle_variables,
    dataset,
    event_variables,
    global_attributes,
    impact_variables,
    sample_variables,
    table_dataset,
)

__all__ = ["poincare_scene", "shock_scene", "phase_scene", "checks_scene"]


def _window(name: str, window) -> tuple[float, float]:
    try:
        lo, hi = (float(w) for w in window)
    except (TypeError, ValueError) as err:
        raise ParameterError(name, window, "a pair [start, end] of times in s") from err
    if not (0 <= lo < hi < np.inf):
        raise ParameterError(name, window, "a pair [start, end] with 0 <= start < end (s)")
    return lo, hi


def _positive_int(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ParameterError(name, value, "a positive integer")
    return int(value)


def poincare_scene(params: Parameters, x0: float, n_cycles: int) -> xr.Dataset:
    """Fig. 3: velocity before impact, period and amplitude for cycles 1 .. n_cycles."""
    run = solve_exact(params, x0, n_cycles=_positive_int("n_cycles", n_cycles), record_trajectory=False)
    return dataset(
        run,
        {**cycle_variables(run), **event_variables(run)},
        title="Poincare map of the escapement model (Mao, Fu & Li 2013, Fig. 3)",
        scene="fig3",
        n_cycles=int(n_cycles),
        fixed_point_19=fixed_point_19(params),
    )


def shock_scene(
    params: Parameters,
    x0: float,
    velocity_window: tuple[float, float],
    acceleration_window: tuple[float, float],
    samples_per_second: int,
) -> xr.Dataset:
    """Fig. 4: motion sampled only over the union of both windows, and the impacts inside it."""
    v_lo, v_hi = _window("velocity_window", velocity_window)
    a_lo, a_hi = _window("acceleration_window", acceleration_window)
    rate = _positive_int("samples_per_second", samples_per_second)
    lo, hi = min(v_lo, a_lo), max(v_hi, a_hi)
    run = solve_exact(params, x0, t_end=hi)
    t = np.linspace(lo, hi, int(round((hi - lo) * rate)) + 1)
    variables = sample_variables(run, t, acceleration=True)
    variables.update(impact_variables(run, window=(lo, hi)))
    variables.update(event_variables(run, window=(lo, hi)))
    return dataset(
        run,
        variables,
        title="Shock detail of the escapement model (Mao, Fu & Li 2013, Fig. 4)",
        scene="fig4",
        velocity_window=np.array([v_lo, v_hi]),
        acceleration_window=np.array([a_lo, a_hi]),
        samples_per_second=rate,
    )


def phase_scene(params: Parameters, x0: float, n_cycles: int, samples_per_period: int) -> xr.Dataset:
    """Fig. 5: the phase trajectory from release to the end of cycle ``n_cycles``, and its impacts."""
    per_period = _positive_int("samples_per_period", samples_per_period)
    run = solve_exact(params, x0, n_cycles=_positive_int("n_cycles", n_cycles))
    end = run.t_final if np.isfinite(run.t_final) else (n_cycles + 1) * params.natural_period
    n = int(np.ceil(end / params.natural_period * per_period)) + 1
    t = np.linspace(0.0, end, n)
    variables = sample_variables(run, t)
    variables.update(cycle_variables(run))
    variables.update(impact_variables(run))
    return dataset(
        run,
        variables,
        title="Phase diagram of the escapement model (Mao, Fu & Li 2013, Fig. 5)",
        scene="fig5",
        n_cycles=int(n_cycles),
        samples_per_period=per_period,
    )


def checks_scene(cases: list[dict], n_cycles: int) -> xr.Dataset:
    """Measure every case (a mapping with ``group``, ``label``, the model keys and ``x0``)."""
    n_cycles = _positive_int("n_cycles", n_cycles)
    runs = []
    for case in cases:
        params = Parameters.from_mapping(case)
        x0, _ = check_initial_state(case["x0"], case.get("v0", 0.0))
        runs.append((case, params, x0, measure_cycle(params, x0, n_cycles)))
    columns = {
        "label": ([c["label"] for c, *_ in runs], None, "name of the case"),
        "group": ([c["group"] for c, *_ in runs], None, "claim the case serves"),
        "outcome": ([m.outcome for *_, m in runs], None, "how the run ended"),
        "outcome_message": ([m.message for *_, m in runs], None, "how the run ended, in words"),
        "x0": ([x0 for _, _, x0, _ in runs], "m", "initial displacement (released from rest)"),
        "velocity": ([m.velocity for *_, m in runs], "m s-1", "velocity before impact at the last cycle"),
        "period": ([m.period for *_, m in runs], "s", "period of the last cycle"),
        "amplitude": ([m.amplitude for *_, m in runs], "m", "amplitude of the last cycle"),
        "multiplier": ([m.multiplier for *_, m in runs], "1", "multiplier mu_2 measured from the return map"),
        "multiplier_eq21": ([(1 - p.b) ** 4 for _, p, _, _ in runs], "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point_eq16": ([fixed_point(p) for _, p, _, _ in runs], "m s-1", "fixed point of the map (16)"),
        "cycles_to_converge": (
            np.array([m.cycles_to_converge for *_, m in runs], dtype=np.int32), "1",
            "first cycle within 1e-9 (relative) of the last velocity; -1 if none",
        ),
    }
    for key in MODEL_KEYS:
        q = PARAMETERS[key]
        columns[key] = ([getattr(p, key) for _, p, _, _ in runs], q.units, q.long_name)
    return table_dataset(
        columns, "Measured Poincare maps for the claims register", "checks", solver="exact", n_cycles=n_cycles
    )


def long_run_scene(
    params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float, ivp_cycles: int
) -> tuple[xr.Dataset, dict[str, float]]:
    """Errors of the exact solver over ``n_cycles`` and of ``solve_ivp`` over ``ivp_cycles``, against 50 digits;
    apart from the dataset (wall times vary from run to run), the wall time of each solver."""
    r = long_run(params, x0, _positive_int("n_cycles", n_cycles), ivp_method, ivp_rtol, _positive_int("ivp_cycles", ivp_cycles))
    coords = {"cycle": ("cycle", r["cycles"].astype(np.int32), {"long_name": "cycle number", "units": "1"})}
    names = {
        "error_time": ("1", "relative error of the impact time at a1"),
        "error_velocity": ("1", "relative error of the velocity before impact"),
        "drift": ("s", "impact time minus the 50-digit reference"),
    }
    variables = {}
    ivp_label = f"solve_ivp {ivp_method} rtol={ivp_rtol:g}"
    for solver, label in (("exact", "exact solver"), ("ivp", ivp_label)):
        for (name, (units, long_name)), values in zip(names.items(), r[solver]):
            variables[f"{name}_{solver}"] = xr.DataArray(
                values, dims="cycle", coords=coords, attrs={"units": units, "long_name": f"{long_name}, {label}"}
            )
    attrs = global_attributes(
        "Long run of the escapement model: error against the number of cycles",
        "long_run",
        solver="exact; " + ivp_label,
        ivp_label=ivp_label,
        x0=float(x0),
        n_cycles=int(n_cycles),
        ivp_cycles=int(ivp_cycles),
        converged_after=int(r["converged_after"]),
        max_velocity_deviation=r["max_velocity_deviation"],
        max_period_deviation=r["max_period_deviation"],
        fixed_point_velocity=r["fixed_point_velocity"],
        fixed_point_period=r["fixed_point_period"],
        any_nan=int(r["any_nan"]),
        **params.as_dict(),
    )
    timings = {"exact_seconds": r["exact_wall_s"], "ivp_seconds": r["ivp_wall_s"]}
    return xr.Dataset(variables, attrs=attrs), timings


def stability_chunk_scene(
    model: dict, b_values, F_values, speed_sample: int = 100
) -> tuple[xr.Dataset, dict[str, float]]:
    """Fixed point and measured multiplier over the grid ``b_values x F_values`` (ensemble solver),
    and, apart from the dataset (wall times vary from run to run), the cost per trajectory of the
    ensemble against looping the scalar solver on a sample."""
    b_values = np.asarray(b_values, dtype=float)
    F_values = np.asarray(F_values, dtype=float)
    bb, ff = np.meshgrid(b_values, F_values, indexing="ij")
    grid = stability_grid(model, bb.ravel(), ff.ravel())

    # The cost of one return-map evaluation per trajectory: the ensemble over the whole chunk, and
    # the scalar solver looped over an even sample of it, both at the fixed points, in this one run.
    v = np.where(np.isfinite(grid["fixed_point"]), grid["fixed_point"], 1.0)
    start = time.perf_counter()
    ensemble_return_map(model, bb.ravel(), ff.ravel(), v)
    ensemble_per_trajectory = (time.perf_counter() - start) / bb.size
    pick = np.linspace(0, bb.size - 1, min(speed_sample, bb.size)).astype(int)
    start = time.perf_counter()
    for i in pick:
        return_map(Parameters(**{**model, "F": ff.ravel()[i], "b": bb.ravel()[i]}), v[i], strict=False)
    scalar_per_trajectory = (time.perf_counter() - start) / len(pick)
    shape = bb.shape
    dims = ("b", "F")
    coords = {
        "b": ("b", b_values, {"long_name": "impact coefficient b (v+ = (1 - b) v-)", "units": "1"}),
        "F": ("F", F_values, {"long_name": "force F", "units": "N"}),
    }

    def grid_var(values, units, long_name, **attrs):
        return xr.DataArray(np.asarray(values).reshape(shape), dims=dims, coords=coords,
                            attrs={"units": units, "long_name": long_name, **attrs})

    variables = {
        "multiplier": grid_var(grid["multiplier"], "1", "multiplier mu_2 measured from the simulated return map"),
        "multiplier_eq21": grid_var((1 - bb) ** 4, "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point": grid_var(grid["fixed_point"], "m s-1", "fixed point of the simulated return map"),
        "period": grid_var(grid["period"], "s", "period of the cycle at the fixed point"),
        "outcome": xr.DataArray(
            np.asarray(grid["status"], dtype=np.int8).reshape(shape), dims=dims, coords=coords,
            attrs={"long_name": "how the cycle from the fixed point ended", **flag_attributes()},
        ),
    }
    attrs = global_attributes(
        "Stability and existence map of the escapement model over (b, F)",
        "stability_map",
        solver="exact, vectorised ensemble",
        **{k: float(v) for k, v in model.items() if v is not None},
    )
    timings = {"ensemble_seconds_per_trajectory": ensemble_per_trajectory,
               "scalar_seconds_per_trajectory": scalar_per_trajectory}
    return xr.Dataset(variables, attrs=attrs), timings
