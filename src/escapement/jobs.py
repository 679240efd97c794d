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
from .scenes import checks_scene, phase_scene, poincare_scene, shock_scene

__all__ = [
    "check_claims",
    "render_docs",
    "simulate_poincare",
    "simulate_shock",
    "simulate_phase",
    "simulate_checks",
    "plot_fig3",
    "plot_fig4",
    "plot_fig5",
]


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


def simulate_checks(cases: Sequence[Mapping], n_cycles: int, output: str, log: str) -> None:
    with logged(log, "simulate_checks") as logger:
        ds = checks_scene([dict(c) for c in cases], n_cycles)
        for label, outcome, mu in zip(ds["label"].values, ds["outcome"].values, ds["multiplier"].values):
            logger.info("%s: %s, measured multiplier %.12g", label, outcome, mu)
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


def check_claims(
    register: str, fig3: Mapping[str, str], fig4: str, fig5: Mapping[str, str], checks: str, output: str, log: str
) -> None:
    from .claims import Evidence, evaluate, load_claims, write_claims_csv

    with logged(log, "check_claims") as logger:
        evidence = Evidence(
            fig3={label: read_netcdf(path, CYCLE_VARIABLES + ("event_time", "event_kind")) for label, path in fig3.items()},
            fig4=read_netcdf(fig4, SHOCK_VARIABLES),
            fig5={label: read_netcdf(path, PHASE_VARIABLES) for label, path in fig5.items()},
            checks=read_netcdf(checks, ("label", "group", "multiplier", "period")),
        )
        rows = evaluate(load_claims(register), evidence)
        for row in rows:
            logger.info("%s: %s: %s", row["claim_id"], row["status"], row["replicated_value"])
        write_claims_csv(rows, output)


def render_docs(claims: str, templates: Sequence[str], outputs: Sequence[str], log: str) -> None:
    from .claims import read_claims_csv
    from .docs import render, write_text

    with logged(log, "render_docs"):
        rows = read_claims_csv(claims)
        for template, output in zip(templates, outputs):
            write_text(render(Path(template).read_text(), rows, template), output)
