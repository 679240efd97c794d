"""The claims register: each of the paper's claims checked against the netCDF outputs.

``workflow/claims.yaml`` lists the claims; each names a check of :data:`escapement.paper.registry.CHECKS`
(the one list of them), which computes the replicated value and decides the status.
:func:`evaluate` gives one row per claim:

* each row carries the claim's origin, finding and kind of evidence from the register, and its
  status is the check's weighed by that evidence (:func:`escapement.paper.vocabulary.weighed`:
  an agreement by construction or under a fitted reading is ``consistent``);
* a claim whose scene left the escapement regime (its ``outcome`` is not ``completed``) gets
  ``not_reproduced`` with the scene's outcome message, and its check is not run;
* a check that raises is a defect of the code or of its inputs, never a verdict:
  :func:`evaluate` raises :class:`ClaimError` naming the claim, chained to the original error.

Tolerances and the Fig. 3 case labels come from the register, never from here.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from pathlib import Path

import xarray as xr
import yaml

from .checks import COMPLETED, NOT, Evidence, Verdict, fmt
from .registry import CHECKS
from .vocabulary import EVIDENCE, ORIGINS, STATUSES, weighed

__all__ = ["COLUMNS", "STATUSES", "CHECKS", "ClaimError", "Evidence", "Verdict", "evaluate", "fmt", "load_claims"]

COLUMNS = ["claim_id", "source", "origin", "finding", "evidence", "statement", "paper_value", "replicated_value",
           "tolerance", "status", "note"]
#: the register's keys every claim must have
REQUIRED = ("id", "source", "origin", "finding", "evidence", "statement", "paper_value", "tolerance", "check")
#: the words a finding's name may use
_FINDING = re.compile(r"[a-z][a-z0-9_]*")


class ClaimError(RuntimeError):
    """A check could not compute its verdict on a claim; the message names the claim."""


# --- the register ------------------------------------------------------------------------------


def load_claims(path: str | os.PathLike) -> list[dict]:
    """Read and check the register: unique ids, the required keys, an origin, a finding and a kind of
    evidence from the vocabulary, a tolerance with its reason (or neither), a registered check and its args."""
    data = yaml.safe_load(Path(path).read_text())
    claims = data.get("claims") if isinstance(data, dict) else None
    if not isinstance(claims, list) or not claims:
        raise ValueError(f"{path}: expected a mapping with a non-empty list 'claims'")
    seen = set()
    for i, claim in enumerate(claims):
        if not isinstance(claim, dict):
            raise ValueError(f"{path}: claim {i} is {claim!r}; it must be a mapping")
        for key in REQUIRED:
            if key not in claim:
                raise ValueError(f"{path}: claim {i} lacks '{key}'")
        for key, words in (("origin", ORIGINS), ("evidence", EVIDENCE)):
            if claim[key] not in words:
                raise ValueError(f"{path}: claim '{claim['id']}' has {key} = {claim[key]!r}; "
                                 f"it must be one of {', '.join(words)}")
        if not (isinstance(claim["finding"], str) and _FINDING.fullmatch(claim["finding"])):
            raise ValueError(f"{path}: claim '{claim['id']}' has finding = {claim['finding']!r}; it must be a "
                             "name of lower-case letters, digits and underscores")
        _check_tolerance(path, claim)
        if claim["id"] in seen:
            raise ValueError(f"{path}: claim id '{claim['id']}' appears twice")
        seen.add(claim["id"])
        if claim["check"] not in CHECKS:
            raise ValueError(f"{path}: claim '{claim['id']}' names an unknown check '{claim['check']}'")
        claim.setdefault("args", {})
        missing = [a for a in CHECKS[claim["check"]].args if a not in claim["args"]]
        if missing:
            raise ValueError(f"{path}: claim '{claim['id']}' lacks the args {', '.join(missing)} of its check")
    return claims


def _check_tolerance(path, claim: dict) -> None:
    """A tolerance is a number >= 0 published with its reason (``tolerance_reason``), or null with none."""
    tolerance, reason = claim["tolerance"], claim.get("tolerance_reason")
    if tolerance is None:
        if reason is not None:
            raise ValueError(f"{path}: claim '{claim['id']}' gives a tolerance_reason but no tolerance")
        return
    if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float)) or not tolerance >= 0:
        raise ValueError(f"{path}: claim '{claim['id']}' has tolerance = {tolerance!r}; it must be a number >= 0 "
                         "or null")
    if not (isinstance(reason, str) and reason.strip()):
        raise ValueError(f"{path}: claim '{claim['id']}' has tolerance = {tolerance!r} and tolerance_reason = "
                         f"{reason!r}; a tolerance is a decision: it must give its reason as non-empty text")


def left_regime(scene: str, ds: xr.Dataset) -> Verdict:
    """The verdict on a claim whose scene left the escapement regime."""
    outcome, message = ds.attrs["outcome"], ds.attrs["outcome_message"]
    return Verdict(
        f"not evaluated: {scene} left the escapement regime ({outcome})",
        NOT,
        note=f"{scene} ended with outcome '{outcome}': {message}; the claim concerns the escapement regime",
    )


def verdict(claim: Mapping, evidence: Evidence) -> Verdict:
    """The verdict of the claim's check; :class:`ClaimError` naming the claim if the check fails."""
    if claim["check"] not in CHECKS:
        raise ClaimError(f"claim '{claim['id']}' names an unknown check '{claim['check']}'")
    registered = CHECKS[claim["check"]]
    try:
        scenes = registered.scenes(claim, evidence)
        left = [(name, ds) for name, ds in scenes.items() if ds.attrs["outcome"] != COMPLETED]
        result = left_regime(*left[0]) if left else registered.function(claim, evidence)
    except Exception as err:  # re-raised naming the claim: a failing check is never a verdict
        raise ClaimError(
            f"claim '{claim['id']}': check '{registered.name}' failed: {type(err).__name__}: {err}"
        ) from err
    if result.status not in STATUSES:
        raise ClaimError(f"claim '{claim['id']}': check '{registered.name}' returned the status {result.status!r}")
    return result


def evaluate(claims: list[dict], evidence: Evidence) -> list[dict[str, str]]:
    """One row per claim, with exactly the columns of ``COLUMNS``; raises :class:`ClaimError` on a failing check."""
    rows = []
    for claim in claims:
        result = verdict(claim, evidence)
        paper = claim["paper_value"]
        if paper is None:
            paper = result.paper_value or ""
        elif isinstance(paper, list):
            paper = "[" + ", ".join(fmt(x) for x in paper) + "]"
        rows.append(
            {
                "claim_id": claim["id"],
                "source": claim["source"],
                "origin": claim["origin"],
                "finding": claim["finding"],
                "evidence": claim["evidence"],
                "statement": claim["statement"],
                "paper_value": fmt(paper) if not isinstance(paper, str) else paper,
                "replicated_value": result.replicated_value,
                "tolerance": "" if claim["tolerance"] is None else fmt(claim["tolerance"]),
                "status": weighed(result.status, claim["evidence"]),
                "note": result.note,
            }
        )
    return rows
