"""The words of the verdict, defined once: statuses, kinds of evidence, origins.

A row of the claims register carries three judgements besides its numbers:

* its **origin**: a claim the paper makes, or one the replication adds beyond it;
* its **evidence**: how the replicated value bears on the claim: an independent computation, a
  comparison that holds by construction (the model is built from the claim), a comparison under a
  reading chosen by fitting the same evidence (the printed axes), or nothing the paper gives that
  can be computed against;
* its **status**, decided by the check and then weighed by the evidence (:func:`weighed`): an
  agreement that holds by construction or by choice is ``consistent``, never ``reproduced``.

Rows that share one root cause share a **finding** (a short name in the register), so that one
discrepancy is counted once however many rows show it (:func:`escapement.pipeline.tally`).
"""

from __future__ import annotations

__all__ = [
    "CONSISTENT", "EVIDENCE", "NOT", "ORIGINS", "PARTIAL", "REPRODUCED", "STATUSES", "UNDETERMINED",
    "UNTESTABLE", "weighed",
]

#: every status a row may have, with what it means
STATUSES: dict[str, str] = {
    "reproduced": "an independent computation agrees with the claim within its tolerance",
    "partially_reproduced": "an independent computation agrees with part of the claim only",
    "not_reproduced": "an independent computation disagrees with the claim",
    "consistent": ("the replication agrees with the claim, but by construction or under a reading chosen "
                   "from the same evidence: it confirms nothing"),
    "undetermined": ("several readings fit the paper's evidence equally well, and the claim holds under some "
                     "and fails under others: no verdict"),
    "untestable": "the paper gives nothing the claim can be computed against",
}
REPRODUCED, PARTIAL, NOT, CONSISTENT, UNDETERMINED, UNTESTABLE = STATUSES

#: every kind of evidence a row may rest on, with what it means
EVIDENCE: dict[str, str] = {
    "independent": "computed independently of the claim (a simulation, a closed form derived here)",
    "by_construction": "the model is built from the claim, so the comparison cannot fail",
    "fitted": "compared under a reading of the paper's open choices chosen by fitting the same evidence",
    "none": "the paper gives no number, formula or figure the claim can be computed against",
}

#: where a claim comes from
ORIGINS: dict[str, str] = {
    "paper": "a claim the paper makes",
    "beyond": "a claim the replication adds beyond the paper (it is not counted in the paper's tally)",
}


def weighed(status: str, evidence: str) -> str:
    """The row's status: the check's ``status`` weighed by the kind of ``evidence`` it rests on.

    An agreement by construction or under a fitted reading is ``consistent``; a disagreement under
    a fitted reading stays what the check found (no reading of the grid reaches the claim, which is
    evidence against it whatever the choice); a claim with no evidence is ``untestable`` whatever
    the check says.

    Raises
    ------
    ValueError
        If ``status`` or ``evidence`` is not one of :data:`STATUSES`, :data:`EVIDENCE`.
    """
    if status not in STATUSES:
        raise ValueError(f"status = {status!r} must be one of {', '.join(STATUSES)}")
    if evidence not in EVIDENCE:
        raise ValueError(f"evidence = {evidence!r} must be one of {', '.join(EVIDENCE)}")
    if evidence == "none":
        return UNTESTABLE
    if evidence in ("by_construction", "fitted") and status == REPRODUCED:
        return CONSISTENT
    return status
