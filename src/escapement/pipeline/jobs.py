"""The work behind each workflow rule, so that the workflow's scripts stay thin.

Every job logs what it did to its log file, writes its outputs atomically and
reads its inputs through :func:`escapement.io.netcdf.read_netcdf`, which names a
damaged file.
"""

from __future__ import annotations

import contextlib
import logging
import time
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

from ..io.atomic import write_csv
from ..io.netcdf import DatasetError, read_netcdf, write_netcdf
from ..io.provenance import history_line, source_string
from ..io.scenes import (
    checks_scene,
    long_run_scene,
    phase_scene,
    poincare_scene,
    shock_scene,
    stability_chunk_scene,
)
from ..model.parameters import Parameters, check_initial_state
from ..paper.claims import Evidence, evaluate, load_claims, read_claims_csv, write_claims_csv
from ..plotting import fig3, fig4, fig5, long_run, save_figure, stability_map, work_precision
from ..studies.benchmark import work_precision as run_benchmark
from ..studies.stress import run_all
from .docs import markdown_table, render, write_text
from .facts import collect_facts


__all__ = [
    "run_stress",
    "merge_stability",
    "plot_long_run",
    "plot_stability_map",
    "plot_work_precision",
    "run_work_precision",
    "simulate_long_run",
    "simulate_stability_chunk",
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
    logger = logging.getLogger(f"escapement.pipeline.{what}")
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


def _x0(scene: Mapping) -> float:
    return check_initial_state(scene["x0"], scene.get("v0", 0.0))[0]


def _report(logger: logging.Logger, scene: Mapping, ds) -> None:
    logger.info("parameters: %s", dict(scene))
    logger.info("outcome: %s: %s", ds.attrs["outcome"], ds.attrs["outcome_message"])


def simulate_poincare(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_poincare") as logger:
        ds = poincare_scene(Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"])
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


CYCLE_VARIABLES = ("cycle", "velocity_before_impact", "period", "amplitude")
SHOCK_VARIABLES = ("t", "velocity", "acceleration", "impact_time", "impulse", "energy_dissipated", "event_time")
PHASE_VARIABLES = ("t", "displacement", "velocity", "impact_time", "impact_position", "velocity_after")


def plot_fig3(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig3"):
        cases = {label: read_netcdf(path, CYCLE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig3(cases), png, pdf)


def plot_fig4(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig4"):
        save_figure(fig4(read_netcdf(path, SHOCK_VARIABLES)), png, pdf)


def plot_fig5(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig5"):
        panels = {label: read_netcdf(path, PHASE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig5(panels), png, pdf)


def check_claims(
    register: str, fig3: Mapping[str, str], fig4: str, fig5: Mapping[str, str], checks: str, output: str, log: str
) -> None:
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


def render_docs(
    claims: str, benchmark: str, long_run: str, stability: str, stress: str, templates: Sequence[str],
    outputs: Sequence[str], log: str,
) -> None:
    import csv

    with logged(log, "render_docs"):
        rows = read_claims_csv(claims)
        facts = collect_facts(
            read_work_precision(benchmark),
            read_netcdf(long_run, ("cycle", "drift_exact", "drift_ivp", "error_time_exact", "error_time_ivp")),
            read_netcdf(stability, ("b", "F", "multiplier", "multiplier_eq21", "outcome")),
        )
        with open(stress, newline="") as handle:
            stress_rows = list(csv.DictReader(handle))
        if not stress_rows or list(stress_rows[0]) != STRESS_COLUMNS:
            raise ValueError(f"{stress}: not a stress summary with the columns {', '.join(STRESS_COLUMNS)}")
        tables = {"stress": markdown_table(stress_rows, ["regime", "outcome", "check", "passed", "detail"])}
        for template, output in zip(templates, outputs):
            write_text(render(Path(template).read_text(), rows, template, facts, tables), output)


def run_work_precision(scene: Mapping, settings: Mapping[str, list], output: str, log: str) -> None:
    with logged(log, "run_work_precision") as logger:
        rows = run_benchmark(
            Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"],
            {k: list(v) for k, v in settings.items()}, scene["repeats"], log=logger.info,
        )
        formatted = [{k: (f"{v:.6e}" if isinstance(v, float) else v) for k, v in row.items()} for row in rows]
        write_csv(formatted, list(rows[0]), output)


def read_work_precision(path: str) -> list[dict]:
    import csv

    try:
        with open(path, newline="") as handle:
            rows = list(csv.DictReader(handle))
    except OSError as err:
        raise DatasetError(f"{path}: cannot be read ({err})") from err
    expected = ["method", "setting", "wall_s", "error_velocity", "error_time"]
    if not rows or list(rows[0]) != expected:
        raise DatasetError(f"{path}: not a work-precision table with the columns {', '.join(expected)}")
    return rows


def plot_work_precision(table: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_work_precision"):
        save_figure(work_precision(read_work_precision(table)), png, pdf)


def simulate_long_run(scene: Mapping, output: str, log: str) -> None:
    with logged(log, "simulate_long_run") as logger:
        ds = long_run_scene(
            Parameters.from_mapping(scene), _x0(scene), scene["n_cycles"], scene["ivp_method"],
            scene["ivp_rtol"], scene["ivp_cycles"],
        )
        for key in ("max_velocity_deviation", "max_period_deviation", "exact_wall_s", "ivp_wall_s"):
            logger.info("%s: %.3e", key, ds.attrs[key])
        write_netcdf(ds, output)


def plot_long_run(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_long_run"):
        save_figure(long_run(read_netcdf(path, ("cycle", "drift_exact", "drift_ivp"))), png, pdf)


def simulate_stability_chunk(model: Mapping, b_values: Sequence[float], F_values: Sequence[float], output: str,
                             log: str) -> None:
    with logged(log, "simulate_stability_chunk") as logger:
        ds = stability_chunk_scene(dict(model), b_values, F_values)
        logger.info("per trajectory: ensemble %.3e s, scalar %.3e s", ds.attrs["ensemble_seconds_per_trajectory"],
                    ds.attrs["scalar_seconds_per_trajectory"])
        write_netcdf(ds, output)


def merge_stability(paths: Sequence[str], output: str, log: str) -> None:
    import numpy as np
    import xarray as xr

    with logged(log, "merge_stability") as logger:
        chunks = [read_netcdf(p, ("b", "F", "multiplier", "outcome")) for p in paths]
        merged = xr.concat(chunks, dim="b", combine_attrs="override")  # the first chunk's attributes...
        merged.attrs.update(  # ...with the provenance of this merge
            source=source_string(), history=history_line(f"merged from {len(chunks)} chunks by escapement")
        )
        ratios = [c.attrs["scalar_seconds_per_trajectory"] / c.attrs["ensemble_seconds_per_trajectory"] for c in chunks]
        merged.attrs.update(
            ensemble_speedup_per_trajectory=float(np.median(ratios)),
            ensemble_seconds_per_trajectory=float(np.median([c.attrs["ensemble_seconds_per_trajectory"] for c in chunks])),
            scalar_seconds_per_trajectory=float(np.median([c.attrs["scalar_seconds_per_trajectory"] for c in chunks])),
            chunks=len(chunks),
        )
        logger.info("ensemble speed-up per trajectory (median over chunks): %.1f", merged.attrs["ensemble_speedup_per_trajectory"])
        write_netcdf(merged, output)


def plot_stability_map(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_stability_map"):
        save_figure(stability_map(read_netcdf(path, ("b", "F", "multiplier", "multiplier_eq21", "outcome"))), png, pdf)


STRESS_COLUMNS = ["case", "regime", "outcome", "check", "passed", "detail"]


def run_stress(long_run: str, output: str, log: str) -> None:
    """Every stress case, and the very long run's bounds, as one CSV row each."""
    with logged(log, "run_stress") as logger:
        rows = run_all()
        lr = read_netcdf(long_run, ("cycle", "error_time_exact"))
        bounded = (lr.attrs["max_velocity_deviation"] <= 1e-12 and lr.attrs["max_period_deviation"] <= 1e-12
                   and not lr.attrs["any_nan"] and float(lr["error_time_exact"].max()) <= 1e-14)
        rows.append({
            "case": "very_long_run",
            "regime": f"very long runs: {int(lr.attrs['n_cycles'])} cycles, {4 * int(lr.attrs['n_cycles'])} events",
            "outcome": "completed",
            "check": "no NaN; velocity and period within 1e-12 of the fixed point once converged; impact time within "
                     "1e-14 of 50 digits",
            "passed": "yes" if bounded else "no",
            "detail": f"velocity {lr.attrs['max_velocity_deviation']:.1e}, period {lr.attrs['max_period_deviation']:.1e}, "
                      f"impact time {float(lr['error_time_exact'].max()):.1e}",
        })
        for row in rows:
            logger.info("%s: %s (%s)", row["case"], row["passed"], row["detail"])
        write_csv(rows, STRESS_COLUMNS, output)
