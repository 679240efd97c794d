"""The datasets of the paper's figures and of the runs around them, made from the experiments'
results (:mod:`escapement.experiments`): what each file holds, with its units, long names and
attributes. Nothing here runs a solver.

* Fig. 3 (Poincare map): the cycles and the event log of one run, its amplitude and Eq. (19)'s
  fixed point.
* Fig. 4 (shock detail) and Fig. 5 (phase diagrams): the run sampled at the given times (a sample
  on each side of every jump it shows), its impacts and, for Fig. 4, its events.
* The checks of the claims register: one row per case.
* The long run (errors against the number of cycles) and one chunk of the stability map.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.parameters import Parameters
from ..model.quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS
from ..model.status import flag_attributes
from ..solvers.result import Solution
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
    sample_variables,
    scalar_variable,
    table_dataset,
)

__all__ = [
    "CHECKS_COLUMNS",
    "checks_dataset",
    "long_run_dataset",
    "phase_dataset",
    "poincare_dataset",
    "shock_dataset",
    "stability_dataset",
]


def _window_variable(window: tuple[float, float], long_name: str) -> xr.DataArray:
    """A time window [start, end] as a variable of two values (s)."""
    return xr.DataArray(np.array(window), dims="window_edge",
                        attrs={"units": "s", "long_name": long_name, "coverage_content_type": MODEL_INPUT})


def poincare_dataset(solution: Solution, n_cycles: int, amplitude_definition: str, amplitude_long_name: str,
                     amplitude_cycle: np.ndarray, amplitude: np.ndarray, fixed_point_19: float) -> xr.Dataset:
    """Fig. 3: velocity before impact, period and amplitude per cycle, and every event.

    Parameters
    ----------
    solution : Solution
        The run.
    n_cycles : int
        The cycles asked for.
    amplitude_definition, amplitude_long_name : str
        The amplitude's definition (its key) and what it is, in words.
    amplitude_cycle, amplitude : numpy.ndarray
        The cycle number of each amplitude and the amplitudes (m), on a coordinate
        ``amplitude_cycle`` of their own.
    fixed_point_19 : float
        The fixed point of Eq. (19) as printed, m/s.

    Returns
    -------
    xarray.Dataset
        The Fig. 3 dataset.
    """
    variables = {**cycle_variables(solution), **event_variables(solution)}
    variables[amplitude_definition] = xr.DataArray(
        amplitude, dims="amplitude_cycle",
        coords={"amplitude_cycle": ("amplitude_cycle", amplitude_cycle,
                                    {"long_name": "cycle number of the amplitude", "units": "1"})},
        attrs={"units": "m", "long_name": amplitude_long_name},
    )
    variables["fixed_point_19"] = scalar_variable(
        fixed_point_19, "m s-1", "fixed point of the map (17) by Eq. (19) as printed (velocity before impact)"
    )
    return dataset(
        solution,
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
        amplitude_variable=amplitude_definition,
    )


def shock_dataset(solution: Solution, t: np.ndarray, window: tuple[float, float],
                  velocity_window: tuple[float, float], acceleration_window: tuple[float, float],
                  samples_per_second: int) -> xr.Dataset:
    """Fig. 4: the motion sampled at ``t``, and the impacts and events inside ``window``.

    Parameters
    ----------
    solution : Solution
        The run, with its trajectory.
    t : numpy.ndarray
        The sample times, s.
    window : tuple of float
        The union of both panels' windows, s.
    velocity_window, acceleration_window : tuple of float
        The windows of the velocity and acceleration panels, s.
    samples_per_second : int
        The rate of the uniform grid.

    Returns
    -------
    xarray.Dataset
        The Fig. 4 dataset.
    """
    variables = sample_variables(solution, t, acceleration=True)
    variables.update(impact_variables(solution, window=window))
    variables.update(event_variables(solution, window=window))
    variables["velocity_window"] = _window_variable(velocity_window, "time window [start, end] of the velocity panel")
    variables["acceleration_window"] = _window_variable(
        acceleration_window, "time window [start, end] of the acceleration panel"
    )
    variables["samples_per_second"] = scalar_variable(
        float(samples_per_second), "s-1", "sampling rate of the uniform time grid", MODEL_INPUT
    )
    return dataset(
        solution,
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


def phase_dataset(solution: Solution, t: np.ndarray, n_cycles: int, samples_per_period: int) -> xr.Dataset:
    """Fig. 5: the phase trajectory sampled at ``t``, the per-cycle map and every impact.

    Parameters
    ----------
    solution : Solution
        The run, with its trajectory.
    t : numpy.ndarray
        The sample times, s.
    n_cycles : int
        The cycles asked for.
    samples_per_period : int
        Samples per natural period of the uniform grid.

    Returns
    -------
    xarray.Dataset
        The dataset of one panel of Fig. 5.
    """
    variables = sample_variables(solution, t)
    variables.update(cycle_variables(solution))
    variables.update(impact_variables(solution))
    return dataset(
        solution,
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
        samples_per_period=int(samples_per_period),
    )


#: the columns of the checks dataset: name: (units, or None for text; long name[, content type])
CHECKS_COLUMNS = {
    "label": (None, "name of the case", MODEL_INPUT),
    "group": (None, "claim the case serves", MODEL_INPUT),
    "outcome": (None, "how the run ended", CLASSIFICATION),
    "outcome_message": (None, "how the run ended, in words", CLASSIFICATION),
    "x0": (INITIAL_STATE["x0"].units, f"{INITIAL_STATE['x0'].long_name} (released from rest)", MODEL_INPUT),
    "velocity": ("m s-1", "velocity before impact at the last cycle"),
    "period": ("s", "period of the last cycle"),
    "largest_displacement": ("m", "largest displacement of the last cycle"),
    "multiplier": ("1", "multiplier mu_2 measured from the return map"),
    "multiplier_eq21": ("1", "multiplier (1 - b)**4 of Eq. (21)"),
    "fixed_point_eq16": ("m s-1", "fixed point of the map (16)"),
    "cycles_to_converge": ("1", "first cycle within 1e-9 (relative) of the last velocity; -1 if none"),
    "first_period": ("s", "period of the first cycle"),
    "largest_speed": ("m s-1", "largest |v| on the last cycle, exact from the harmonic arcs"),
    "floquet_major": ("1", "larger Floquet multiplier of the flow over the last period, measured"),
    "floquet_minor": ("1", "smaller Floquet multiplier of the flow over the last period, measured"),
    **{key: (PARAMETERS[key].units, PARAMETERS[key].long_name, MODEL_INPUT) for key in MODEL_KEYS},
}


def checks_dataset(columns: Mapping[str, object], n_cycles: int) -> xr.Dataset:
    """The runs of the claims register, one row per case.

    Parameters
    ----------
    columns : mapping
        One sequence per name of :data:`CHECKS_COLUMNS` (what
        :func:`escapement.experiments.checks.measure_cases` returns), one value per case.
    n_cycles : int
        The cycles each case ran.

    Returns
    -------
    xarray.Dataset
        The checks dataset.
    """
    table = {name: (columns[name], *description) for name, description in CHECKS_COLUMNS.items()}
    summary = (
        "This file holds one row per run of the claims register: each run, with the parameters of its row, "
        "starts from rest at x0 and lasts n_cycles cycles; its fixed point, period, amplitude and multiplier "
        "are measured at the last cycle, beside the fixed point of Eq. (16) and the multiplier of Eq. (21); "
        "with the first cycle's period, the largest speed on the last cycle and both Floquet multipliers of "
        "the flow over the last period (central differences of the exact flow)."
    )
    return table_dataset(
        table, "Measured Poincare maps for the claims register", "checks", summary, solver="exact",
        n_cycles=int(n_cycles),
    )


def long_run_dataset(errors: Mapping, params: Parameters, x0: float, n_cycles: int,
                     ivp_method: str, ivp_rtol: float, ivp_cycles: int) -> xr.Dataset:
    """The long run: each method's errors against 50 digits at the sampled cycles.

    Parameters
    ----------
    errors : mapping
        What :func:`escapement.studies.long_run.long_run` returns.
    params : Parameters
        The model.
    x0 : float
        Release position, m.
    n_cycles, ivp_cycles : int
        The cycles of the closed forms and of ``solve_ivp``.
    ivp_method : str
        The ``solve_ivp`` method.
    ivp_rtol : float
        Its relative tolerance.

    Returns
    -------
    xarray.Dataset
        The long-run dataset (no wall time: those vary from run to run).
    """
    r = errors
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
    return assemble(variables, attrs)


def stability_dataset(b_values: np.ndarray, F_values: np.ndarray, grid: Mapping[str, np.ndarray],
                      constants: Mapping[str, float]) -> xr.Dataset:
    """One chunk of the stability and existence map over (b, F).

    Parameters
    ----------
    b_values, F_values : numpy.ndarray
        The axes.
    grid : mapping of str to numpy.ndarray
        ``multiplier``, ``multiplier_eq21``, ``fixed_point`` (m/s), ``period`` (s) and ``status``
        (:attr:`~escapement.model.status.Status.code`), each of shape ``(len(b_values), len(F_values))``.
    constants : mapping of str to float
        The other parameters, the same at every cell.

    Returns
    -------
    xarray.Dataset
        The chunk's dataset (no wall time: those vary from run to run).
    """
    dims = ("b", "F")
    coords = {
        name: (name, values, {"long_name": PARAMETERS[name].long_name, "units": PARAMETERS[name].units})
        for name, values in (("b", b_values), ("F", F_values))
    }

    def grid_var(values, units, long_name, **attrs):
        return xr.DataArray(np.asarray(values), dims=dims, coords=coords,
                            attrs={"units": units, "long_name": long_name, **attrs})

    variables = {
        "multiplier": grid_var(grid["multiplier"], "1", "multiplier mu_2 measured from the simulated return map"),
        "multiplier_eq21": grid_var(grid["multiplier_eq21"], "1", "multiplier (1 - b)**4 of Eq. (21)"),
        "fixed_point": grid_var(grid["fixed_point"], "m s-1", "fixed point of the simulated return map"),
        "period": grid_var(grid["period"], "s", "period of the cycle at the fixed point"),
        "outcome": xr.DataArray(
            np.asarray(grid["status"], dtype=np.int8), dims=dims, coords=coords,
            attrs={"long_name": "how the cycle from the fixed point ended", **flag_attributes()},
        ),
    }
    variables.update(parameter_variables(constants))
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
    return assemble(variables, attrs)
