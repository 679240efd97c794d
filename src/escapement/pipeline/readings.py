"""The printed axes as data: each candidate reading of the paper's unstated choices scored by the axis limits it would
give. For every reading, scored axis, margin and tick mode, ``matches`` counts the printed limits that matplotlib's
limits of the reading's values reproduce exactly (0, 1 or 2).
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Mapping

import numpy as np

from ..io.netcdf import write_csv
from ..paper.printed_axes import PANELS, limits_match
from ..plotting.autoscale import VARIANTS, autoscaled_axes
from ..studies.readings import Reading, Runs, all_readings
from .logs import logged
from ..verdict.scores import COLUMNS, PRINTED_STEP, TICKS, joint_candidates, panel_candidates, summary

__all__ = ["COLUMNS", "equivalence", "limits_match", "score_readings", "score_table"]

#: plotted values equal to this relative tolerance are the same values (the rounding of a mirror image)
SAME_VALUES_RTOL = 1e-9


def _same(a: Reading, b: Reading) -> bool:
    return all(u.shape == v.shape and np.allclose(u, v, rtol=SAME_VALUES_RTOL, atol=0.0, equal_nan=True)
               for u, v in ((np.asarray(p, float), np.asarray(q, float)) for p, q in ((a.x, b.x), (a.y, b.y))))


def equivalence(readings: Iterable[Reading]) -> dict[tuple[str, str, str], str]:
    """For each reading, keyed ``(figure, panel, name)``, the name of the first reading of its panel that plots the
    same values (its own name if none before it does)."""
    first: dict[tuple[str, str], list[Reading]] = {}  # the readings that head a group of the same values, by panel
    found: dict[tuple[str, str, str], str] = {}
    for r in readings:
        key = (r.figure, r.panel, r.name)
        if key in found:
            raise ValueError(f"the reading {r.name!r} of Fig. {r.figure} {r.panel!r} appears twice")
        heads = first.setdefault((r.figure, r.panel), [])
        found[key] = next((h.name for h in heads if _same(h, r)), r.name)
        if found[key] == r.name:
            heads.append(r)
    return found


def score_table(readings: Iterable[Reading]) -> list[dict]:
    """One row per reading, scored axis of its panel, margin and tick mode (numbers as floats), in that order."""
    printed, readings = {(p.figure, p.name): p for p in PANELS}, list(readings)
    same = equivalence(readings)
    jobs = []  # (reading, axis name, axis, finite values)
    for reading in readings:
        for axis_name, axis in printed[(reading.figure, reading.panel)].axes.items():
            if axis.scored:
                values = np.asarray(reading.x if axis_name == "x" else reading.y, dtype=float).ravel()
                jobs.append((reading, axis_name, axis, values[np.isfinite(values)]))
    # one matplotlib axes per tick step (printed, or the default locator on the axis printed), margin
    found: dict[tuple[int, str, str], tuple[float, float, float]] = {}
    for ticks in TICKS:
        for kind in {(axis.step if ticks == PRINTED_STEP else None, name) for _, name, axis, _ in jobs}:
            batch = [i for i, (_, name, axis, values) in enumerate(jobs) if values.size
                     and (axis.step if ticks == PRINTED_STEP else None, name) == kind]
            for variant, margin in VARIANTS.items():
                limits = autoscaled_axes([jobs[i][3] for i in batch], kind[0], margin, axis=kind[1])
                found.update({(i, variant, ticks): lim for i, lim in zip(batch, limits)})
    rows = []
    for i, (reading, axis_name, axis, values) in enumerate(jobs):
        low_data, high_data = (float(values.min()), float(values.max())) if values.size else (math.nan, math.nan)
        for variant in VARIANTS:
            for ticks in TICKS:
                low, high, tick_step = found.get((i, variant, ticks), (math.nan, math.nan, math.nan))
                rows.append({
                    "figure": reading.figure, "panel": reading.panel, "axis": axis_name, "reading": reading.name,
                    "outcome": reading.outcome, "autoscale": variant, "ticks": ticks,
                    "data_min": low_data, "data_max": high_data, "low": low, "high": high, "tick_step": tick_step,
                    "printed_low": axis.low, "printed_high": axis.high, "step": axis.step,
                    "matches": limits_match(low, high, axis.low, axis.high, axis.step) if values.size else 0,
                    "same_values_as": same[(reading.figure, reading.panel, reading.name)],
                })
    return rows


def _formatted(row: Mapping) -> dict:
    """A row as the table writes it: the data's extremes to 8 digits, the limits and steps to 10."""
    return {**row, **{k: f"{row[k]:.8g}" for k in ("data_min", "data_max")},
            **{k: f"{row[k]:.10g}" for k in ("low", "high", "tick_step", "printed_low", "printed_high", "step")}}


def score_readings(output_csv: str, log: str, settings: Mapping) -> None:
    """The job: every reading scored, written as CSV, the readings tied at the best score logged per panel and
    margin; ``settings`` holds the blocks ``model``, ``fig3``, ``fig4`` and ``fig5`` of config/paper.yaml."""
    with logged(log, "score_readings") as logger:
        start, runs = time.perf_counter(), Runs(settings["model"])
        readings = all_readings(settings, runs)
        logger.info("%d readings from %d runs in %.2f s", len(readings), runs.solved, time.perf_counter() - start)
        rows = score_table(readings)
        logger.info("%d scores (%s) in %.2f s", len(rows), ", ".join(TICKS), time.perf_counter() - start)
        for variant in VARIANTS:
            for (figure, panel), candidates in panel_candidates(rows, variant).items():
                logger.info("[%s] Fig. %s %s: %s; %s", variant, figure, panel, *summary(candidates))
            logger.info("[%s] Fig. 4, both panels: %s; %s", variant, *summary(joint_candidates(rows, "4", variant)))
        write_csv([_formatted(r) for r in rows], COLUMNS, output_csv)
