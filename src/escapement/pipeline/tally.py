"""The headline of the verdict: the paper's claims counted by finding, not by row.

One root cause can show in several rows (the period, for example, in the printed period, both
Fig. 3 cases, the period axes and the natural period): the register names it once, as the rows'
``finding``, and the headline counts it once. Only the paper's own claims (``origin`` paper) with independent
evidence and a verdict (reproduced, partially, not reproduced) are counted as findings; the rows
that hold by construction, the rows under a reading chosen from the same axes (whatever their
status), the undetermined and untestable rows, and the rows beyond the paper, are counted apart. A finding is as
strong as its weakest row: when its rows disagree (a configuration other than the paper's can make one of them fail), it
takes the weakest status and the headline says so. Reads the claims table only.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from ..paper.vocabulary import (
    CONSISTENT,
    EVIDENCE,
    NOT,
    ORIGINS,
    PARTIAL,
    REPRODUCED,
    STATUSES,
    UNDETERMINED,
    UNTESTABLE,
)

__all__ = ["Tally", "findings_table", "headline", "tally", "vocabulary_table"]

#: the statuses a finding may have, in the headline's order
VERDICTS = (REPRODUCED, PARTIAL, NOT)


@dataclass(frozen=True)
class Tally:
    """The counts of the headline; each list holds claim ids, ``findings`` maps a finding to its status."""

    paper_rows: int
    findings: Mapping[str, str]  #: each finding's status: the weakest of its rows'
    mixed: tuple[str, ...]  #: the findings whose rows disagree
    by_construction: tuple[str, ...]
    by_choice: Mapping[str, str]  #: each row under a reading fitted to the same axes, with its status
    undetermined: tuple[str, ...]
    untestable: tuple[str, ...]
    beyond: tuple[str, ...]

    def count(self, status: str) -> int:
        """How many findings have ``status``."""
        return sum(s == status for s in self.findings.values())


def _weakest(statuses: set[str]) -> str:
    """The weakest of ``statuses``: not reproduced before partially before reproduced."""
    return max(statuses, key=VERDICTS.index)


def tally(rows: Iterable[Mapping[str, str]]) -> Tally:
    """Count the rows of the claims table (``claim_id``, ``origin``, ``finding``, ``evidence`` and
    ``status`` are read).

    Raises
    ------
    ValueError
        If a row has a status outside the vocabulary.
    """
    statuses: dict[str, set[str]] = {}
    lists: dict[str, list[str]] = {"construction": [], UNDETERMINED: [], UNTESTABLE: [], "beyond": []}
    choice: dict[str, str] = {}
    paper = 0
    for row in rows:
        claim, status = row["claim_id"], row["status"]
        if status not in STATUSES:
            raise ValueError(f"claim '{claim}' has status = {status!r}, which the vocabulary does not define")
        if row["origin"] != "paper":
            lists["beyond"].append(claim)
            continue
        paper += 1
        if row["evidence"] == "by_construction":
            lists["construction"].append(claim)
        elif row["evidence"] == "fitted":  # a reading chosen from the same axes: never a finding
            choice[claim] = status
        elif status in (UNDETERMINED, UNTESTABLE):
            lists[status].append(claim)
        elif status in VERDICTS:
            statuses.setdefault(row["finding"], set()).add(status)
        else:
            raise ValueError(f"claim '{claim}' has status = {status!r} on independent evidence; it must be one of "
                             f"{', '.join(VERDICTS)}, undetermined or untestable")
    mixed = tuple(f for f, s in statuses.items() if len(s) > 1)
    return Tally(
        paper_rows=paper,
        findings={f: _weakest(s) for f, s in statuses.items()},
        mixed=mixed,
        by_construction=tuple(lists["construction"]),
        by_choice=choice,
        undetermined=tuple(lists[UNDETERMINED]),
        untestable=tuple(lists[UNTESTABLE]),
        beyond=tuple(lists["beyond"]),
    )


def _rows(n: int) -> str:
    return f"{n} row" + ("" if n == 1 else "s")


def headline(rows: Iterable[Mapping[str, str]]) -> str:
    """The verdict's count in one sentence (Markdown), from the rows of the claims table."""
    t = tally(rows)
    findings = len(t.findings)
    fitted = list(t.by_choice.values())
    return (
        f"The paper's claims fill {_rows(t.paper_rows)} of the register. The rows with an independent verdict "
        f"come down to {findings} findings: {t.count(REPRODUCED)} reproduced, {t.count(PARTIAL)} partially "
        f"reproduced and {t.count(NOT)} not reproduced. Apart from these, rows consistent by construction (the "
        f"model is built from them): {len(t.by_construction)}; rows under a reading chosen from the same printed "
        f"axes: {len(fitted)} ({fitted.count(CONSISTENT)} consistent with it, {fitted.count(PARTIAL)} partly and "
        f"{fitted.count(NOT)} not met by any reading of the grid); undetermined (readings the paper's evidence "
        f"cannot tell apart, under which the claim holds and fails): {len(t.undetermined)}; untestable from the "
        f"paper's evidence: {len(t.untestable)}. Beyond the paper, and not counted: {_rows(len(t.beyond))}."
        + (f" The rows of {len(t.mixed)} findings disagree ({', '.join(t.mixed)}); each is counted at its weakest "
           "row." if t.mixed else "")
    )


def findings_table(rows: Iterable[Mapping[str, str]]) -> list[dict[str, str]]:
    """One row per finding of the headline: its name, its status and the claims that show it."""
    rows = list(rows)
    t = tally(rows)
    by_finding: dict[str, list[str]] = {}
    for row in rows:
        if (row["finding"] in t.findings and row["origin"] == "paper" and row["evidence"] == "independent"
                and row["status"] in VERDICTS):
            by_finding.setdefault(row["finding"], []).append(f"`{row['claim_id']}`")
    return [{"finding": f,
             "verdict": t.findings[f].replace("_", " ") + (" (its rows disagree)" if f in t.mixed else ""),
             "rows": ", ".join(by_finding[f])}
            for f in sorted(t.findings, key=lambda f: (VERDICTS.index(t.findings[f]), f))]


def vocabulary_table() -> list[dict[str, str]]:
    """The statuses, kinds of evidence and origins with their meanings, as the vocabulary defines them."""
    return ([{"word": f"status: {w.replace('_', ' ')}", "meaning": m} for w, m in STATUSES.items()]
            + [{"word": f"evidence: {w.replace('_', ' ')}", "meaning": m} for w, m in EVIDENCE.items()]
            + [{"word": f"origin: {w}", "meaning": m} for w, m in ORIGINS.items()])
