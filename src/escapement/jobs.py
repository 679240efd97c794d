"""The work behind each workflow rule, so that the workflow's scripts stay thin.

Every job logs what it did to its log file, writes its outputs atomically and
reads its inputs through :func:`escapement.netcdf_io.read_netcdf`, which names a
damaged file.
"""

from __future__ import annotations

import contextlib
import logging
import time
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

from .netcdf_io import read_netcdf, write_netcdf
from .scene_config import initial_state_from, parameters_from
from .scenes import phase_scene, poincare_scene, shock_scene

__all__ = ["simulate_poincare", "simulate_shock", "simulate_phase", "plot_fig3", "plot_fig4", "plot_fig5"]


@contextlib.contextmanager
def logged(log: str | Path, what: str) -> Iterator[logging.Logger]:
    """Log to ``log`` (replacing it) for the duration of one job."""
    logger = logging.getLogger(f"escapement.jobs.{what}")
    logger.setLevel(logging.INFO)
    Path(log).parent.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(log, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    logger.addHandler(handler)
    start = time.perf_counter()
    try:
        yield logger
        logger.info("%s done in %.3f s", what, time.perf_counter() - start)
    except Exception:
        logger.exception("%s failed", what)
        raise
    finally:
        logger.removeHandler(handler)
        handler.close()


def _report(logger: logging.Logger, scene: Mapping, ds) -> None:
    logger.info("parameters: %s", dict(scene))
    logger.info("outcome: %s: %s", ds.attrs["outcome"], ds.attrs["outcome_message"])


def simulate_poincare(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_poincare") as logger:
        ds = poincare_scene(parameters_from(scene), initial_state_from(scene)[0], scene["n_cycles"])
        _report(logger, scene, ds)
        write_netcdf(ds, output)


def simulate_shock(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_shock") as logger:
        ds = shock_scene(
            parameters_from(scene),
            initial_state_from(scene)[0],
            scene["velocity_window"],
            scene["acceleration_window"],
            scene["samples_per_second"],
        )
        _report(logger, scene, ds)
        write_netcdf(ds, output)


def simulate_phase(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_phase") as logger:
        ds = phase_scene(
            parameters_from(scene), initial_state_from(scene)[0], scene["n_cycles"], scene["samples_per_period"]
        )
        _report(logger, scene, ds)
        write_netcdf(ds, output)


CYCLE_VARIABLES = ("cycle", "velocity_before_impact", "period", "amplitude")
SHOCK_VARIABLES = ("t", "velocity", "acceleration", "impact_time", "impulse", "energy_dissipated", "event_time")
PHASE_VARIABLES = ("t", "displacement", "velocity", "impact_time", "impact_position", "velocity_after")


def plot_fig3(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    from .plotting import fig3, save_figure

    with logged(log, "plot_fig3"):
        cases = {label: read_netcdf(path, CYCLE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig3(cases), png, pdf)


def plot_fig4(path: str, png: str, pdf: str, log: str) -> None:
    from .plotting import fig4, save_figure

    with logged(log, "plot_fig4"):
        save_figure(fig4(read_netcdf(path, SHOCK_VARIABLES)), png, pdf)


def plot_fig5(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    from .plotting import fig5, save_figure

    with logged(log, "plot_fig5"):
        panels = {label: read_netcdf(path, PHASE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig5(panels), png, pdf)
