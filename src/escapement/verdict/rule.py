"""The words of the verdict, the columns of the claims table, and the one rule that gives a row its status. Only a
finding, a sentence, takes a partial status, from its parts' (:func:`finding_status`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

__all__ = ["COLUMNS", "CONSISTENT", "EVIDENCE", "NOT", "ORIGINS", "PARTIAL", "REPRODUCED", "STATUSES", "UNDETERMINED",
    "UNTESTABLE", "evidence_of", "finding_status", "fmt", "row_status", "status_of", "weighed"]

COLUMNS = ["claim_id", "source", "origin", "quote", "part", "finding", "evidence", "statement", "readings",
           "paper_value", "replicated_value", "tolerance", "status", "note"]

#: every status a row or a finding may have, with what it means
STATUSES: dict[str, str] = {
    "reproduced": "holds under every reading of the sentence's words, on evidence computed independently of it",
    "partially_reproduced": ("a finding only: a named part of the sentence is reproduced (holds under every "
                             "reading, on independent evidence), another fails under every reading"),
    "not_reproduced": ("fails under every reading of the sentence's words, on evidence that rests on no reading or "
                       "threshold chosen by the project"),
    "consistent": ("holds, but by construction (the model is built from it) or under a reading or threshold chosen "
                   "by the project: it confirms nothing"),
    "undetermined": ("holds under some readings of the sentence's words and fails under others, and no printed "
                     "figure tells the readings apart; or fails only under a reading or threshold chosen by the "
                     "project; or, for a finding, a part holds and another has no verdict: no verdict"),
    "untestable": "the paper gives nothing the claim can be computed against",
}
REPRODUCED, PARTIAL, NOT, CONSISTENT, UNDETERMINED, UNTESTABLE = STATUSES

#: every kind of evidence, from the strongest, with what it means
EVIDENCE: dict[str, str] = {
    "independent": "computed independently of the claim (a simulation, a closed form derived here)",
    "fitted": ("computed under a reading fitted to the paper's printed axes, or judged by a threshold the project "
               "chose"),
    "by_construction": "restates a law the model is built on, so the comparison cannot fail",
    "none": "the paper gives no number, formula or figure the claim can be computed against",
}

ORIGINS: dict[str, str] = {
    "paper": "a sentence of the paper, quoted",
    "beyond": "a result the paper does not state, added by the replication (not counted among the findings)",
}


def evidence_of(law: str | None, fitted: str | None, threshold: str | None, holds) -> str:
    """The kind of evidence of one reading, from what its check consumes; none when it computed nothing."""
    return "none" if holds is None else "by_construction" if law else "fitted" if fitted or threshold else "independent"


def status_of(outcomes: Iterable[bool | None]) -> str:
    """The one rule: the status of a claim from whether it holds under each reading of its words."""
    outcomes = list(outcomes)
    if not outcomes or (None in outcomes and any(o is not None for o in outcomes)):
        raise ValueError(f"outcomes = {outcomes!r}: every reading computes an outcome, or none does")
    if outcomes[0] is None:
        return UNTESTABLE
    return REPRODUCED if all(outcomes) else UNDETERMINED if any(outcomes) else NOT


def weighed(status: str, evidence: str) -> str:
    """The row's status: agreement by construction or on fitted evidence is only consistent, failure on the latter
    only undetermined (the readings and thresholds it rests on are the project's)."""
    if status not in STATUSES or evidence not in EVIDENCE:
        raise ValueError(f"status = {status!r}, evidence = {evidence!r}: not words of the vocabulary")
    if evidence == "fitted" and status == NOT:
        return UNDETERMINED
    return CONSISTENT if status == REPRODUCED and evidence in ("fitted", "by_construction") else status


def row_status(readings: Iterable[tuple]) -> tuple[str, str]:
    """A row's kind of evidence, the weakest of its readings', and its status over every outcome, weighed by it."""
    readings = list(readings)
    kind = max((evidence_of(*reading) for reading in readings), key=list(EVIDENCE).index)
    outcomes = [o for *_, holds in readings for o in (holds.values() if isinstance(holds, Mapping) else [holds])]
    return kind, weighed(status_of(outcomes), kind)


def finding_status(statuses: Iterable[str]) -> str:
    """A sentence's status from its parts' (a consistent part confirms nothing, an untestable one never holds)."""
    statuses = list(statuses)
    if all(s == UNTESTABLE for s in statuses):
        return UNTESTABLE
    if all(s in (REPRODUCED, CONSISTENT) for s in statuses):
        return CONSISTENT if CONSISTENT in statuses else REPRODUCED
    if NOT not in statuses:
        return UNDETERMINED
    return PARTIAL if REPRODUCED in statuses else NOT


def fmt(x: float, digits: int = 10) -> str:
    """A number as text, to ``digits`` significant digits (enough to compare, stable across runs)."""
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "nan"
    return f"{float(x):.{digits}g}"
