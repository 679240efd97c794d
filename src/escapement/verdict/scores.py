"""The score table of the readings of the printed axes (written by :mod:`escapement.pipeline.readings`), read back
and summarised per panel: the readings tied at the best score, those that plot the same values grouped.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from ..io.netcdf import read_csv
from ..paper.printed_axes import PANELS

__all__ = ["CLAIM_AUTOSCALE", "COLUMNS", "DEFAULT_LOCATOR", "PRINTED_STEP", "TICKS", "Candidates",
           "best_readings_table", "joint_candidates", "panel_candidates", "read_scores", "summary"]

#: the score table's columns (``same_values_as``: the panel's first reading that plots the same values)
COLUMNS = ["figure", "panel", "axis", "reading", "outcome", "autoscale", "ticks", "data_min", "data_max", "low",
           "high", "tick_step", "printed_low", "printed_high", "step", "matches", "same_values_as"]
_NUMBERS = ("data_min", "data_max", "low", "high", "tick_step", "printed_low", "printed_high", "step")

#: the tick modes: the printed step imposed (a fixed locator), or the plotting program's own (matplotlib's default)
PRINTED_STEP = "printed step"
DEFAULT_LOCATOR = "default locator"
TICKS = (PRINTED_STEP, DEFAULT_LOCATOR)

#: the autoscaling the axis claims use: limits rounded out to the ticks, no margin (MATLAB's automatic limits)
CLAIM_AUTOSCALE = "round, margin 0"


@dataclass(frozen=True)
class Candidates:
    """The printed limits each candidate reading of a panel reproduces; ``equivalent`` readings plot the same values."""

    out_of: int
    scores: Mapping[str, int]
    default_scores: Mapping[str, int] = field(default_factory=dict)
    equivalent: tuple[tuple[str, ...], ...] = ()

    def tied(self) -> tuple[int, list[tuple[str, ...]]]:
        """The best score and the readings tied at it, in groups of equivalent readings, in the order of the scores."""
        if not self.scores:
            raise ValueError("the grid of candidate readings holds no score")
        best = max(self.scores.values())
        tied = [name for name, score in self.scores.items() if score == best]
        group_of = {name: group for group in self.equivalent for name in group}
        groups = dict.fromkeys(tuple(n for n in group_of.get(name, (name,)) if n in tied) for name in tied)
        return best, list(groups)


def read_scores(path: str) -> list[dict]:
    """The score table of :func:`escapement.pipeline.readings.score_readings`, checked whole, its numbers parsed."""
    rows = read_csv(path, COLUMNS)
    for row in rows:
        row.update({name: float(row[name]) for name in _NUMBERS}, matches=int(row["matches"]))
    return rows


def _panel_scores(rows: Iterable[Mapping], autoscale: str) -> dict[tuple[str, str], dict]:
    """Per panel (in the order met): the scored axes, and per tick mode the limits each reading matches."""
    found: dict[tuple[str, str], dict] = {}
    for row in rows:
        if row["autoscale"] != autoscale:
            continue
        if row["ticks"] not in TICKS:
            raise ValueError(f"a score row has ticks = {row['ticks']!r}; it must be one of {', '.join(TICKS)}")
        key = (str(row["figure"]), str(row["panel"]))
        panel = found.setdefault(key, {"axes": set(), "groups": {}, **{t: defaultdict(int) for t in TICKS}})
        panel["axes"].add(row["axis"])
        panel[row["ticks"]][row["reading"]] += int(row["matches"])
        panel["groups"][row["reading"]] = row["same_values_as"]
    if not found:
        raise ValueError(f"the score rows hold no row with autoscale = {autoscale!r}")
    return found


def _equivalent(groups: Mapping[str, str]) -> tuple[tuple[str, ...], ...]:
    members: dict[str, list[str]] = defaultdict(list)
    for name, group in groups.items():
        members[group].append(name)
    return tuple(tuple(names) for names in members.values() if len(names) > 1)


def panel_candidates(rows: Iterable[Mapping], autoscale: str = CLAIM_AUTOSCALE) -> dict[tuple[str, str], Candidates]:
    """The :class:`Candidates` of each printed panel, keyed ``(figure, panel)``, under the margin ``autoscale``."""
    return {key: Candidates(out_of=2 * len(p["axes"]), scores=dict(p[PRINTED_STEP]),
                            default_scores=dict(p[DEFAULT_LOCATOR]), equivalent=_equivalent(p["groups"]))
            for key, p in _panel_scores(rows, autoscale).items()}


def joint_candidates(rows: Iterable[Mapping], figure: str, autoscale: str = CLAIM_AUTOSCALE) -> Candidates:
    """The readings every panel of Fig. ``figure`` scores under one name, scored over all its panels."""
    panels = [p for (fig, _), p in _panel_scores(rows, autoscale).items() if fig == str(figure)]
    if not panels:
        raise ValueError(f"figure = {figure!r}: the score rows hold no panel of that figure")
    names = [n for n in panels[0][PRINTED_STEP] if all(n in p[PRINTED_STEP] for p in panels)]
    if not names:
        raise ValueError(f"figure = {figure!r}: no reading is scored under one name in all its panels")
    return Candidates(out_of=sum(2 * len(p["axes"]) for p in panels),
                      scores={n: sum(p[PRINTED_STEP][n] for p in panels) for n in names},
                      default_scores={n: sum(p[DEFAULT_LOCATOR][n] for p in panels) for n in names},
                      equivalent=_equivalent({n: " | ".join(p["groups"][n] for p in panels) for n in names}))


def summary(candidates: Candidates) -> tuple[str, str]:
    """The best score in words, and every reading tied at it, equivalent ones joined by ``=``."""
    best, groups = candidates.tied()
    default = max(candidates.default_scores.values()) if candidates.default_scores else None
    score = f"{best} of {candidates.out_of}" + ("" if default is None else f" ({default} with the default locator)")
    if len(groups) == 1:
        lead = "one reading" if len(groups[0]) == 1 else f"{len(groups[0])} equivalent readings (identical values)"
    else:
        lead = f"**undetermined**: {len(groups)} readings tie, plotting different values"
    return score, f"{lead} of {len(candidates.scores)}:<br>" + "<br>".join(" = ".join(g) for g in groups)


def best_readings_table(rows: Iterable[Mapping], autoscale: str = CLAIM_AUTOSCALE) -> list[dict[str, str]]:
    """One row per printed panel (and one for Fig. 4's panels together): its printed limits and :func:`summary`."""
    rows, table = list(rows), []
    for (figure, name), c in panel_candidates(rows, autoscale).items():
        printed = next(p for p in PANELS if (p.figure, p.name) == (figure, name))
        limits = "; ".join(f"{axis} {a.low:g} to {a.high:g}" for axis, a in printed.axes.items() if a.scored)
        score, readings = summary(c)
        table.append({"figure": figure, "panel": name, "printed limits": limits, "limits reproduced": score,
                      "best-supported readings": readings})
    if "4" in {row["figure"] for row in table}:
        score, readings = summary(joint_candidates(rows, "4", autoscale))
        at = max(i for i, row in enumerate(table) if row["figure"] == "4") + 1
        limits = "; ".join(f"{row['panel']}: {row['printed limits']}" for row in table if row["figure"] == "4")
        table.insert(at, {"figure": "4", "panel": "both panels", "printed limits": limits,
                          "limits reproduced": score, "best-supported readings": readings})
    return table
