"""The simulation jobs: a scene's parameters in, one netCDF file out (never a figure)."""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence

from ..io.netcdf import write_netcdf
from ..io.scenes import (
    checks_scene,
    long_run_scene,
    phase_scene,
    poincare_scene,
    shock_scene,
    stability_chunk_scene,
)
from ..io.studies import escapement_error_scene
from ..model.parameters import Parameters, check_initial_state
from .logs import logged
from .tables import write_timings

__all__ = [
    "simulate_checks",
    "simulate_escapement_error",
    "simulate_long_run",
    "simulate_phase",
    "simulate_poincare",
    "simulate_shock",
    "simulate_stability_chunk",
]


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
