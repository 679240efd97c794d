"""The simulation jobs: a scene's parameters in, one netCDF file out (never a figure).

Each scene is run by :mod:`escapement.experiments` and made a dataset by :mod:`escapement.io`;
the ``*_scene`` functions do both and return the dataset in memory, the ``simulate_*`` jobs log
the outcome and write it. Each job is a process of its own: the experiments that only one scene runs
are imported by its function (the long run's and the checks' bring mpmath), not by every job.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence

import xarray as xr

from ..experiments.figures import phase, poincare, shock
from ..io.netcdf import write_netcdf
from ..io.scenes import (
    checks_dataset,
    long_run_dataset,
    phase_dataset,
    poincare_dataset,
    shock_dataset,
    stability_dataset,
)
from ..io.studies import escapement_error_dataset, existence_dataset
from ..model.parameters import Parameters, check_initial_state
from ..model.status import Status
from .logs import logged
from .tables import write_timings

__all__ = [
    "checks_scene",
    "escapement_error_scene",
    "existence_scene",
    "long_run_scene",
    "phase_scene",
    "poincare_scene",
    "shock_scene",
    "simulate_checks",
    "simulate_escapement_error",
    "simulate_existence_map",
    "simulate_long_run",
    "simulate_phase",
    "simulate_poincare",
    "simulate_shock",
    "simulate_stability_chunk",
    "stability_chunk_scene",
]


def poincare_scene(params: Parameters, x0: float, n_cycles: int, amplitude: str = "largest_displacement"
                   ) -> xr.Dataset:
    """The Fig. 3 dataset of a run from ``x0`` (:func:`escapement.experiments.figures.poincare`)."""
    run = poincare(params, x0, n_cycles, amplitude)
    return poincare_dataset(run.solution, run.n_cycles, run.amplitude_definition, run.amplitude_long_name,
                            run.amplitude_cycle, run.amplitude, run.fixed_point_19)


def shock_scene(params: Parameters, x0: float, velocity_window: tuple[float, float],
                acceleration_window: tuple[float, float], samples_per_second: int) -> xr.Dataset:
    """The Fig. 4 dataset (:func:`escapement.experiments.figures.shock`)."""
    run = shock(params, x0, velocity_window, acceleration_window, samples_per_second)
    return shock_dataset(run.solution, run.t, run.window, run.velocity_window, run.acceleration_window,
                         run.samples_per_second)


def phase_scene(params: Parameters, x0: float, n_cycles: int, samples_per_period: int) -> xr.Dataset:
    """The dataset of one Fig. 5 panel (:func:`escapement.experiments.figures.phase`)."""
    run = phase(params, x0, n_cycles, samples_per_period)
    return phase_dataset(run.solution, run.t, run.n_cycles, run.samples_per_period)


def checks_scene(cases: Sequence[Mapping], n_cycles: int) -> xr.Dataset:
    """The checks dataset of the claims register (:func:`escapement.experiments.checks.measure_cases`)."""
    from ..experiments.checks import measure_cases
    return checks_dataset(measure_cases(cases, n_cycles), n_cycles)


def long_run_scene(params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float,
                   ivp_cycles: int) -> tuple[xr.Dataset, dict[str, float]]:
    """The long-run dataset and, apart from it, each method's wall time
    (:func:`escapement.experiments.long_run.run_long`)."""
    from ..experiments.long_run import run_long
    run = run_long(params, x0, n_cycles, ivp_method, ivp_rtol, ivp_cycles)
    ds = long_run_dataset(run.errors, params, x0, run.n_cycles, run.ivp_method, run.ivp_rtol, run.ivp_cycles)
    return ds, run.timings


def stability_chunk_scene(model: Mapping, b_values: Sequence[float], F_values: Sequence[float],
                          speed_sample: int = 100) -> tuple[xr.Dataset, dict[str, float]]:
    """The dataset of one chunk of the stability map and, apart from it, the cost per trajectory of
    each solver (:func:`escapement.experiments.stability.stability_chunk`)."""
    from ..experiments.stability import stability_chunk
    chunk = stability_chunk(model, b_values, F_values, speed_sample)
    grid = {"multiplier": chunk.multiplier, "multiplier_eq21": chunk.multiplier_eq21,
            "fixed_point": chunk.fixed_point, "period": chunk.period, "status": chunk.status}
    return stability_dataset(chunk.b_values, chunk.F_values, grid, chunk.constants), chunk.timings


def escapement_error_scene(base: Parameters, forces: Sequence[float], zones: Mapping[str, Sequence[float]]
                           ) -> xr.Dataset:
    """The escapement-error dataset (:func:`escapement.experiments.escapement_error.escapement_error`)."""
    from ..experiments.escapement_error import escapement_error
    result = escapement_error(base, forces, zones)
    return escapement_error_dataset(result.zones, result.forces, result.values, result.max_period_difference,
                                    result.seconds_per_day, result.model)


def existence_scene(model: Mapping, block: Mapping) -> xr.Dataset:
    """The existence map's dataset over the cell centres of the block's a3 and F axes
    (:func:`escapement.experiments.existence.existence_map`)."""
    from ..experiments.existence import axis_centres, existence_map
    run = existence_map(model, axis_centres(block["a3"]), axis_centres(block["F"]), float(block["x0"]),
                        int(block["n_cycles"]), float(block["tolerance"]), float(block.get("v0", 0.0)))
    return existence_dataset(run.a3_values, run.F_values, run.status, run.converged, run.threshold,
                             run.threshold_mirror, run.constants, run.n_cycles, run.tolerance)


def _x0(scene: Mapping) -> float:
    return check_initial_state(scene["x0"], scene.get("v0", 0.0))[0]


def _report(logger: logging.Logger, scene: Mapping, ds) -> None:
    logger.info("parameters: %s", dict(scene))
    logger.info("outcome: %s: %s", ds.attrs["outcome"], ds.attrs["outcome_message"])


def simulate_poincare(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_poincare") as logger:
        ds = poincare_scene(Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"], scene["amplitude"])
        _report(logger, scene, ds)
        write_netcdf(ds, output)


def simulate_shock(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_shock") as logger:
        ds = shock_scene(
            Parameters.from_mapping(scene),
            _x0(scene),
            scene["velocity_window"],
            scene["acceleration_window"],
            scene["samples_per_second"],
        )
        _report(logger, scene, ds)
        write_netcdf(ds, output)


def simulate_phase(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_phase") as logger:
        ds = phase_scene(
            Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"], scene["samples_per_period"]
        )
        _report(logger, scene, ds)
        write_netcdf(ds, output)


def simulate_checks(cases: Sequence[Mapping], n_cycles: int, output: str, log: str) -> None:
    with logged(log, "simulate_checks") as logger:
        ds = checks_scene([dict(c) for c in cases], n_cycles)
        for label, outcome, mu in zip(ds["label"].values, ds["outcome"].values, ds["multiplier"].values):
            logger.info("%s: %s, measured multiplier %.12g", label, outcome, mu)
        write_netcdf(ds, output)


def simulate_long_run(scene: Mapping, output: str, timing_output: str, log: str) -> None:
    with logged(log, "simulate_long_run") as logger:
        ds, timings = long_run_scene(
            Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"], scene["ivp_method"],
            scene["ivp_rtol"], scene["ivp_cycles"],
        )
        for key in ("max_velocity_deviation", "max_period_deviation"):
            logger.info("%s: %.3e", key, float(ds[key]))
        for key, seconds in timings.items():
            logger.info("%s: %.3e", key, seconds)
        write_netcdf(ds, output)
        write_timings(timings, timing_output)


def simulate_stability_chunk(model: Mapping, b_values: Sequence[float], F_values: Sequence[float], output: str,
                             timing_output: str, log: str) -> None:
    with logged(log, "simulate_stability_chunk") as logger:
        ds, timings = stability_chunk_scene(dict(model), b_values, F_values)
        logger.info("per trajectory: ensemble %.3e s, scalar %.3e s", timings["ensemble_seconds_per_trajectory"],
                    timings["scalar_seconds_per_trajectory"])
        write_netcdf(ds, output)
        write_timings(timings, timing_output)


def simulate_escapement_error(model: Mapping, forces: Sequence[float], zones: Mapping[str, Sequence[float]],
                              output: str, log: str) -> None:
    """The escapement-error study: the limit cycle's rate for each force and impulse zone."""
    with logged(log, "simulate_escapement_error") as logger:
        ds = escapement_error_scene(Parameters.from_mapping(model), forces, zones)
        logger.info("%d zones x %d forces; corrected Eqs. (24)-(25) against the exact solver: %.1e (relative)",
                    ds.sizes["zone"], ds.sizes["F"], float(ds["max_period_difference"]))
        write_netcdf(ds, output)


def simulate_existence_map(model: Mapping, block: Mapping, output: str, log: str) -> None:
    """The existence map of an asymmetric escapement over (a3, F), the configuration's ``existence_map``."""
    with logged(log, "simulate_existence_map") as logger:
        ds = existence_scene(dict(model), dict(block))
        counts = {s.value: int((ds["outcome"].values == s.code).sum()) for s in Status}
        logger.info("outcomes: %s; limit cycle reached in %d of %d runs", counts, int(ds["converged"].values.sum()),
                    ds["converged"].size)
        write_netcdf(ds, output)
