"""The printed axes as data: each candidate reading of the paper's unstated choices scored by the
axis limits it would give.

For every reading (:mod:`escapement.studies.readings`), every scored axis of its panel
(:mod:`escapement.paper.printed_axes`) and every autoscaling variant
(:data:`escapement.plotting.autoscale.VARIANTS`), the limits matplotlib gives the reading's
values with the printed tick step are compared with the printed limits: ``matches`` counts the
limits reproduced exactly (0, 1 or 2). :func:`best_readings` then names, per panel, the
readings that reproduce the most limits over the panel's scored axes.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

import numpy as np
import xarray as xr

from ..io.atomic import write_csv
from ..paper.printed_axes import FIG5_PANEL_K, PANELS, Panel, limits_match
from ..plotting.autoscale import VARIANTS, autoscaled_limits_many
from ..studies.readings import Reading, all_readings
from .logs import logged
from .scores import CLAIM_AUTOSCALE, COLUMNS, best_readings, best_readings_table, read_scores

__all__ = ["CLAIM_AUTOSCALE", "COLUMNS", "PAPER_SETTINGS", "best_readings", "best_readings_table", "read_scores", "limits_match", "scene_axes", "score_readings",
           "score_table"]

#: Sec. 4 of the paper, with the replication's sampling (the blocks of the workflow's configuration)
PAPER_SETTINGS: dict = {
    "model": {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05},
    "fig3": {"n_cycles": 50, "cases": {"a": {"F": 1.0, "x0": 1.0}, "b": {"F": 0.5, "x0": 3.0}}},
    "fig4": {"velocity_window": [80.0, 87.0], "acceleration_window": [81.0, 85.0], "samples_per_second": 1000},
    "fig5": {"K": [0.1, 1.0, 10.0], "n_cycles": 60, "samples_per_period": 400},
}


def _panel_of(reading: Reading, panels: Iterable[Panel]) -> Panel:
    for p in panels:
        if p.figure == reading.figure and p.name == reading.panel:
            return p
    raise KeyError(f"no printed panel for Fig. {reading.figure} {reading.panel!r} (reading {reading.name!r})")


def score_table(readings: Iterable[Reading], panels: Iterable[Panel] = PANELS,
                variants: Mapping[str, float] = VARIANTS) -> list[dict]:
    """One row per reading, scored axis of its panel and autoscaling variant (numbers as floats),
    in the order of the readings, then the axes (x, y), then the variants."""
    panels = tuple(panels)
    readings = list(readings)
    jobs = []  # (reading, axis name, axis, finite values)
    for reading in readings:
        panel = _panel_of(reading, panels)
        for axis_name, axis in panel.axes.items():
            if axis.scored:
                values = np.asarray(reading.x if axis_name == "x" else reading.y, dtype=float).ravel()
                jobs.append((reading, axis_name, axis, values[np.isfinite(values)]))
    # one matplotlib axes per tick step and variant
    limits: dict[tuple[int, str], tuple[float, float]] = {}
    for step in {axis.step for _, _, axis, _ in jobs}:
        batch = [i for i, (_, _, axis, values) in enumerate(jobs) if axis.step == step and values.size]
        for variant, margin in variants.items():
            found = autoscaled_limits_many([jobs[i][3] for i in batch], step, margin)
            limits.update({(i, variant): lim for i, lim in zip(batch, found)})
    rows = []
    for i, (reading, axis_name, axis, values) in enumerate(jobs):
        for variant in variants:
            low, high = limits.get((i, variant), (math.nan, math.nan))
            empty = not values.size
            rows.append({
                "figure": reading.figure, "panel": reading.panel, "axis": axis_name, "reading": reading.name,
                "outcome": reading.outcome, "autoscale": variant,
                "data_min": math.nan if empty else float(values.min()),
                "data_max": math.nan if empty else float(values.max()),
                "low": low, "high": high, "printed_low": axis.low, "printed_high": axis.high, "step": axis.step,
                "matches": 0 if empty else limits_match(low, high, axis.low, axis.high, axis.step),
            })
    return rows


def _scene_series(figure: str, name: str, fig3: Mapping[str, xr.Dataset], fig4: xr.Dataset,
                  fig5: Mapping[str, xr.Dataset]) -> tuple[np.ndarray, np.ndarray] | None:
    """The points the pipeline's own figure draws in the printed panel ``name`` of Fig. ``figure``,
    as ``(x, y)``, or None if no output holds that panel (a Fig. 3 case or a Fig. 5 spring
    constant the configuration does not have, or a run that left the regime, whose claims are not
    evaluated)."""
    if figure == "3":
        case, quantity = name.split("/")
        if case not in fig3 or not _completed(fig3[case]):
            return None
        variable = fig3[case][{"velocity": "velocity_before_impact"}.get(quantity, quantity)]
        return variable[variable.dims[0]].values, variable.values
    if figure == "4":
        if not _completed(fig4):
            return None
        lo, hi = fig4[f"{name}_window"].values
        window = fig4[name].sel(t=slice(lo, hi))
        return window["t"].values, window.values
    for ds in fig5.values():
        if math.isclose(float(ds["K"]), FIG5_PANEL_K[name], rel_tol=1e-12) and _completed(ds):
            return ds["displacement"].values, ds["velocity"].values
    return None


def _completed(ds: xr.Dataset) -> bool:
    return ds.attrs.get("outcome", "completed") == "completed"


def scene_axes(fig3: Mapping[str, xr.Dataset], fig4: xr.Dataset, fig5: Mapping[str, xr.Dataset],
               autoscale: str = CLAIM_AUTOSCALE) -> dict[tuple[str, str], dict[str, tuple[float, float]]]:
    """The limits each printed panel's scored axes get when the pipeline's own outputs (Fig. 3 by
    case label, Fig. 4, Fig. 5 by any label) are autoscaled with the printed tick step:
    ``{(figure, panel): {"x": (low, high), "y": (low, high)}}`` (scored axes only; a panel no output
    holds is left out)."""
    margin = VARIANTS[autoscale]  # CLAIM_AUTOSCALE names one of the variants
    found: dict[tuple[str, str], dict[str, tuple[float, float]]] = {}
    for p in PANELS:
        series = _scene_series(p.figure, p.name, fig3, fig4, fig5)
        if series is None:
            continue
        found[(p.figure, p.name)] = {
            axis_name: autoscaled_limits_many([values], axis.step, margin)[0]
            for (axis_name, axis), values in zip(p.axes.items(), series) if axis.scored
        }
    return found


def _formatted(row: Mapping) -> dict:
    out = dict(row)
    for name in ("data_min", "data_max"):
        out[name] = f"{row[name]:.8g}"
    for name in ("low", "high", "printed_low", "printed_high", "step"):
        out[name] = f"{row[name]:.10g}"
    return out


def score_readings(output_csv: str, log: str, settings: Mapping | None = None) -> None:
    """Job: score every reading against the printed axes and write the table as CSV; the log
    names the best-supported readings of each panel. ``settings`` holds the configuration's
    blocks ``model``, ``fig3``, ``fig4``, ``fig5`` (default :data:`PAPER_SETTINGS`)."""
    with logged(log, "score_readings") as logger:
        readings = all_readings(PAPER_SETTINGS if settings is None else settings)
        logger.info("%d readings", len(readings))
        rows = score_table(readings)
        for variant in VARIANTS:
            for best in best_readings(rows, autoscale=variant):
                logger.info("[%s] Fig. %s %s: %d/%d limits by %s", variant, best["figure"], best["panel"],
                            best["score"], best["out_of"], "; ".join(name for name, _ in best["best"]))
        write_csv([_formatted(r) for r in rows], COLUMNS, output_csv)
