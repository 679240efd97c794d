"""The score table of the readings of the printed axes, read back and summarised per panel for the
documents. Imports neither the solvers nor matplotlib: the job that writes the documents reads the
table that :mod:`escapement.pipeline.readings` wrote."""

from __future__ import annotations

import csv
from collections import defaultdict
from collections.abc import Iterable, Mapping

__all__ = ["CLAIM_AUTOSCALE", "COLUMNS", "best_readings", "best_readings_table", "read_scores"]

COLUMNS = ["figure", "panel", "axis", "reading", "outcome", "autoscale", "data_min", "data_max", "low", "high",
           "printed_low", "printed_high", "step", "matches"]

#: the autoscaling the axis claims use: limits rounded out to the printed ticks, no margin (the
#: behaviour of MATLAB's automatic limits, in which the paper's figures appear to be drawn)
CLAIM_AUTOSCALE = "round, margin 0"


def best_readings(rows: Iterable[Mapping], autoscale: str | None = None) -> list[dict]:
    """Per panel (in the order met), the readings that reproduce the most printed limits over the
    panel's scored axes: ``{"figure", "panel", "score", "out_of", "best": [(reading, autoscale), ...]}``.
    With ``autoscale`` only that variant's rows count."""
    totals: dict[tuple[str, str], dict[tuple[str, str], int]] = defaultdict(lambda: defaultdict(int))
    axes: dict[tuple[str, str], set[str]] = defaultdict(set)
    for row in rows:
        if autoscale is not None and row["autoscale"] != autoscale:
            continue
        key = (str(row["figure"]), str(row["panel"]))
        totals[key][(row["reading"], row["autoscale"])] += int(row["matches"])
        axes[key].add(row["axis"])
    result = []
    for key, scores in totals.items():
        top = max(scores.values())
        result.append({
            "figure": key[0], "panel": key[1], "score": top, "out_of": 2 * len(axes[key]),
            "best": [choice for choice, score in scores.items() if score == top],
        })
    return result


def read_scores(path: str) -> list[dict]:
    """The score table written by :func:`score_readings`, numbers as floats and ``matches`` as int."""
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    if not rows or list(rows[0]) != COLUMNS:
        raise ValueError(f"{path}: not a score table of the readings (columns {COLUMNS})")
    for row in rows:
        for name in ("data_min", "data_max", "low", "high", "printed_low", "printed_high", "step"):
            row[name] = float(row[name])
        row["matches"] = int(row["matches"])
    return rows


def best_readings_table(rows: Iterable[Mapping], autoscale: str = CLAIM_AUTOSCALE) -> list[dict[str, str]]:
    """One row per printed panel for the documents: its printed limits, and the readings that
    reproduce the most of them under ``autoscale``, with how many."""
    rows = [r for r in rows if r["autoscale"] == autoscale]
    printed: dict[tuple[str, str], dict[str, str]] = {}
    for r in rows:
        printed.setdefault((str(r["figure"]), str(r["panel"])), {})[r["axis"]] = (
            f"{r['axis']} {r['printed_low']:g} to {r['printed_high']:g}")
    table = []
    for best in best_readings(rows, autoscale=autoscale):
        key = (best["figure"], best["panel"])
        table.append({
            "figure": best["figure"],
            "panel": best["panel"],
            "printed limits": "; ".join(printed[key][axis] for axis in sorted(printed[key])),
            "limits reproduced": f"{best['score']} of {best['out_of']}",
            "best-supported readings": "<br>".join(name for name, _ in best["best"]),  # a name may hold "; "
        })
    return table
