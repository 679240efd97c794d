"""What each of the paper's figures needs, and only that.

* Fig. 3 (Poincare map): events only (per cycle, and the event log); no trajectory is kept or sampled.
* Fig. 4 (shock detail): one run up to the end of its window, sampled only inside it.
* Fig. 5 (phase diagrams): one run of ``n_cycles``, sampled at a rate set by the plot.
* Checks for the claims register: per case, the measured fixed point, period and multiplier.

Each sampled time series holds, besides its uniform grid, a sample on each side of every jump it
shows (:func:`~escapement.io.dataset.sample_times`), so that the values just before and just after
each impact are in the file.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import ParameterError, Parameters, check_initial_state, validate_arrays
from ..model.quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS
from ..model.status import Status, flag_attributes
from ..paper.corrected import fixed_point
from ..paper.poincare import ensemble_return_map, measure_cycle, return_map, stability_grid
from ..paper.printed import fixed_point_19, multiplier_21, multiplier_21_of
from ..solvers.exact import solve_exact
from ..studies.long_run import long_run
from ..studies.readings import AMPLITUDES
from .dataset import (
    CLASSIFICATION,
    MODEL_INPUT,
    QUALITY,
    assemble,
    cycle_variables,
    dataset,
    event_variables,
    global_attributes,
    impact_variables,
    parameter_variables,
    sample_times,
    sample_variables,
    scalar_variable,
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


def _window_variable(lo: float, hi: float, long_name: str) -> xr.DataArray:
    """A time window [start, end] as a variable of two values (s)."""
    return xr.DataArray(np.array([lo, hi]), dims="window_edge",
                        attrs={"units": "s", "long_name": long_name, "coverage_content_type": MODEL_INPUT})


def poincare_scene(params: Parameters, x0: float, n_cycles: int, amplitude: str = "largest_displacement"
                   ) -> xr.Dataset:
    """Fig. 3: velocity before impact, period and amplitude for cycles 1 .. n_cycles; the amplitude
    is the definition ``amplitude`` names in :data:`escapement.studies.readings.AMPLITUDES`, on a
    coordinate ``amplitude_cycle`` of its own (the Step-1 amplitude has one value more than there
    are cycles)."""
    if amplitude not in AMPLITUDES:
        raise ParameterError("amplitude", amplitude, f"one of {', '.join(AMPLITUDES)}")
    run = solve_exact(params, x0, n_cycles=_positive_int("n_cycles", n_cycles),
                      record_trajectory=amplitude == "largest_abs")
    variables = {**cycle_variables(run), **event_variables(run)}
    cycle, values = AMPLITUDES[amplitude].values(run)
    variables["amplitude"] = xr.DataArray(
        values, dims="amplitude_cycle",
        coords={"amplitude_cycle": ("amplitude_cycle", cycle,
                                    {"long_name": "cycle number of the amplitude", "units": "1"})},
        attrs={"units": "m", "long_name": AMPLITUDES[amplitude].long_name, "definition": amplitude},
    )
    variables["fixed_point_19"] = scalar_variable(
        fixed_point_19(params), "m s-1", "fixed point of the map (17) by Eq. (19) as printed (velocity before impact)"
    )
    return dataset(
        run,
        variables,
        title="Poincare map of the escapement model (Mao, Fu & Li 2013, Fig. 3)",
        scene="fig3",
        summary=(
            "This file holds the Poincare map of one run released at x0 with velocity v0 (Fig. 3 of the paper): "
            "per cycle, the velocity just before the impact at a1, the period and the amplitude, for n_cycles "
            "cycles; every event of the run (impacts and ends of the impulse zones); and the fixed point of "
            "Eq. (19) as printed."
        ),
        n_cycles=int(n_cycles),
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
    # the velocity jumps at the impacts, the acceleration at every event: a sample on each side of each
    t = sample_times(np.linspace(lo, hi, int(round((hi - lo) * rate)) + 1), run.events.t)
    variables = sample_variables(run, t, acceleration=True)
    variables.update(impact_variables(run, window=(lo, hi)))
    variables.update(event_variables(run, window=(lo, hi)))
    variables["velocity_window"] = _window_variable(v_lo, v_hi, "time window [start, end] of the velocity panel")
    variables["acceleration_window"] = _window_variable(
        a_lo, a_hi, "time window [start, end] of the acceleration panel"
    )
    variables["samples_per_second"] = scalar_variable(
        float(rate), "s-1", "sampling rate of the uniform time grid", MODEL_INPUT
    )
    return dataset(
        run,
        variables,
        title="Shock detail of the escapement model (Mao, Fu & Li 2013, Fig. 4)",
        scene="fig4",
        summary=(
            "This file holds the shock detail (Fig. 4 of the paper) of one run released at x0 with velocity v0: "
            "displacement, velocity and the smooth part of the acceleration sampled over the union of the "
            "velocity and acceleration windows, on a uniform grid of samples_per_second with, at each event, a "
            "sample at the largest float below its time and one at its time (the velocity jumps at the impacts, "
            "the acceleration at every event); the impacts in the window with their impulse and dissipated "
            "energy; and every event in the window."
        ),
    )


def phase_scene(params: Parameters, x0: float, n_cycles: int, samples_per_period: int) -> xr.Dataset:
    """Fig. 5: the phase trajectory from release to the end of cycle ``n_cycles``, and its impacts."""
    per_period = _positive_int("samples_per_period", samples_per_period)
    run = solve_exact(params, x0, n_cycles=_positive_int("n_cycles", n_cycles))
    end = run.t_final if np.isfinite(run.t_final) else (n_cycles + 1) * params.natural_period
    n = int(np.ceil(end / params.natural_period * per_period)) + 1
    ev = run.events
    impacts = ev.t[(ev.kind == int(EventKind.IMPACT_A1)) | (ev.kind == int(EventKind.IMPACT_A3))]
    t = sample_times(np.linspace(0.0, end, n), impacts)  # a sample on each side of each velocity jump
    variables = sample_variables(run, t)
    variables.update(cycle_variables(run))
    variables.update(impact_variables(run))
    return dataset(
        run,
        variables,
        title="Phase diagram of the escapement model (Mao, Fu & Li 2013, Fig. 5)",
        scene="fig5",
        summary=(
            "This file holds one phase diagram of Fig. 5 of the paper: one run released at x0 with velocity v0, "
            "from t = 0 to the end of cycle n_cycles, its displacement and velocity sampled samples_per_period "
            "times per natural period 2 pi sqrt(M/K) with, at each impact, a sample at the largest float below "
            "its time and one at its time (the velocity just before and just after the jump); the per-cycle "
            "Poincare map; and every impact with its impulse and dissipated energy."
        ),
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
    x0_quantity = INITIAL_STATE["x0"]
    columns = {
        "label": ([c["label"] for c, *_ in runs], None, "name of the case", MODEL_INPUT),
        "group": ([c["group"] for c, *_ in runs], None, "claim the case serves", MODEL_INPUT),
        "outcome": ([m.outcome for *_, m in runs], None, "how the run ended", CLASSIFICATION),
        "outcome_message": ([m.message for *_, m in runs], None, "how the run ended, in words", CLASSIFICATION),
        "x0": ([x0 for _, _, x0, _ in runs], x0_quantity.units, f"{x0_quantity.long_name} (released from rest)",
               MODEL_INPUT),
        "velocity": ([m.velocity for *_, m in runs], "m s-1", "velocity before impact at the last cycle"),
        "period": ([m.period for *_, m in runs], "s", "period of the last cycle"),
        "amplitude": ([m.amplitude for *_, m in runs], "m", "amplitude of the last cycle"),
        "multiplier": ([m.multiplier for *_, m in runs], "1", "multiplier mu_2 measured from the return map"),
        "multiplier_eq21": ([multiplier_21(p) for _, p, _, _ in runs], "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point_eq16": ([fixed_point(p) for _, p, _, _ in runs], "m s-1", "fixed point of the map (16)"),
        "cycles_to_converge": (
            np.array([m.cycles_to_converge for *_, m in runs], dtype=np.int32), "1",
            "first cycle within 1e-9 (relative) of the last velocity; -1 if none",
        ),
    }
    for key in MODEL_KEYS:
        q = PARAMETERS[key]
        columns[key] = ([getattr(p, key) for _, p, _, _ in runs], q.units, q.long_name, MODEL_INPUT)
    summary = (
        "This file holds one row per run of the claims register: each run, with the parameters of its row, "
        "starts from rest at x0 and lasts n_cycles cycles; its fixed point, period, amplitude and multiplier "
        "are measured at the last cycle, beside the fixed point of Eq. (16) and the multiplier of Eq. (21)."
    )
    return table_dataset(
        columns, "Measured Poincare maps for the claims register", "checks", summary, solver="exact",
        n_cycles=n_cycles,
    )


def long_run_scene(
    params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float, ivp_cycles: int
) -> tuple[xr.Dataset, dict[str, float]]:
    """Errors of the exact solver and of the per-cycle closed forms over ``n_cycles`` and of ``solve_ivp`` over
    ``ivp_cycles``, against 50 digits, and the largest difference between the closed forms and the exact solver;
    apart from the dataset (wall times vary from run to run), the wall time of each method."""
    r = long_run(params, x0, _positive_int("n_cycles", n_cycles), ivp_method, ivp_rtol, _positive_int("ivp_cycles", ivp_cycles))
    coords = {"cycle": ("cycle", r["cycles"].astype(np.int32), {"long_name": "cycle number", "units": "1"})}
    names = {
        "error_time": ("1", "relative error of the impact time at a1"),
        "error_velocity": ("1", "relative error of the velocity before impact"),
        "drift": ("s", "impact time minus the 50-digit reference"),
    }
    variables = {}
    ivp_label = f"solve_ivp {ivp_method} rtol={ivp_rtol:g}"
    methods = (("exact", "exact solver"), ("closed_form", "per-cycle closed forms"), ("ivp", ivp_label))
    for solver, label in methods:
        for (name, (units, long_name)), values in zip(names.items(), r[solver]):
            variables[f"{name}_{solver}"] = xr.DataArray(
                values, dims="cycle", coords=coords,
                attrs={"units": units, "long_name": f"{long_name}, {label}", "coverage_content_type": QUALITY},
            )
    variables.update(
        max_velocity_deviation=scalar_variable(
            r["max_velocity_deviation"], "1",
            "largest relative deviation of the velocity before impact from the fixed point once converged, "
            "exact solver", QUALITY,
        ),
        max_period_deviation=scalar_variable(
            r["max_period_deviation"], "1",
            "largest relative deviation of the period from the limit cycle's once converged, exact solver", QUALITY,
        ),
        closed_form_difference=scalar_variable(
            r["check_max_relative_difference"], "1",
            "largest relative difference between the per-cycle closed forms and the exact solver, over the impact "
            "time, velocity before impact, period and amplitude of every cycle both ran", QUALITY,
        ),
        fixed_point_velocity=scalar_variable(
            r["fixed_point_velocity"], "m s-1", "velocity before impact at a1 on the limit cycle, 50-digit reference"
        ),
        fixed_point_period=scalar_variable(
            r["fixed_point_period"], "s", "period of the limit cycle, 50-digit reference"
        ),
    )
    variables.update(parameter_variables({**params.as_dict(), "x0": x0}))
    attrs = global_attributes(
        "Long run of the escapement model: error against the number of cycles",
        "long_run",
        (
            "This file holds the errors against a 50-digit reference of one run released from rest at x0, at "
            "cycles spaced evenly in log: the relative errors of the impact time at a1 and of the velocity "
            "before it, and the drift of the impact time, for the exact solver over check_cycles cycles, for "
            "the per-cycle closed forms (the return map of the squared velocity, Eq. (16), and each cycle's "
            "arcs) over n_cycles cycles and for solve_ivp over ivp_cycles cycles; the largest difference "
            "between the closed forms and the exact solver; the limit cycle of the reference; and the largest "
            "deviations of the exact solver from it after converged_after cycles (any_nan is 1 if the exact "
            "run gave a NaN)."
        ),
        solver="exact; closed-form cycles; " + ivp_label,
        ivp_label=ivp_label,
        n_cycles=int(n_cycles),
        check_cycles=int(r["check_cycles"]),
        closed_form_method=r["series_method"],
        ivp_cycles=int(ivp_cycles),
        converged_after=int(r["converged_after"]),
        any_nan=int(r["any_nan"]),
    )
    timings = {"exact_seconds": r["exact_wall_s"], "closed_form_seconds": r["closed_form_wall_s"],
               "ivp_seconds": r["ivp_wall_s"]}
    return assemble(variables, attrs), timings


def _multiplier_21_grid(b: np.ndarray) -> np.ndarray:
    """Eq. (21) at every cell, computed once per distinct ``b`` (the same float on every machine)."""
    values, index = np.unique(b, return_inverse=True)
    return np.array([multiplier_21_of(float(v)) for v in values])[index].reshape(b.shape)


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
        name: (name, values, {"long_name": PARAMETERS[name].long_name, "units": PARAMETERS[name].units})
        for name, values in (("b", b_values), ("F", F_values))
    }

    def grid_var(values, units, long_name, **attrs):
        return xr.DataArray(np.asarray(values).reshape(shape), dims=dims, coords=coords,
                            attrs={"units": units, "long_name": long_name, **attrs})

    variables = {
        "multiplier": grid_var(grid["multiplier"], "1", "multiplier mu_2 measured from the simulated return map"),
        "multiplier_eq21": grid_var(_multiplier_21_grid(bb), "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point": grid_var(grid["fixed_point"], "m s-1", "fixed point of the simulated return map"),
        "period": grid_var(grid["period"], "s", "period of the cycle at the fixed point"),
        "outcome": xr.DataArray(
            np.asarray(grid["status"], dtype=np.int8).reshape(shape), dims=dims, coords=coords,
            attrs={"long_name": "how the cycle from the fixed point ended", **flag_attributes()},
        ),
    }
    # b and F are the coordinates; the other parameters (a3, a4 resolved to their defaults) are constants
    resolved = validate_arrays({**model, "b": bb.ravel(), "F": ff.ravel()})
    variables.update(parameter_variables({k: np.ravel(resolved[k])[0] for k in MODEL_KEYS if k not in dims}))
    attrs = global_attributes(
        "Stability and existence map of the escapement model over (b, F)",
        "stability_map",
        (
            "This file holds, over a grid of the impact coefficient b and the force F (its coordinates; the "
            "other parameters are constants), the fixed point of the simulated return map of the velocity "
            "before the impact at a1, found by Newton's method, the period of the cycle there, the multiplier "
            "mu_2 measured by central differences of the map beside (1 - b)**4 of Eq. (21), and how the cycle "
            "from the fixed point ended."
        ),
        solver="exact, vectorised ensemble",
    )
    timings = {"ensemble_seconds_per_trajectory": ensemble_per_trajectory,
               "scalar_seconds_per_trajectory": scalar_per_trajectory}
    return assemble(variables, attrs), timings
