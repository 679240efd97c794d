"""The claims register evaluated: each of the paper's claims checked under every reading of its words, one row
per claim. A check that raises is a defect, never a verdict (:class:`ClaimError`, naming the claim).
"""

from __future__ import annotations

import importlib.util
import os
import re
from collections import Counter
from collections.abc import Collection, Mapping
from dataclasses import replace
from pathlib import Path

import jsonschema
import numpy as np
import yaml

from ..paper.printed_axes import PANELS
from .evidence import COMPLETED, Check, Evidence, Verdict, names, run
from .rule import UNDETERMINED, fmt, row_status

__all__ = ["SCHEMA", "ClaimError", "evaluate", "load_claims", "resolved"]

REGISTER, SCHEMA = (Path(__file__).with_name(name) for name in ("claims.yaml", "claims.schema.yaml"))
#: the reading of a claim checked under one reading only
AS_STATED = "as stated"
#: the figures whose printed axes could tell readings apart
FIGURES = sorted({p.figure for p in PANELS})


class ClaimError(RuntimeError):
    """A check could not compute its verdict on a claim; the message names the claim."""


def resolved(name: str) -> Check:
    """The check the register names ``module.function``, imported only then: importing the engine loads no check."""
    module, _, function = name.partition(".")
    found = (getattr(importlib.import_module(f"{__package__}.{module}"), function, None) if re.fullmatch(
        r"\w+\.\w+", name) and importlib.util.find_spec(f"{__package__}.{module}") else None)
    if not isinstance(found, Check):
        raise ValueError(f"check = {name!r} must name a check of escapement.verdict as module.function")
    return found


def load_claims(path: str | os.PathLike, schema: str | os.PathLike = SCHEMA, runs: Collection[str] | None = None
                ) -> list[dict]:
    """The claims of the register at ``path``, each with its ``readings``; ValueError naming the claim and its fault."""
    data, schema = (yaml.load(Path(p).read_text(), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
                    for p in (path, schema))
    error = jsonschema.exceptions.best_match(jsonschema.Draft202012Validator(schema).iter_errors(data))
    if error is not None:
        where = list(error.absolute_path)
        claim = data["claims"][where[1]] if where[:1] == ["claims"] and len(where) > 1 else {}
        name = f"claim '{claim['id']}'" if "id" in claim else "/".join(map(str, where))
        message = f"{error.instance!r} is a value this claim may not have" if error.validator is None else error.message
        at = "/".join(map(str, where[2:])) or ("the claim" if claim else "the entry")
        raise ValueError(f"{path}: {name}: {message} (at {at})")
    quoted = Counter(claim.get("quote") for claim in data["claims"])
    paper, seen = [*quoted, *data.get("cited", {}).values()], {"id": set(), "part": set()}
    for claim in data["claims"]:
        where = f"{path}: claim '{claim['id']}'"
        if "quote" in claim and ("part" in claim) != (quoted[claim["quote"]] > 1):
            raise ValueError(f"{where}: {quoted[claim['quote']]} claim(s) quote its sentence and it names "
                             f"{'a' if 'part' in claim else 'no'} part: the claims that quote one sentence are its "
                             "parts, each naming its part")
        if "readings" in claim and (missed := set(FIGURES) - figures_named(claim["figures_tried"])):
            raise ValueError(f"{where}: its figures_tried names no Fig. {', '.join(sorted(missed))}: every printed "
                             "figure is tried before a row may say that none decides")
        for reading in claim.get("readings", []):
            if not any(reading["words"] in text for text in paper if text):
                raise ValueError(f"{where}: the words {reading['words']!r} of the reading {reading['reading']!r} "
                                 "are in no quote and no sentence the register cites")
        for key, value in [("id", claim["id"])] + ([("part", (claim["quote"], claim.get("part")))]
                                                   if "quote" in claim else []):
            if value in seen[key]:
                raise ValueError(f"{where}: a second claim with this {key} ({value!r}); the rows that quote one "
                                 "sentence name each its part")
            seen[key].add(value)
        if "readings" not in claim:
            spec = {k: claim.pop(k) for k in ("check", "args", "tolerance", "tolerance_reason") if k in claim}
            claim["readings"] = [{"reading": AS_STATED, **spec}]
        for reading in claim["readings"]:
            reading["args"] = reading.get("args", {})
            try:
                declared = resolved(reading["check"])
            except ValueError as err:
                raise ValueError(f"{where}: {err}") from None
            if missing := [a for a in (*declared.runs, *declared.args) if a not in reading["args"]]:
                raise ValueError(f"{where}: the check '{reading['check']}' needs the args {', '.join(missing)}")
            if runs is not None and (unknown := [n for a in declared.runs for n in names(reading, a) if n not in runs]):
                raise ValueError(f"{where}: runs {unknown[0]!r} must name a run of the configuration's checks block, "
                                 f"one of {', '.join(sorted(runs))}")
    return data["claims"]


def left_regime(name: str, ds, answers: tuple[str, ...]) -> Verdict | None:
    """The verdict when the scene or a run ``name`` left the escapement regime (neither completed nor an answer)."""
    if "run" not in ds.dims:
        outcome = ds.attrs["outcome"]
        return None if outcome == COMPLETED else Verdict(
            f"not evaluated: {name} left the escapement regime ({outcome})", False,
            note=f"{name} ended with outcome '{outcome}': {ds.attrs['outcome_message']}; the claim concerns the "
                 "escapement regime")
    left = np.flatnonzero(~np.isin(ds["outcome"].values, [COMPLETED, *answers])) if "outcome" in ds else []
    return None if not len(left) else Verdict(
        f"not evaluated: {len(left)} of {ds.sizes['run']} runs left the escapement regime", False,
        note="; ".join(f"{lab} ended with outcome '{o}': {m}" for lab, o, m in zip(
            *(ds[k].values[left] for k in ("label", "outcome", "outcome_message")))))


def verdict(claim: Mapping, reading: Mapping, evidence: Evidence) -> Verdict:
    """The verdict of one ``reading`` of the claim; :class:`ClaimError` if its check fails or answers no outcome."""
    check, spec = resolved(reading["check"]), {**claim, **reading}
    try:
        runs = {f"the runs {name}": run(evidence, name) for arg in check.runs for name in names(spec, arg)}
        for name, ds in {**check.scenes(spec, evidence), **runs}.items():
            if (left := left_regime(name, ds, check.answers)) is not None:
                return left
        result = check(spec, evidence)
    except Exception as err:  # re-raised naming the claim: a failing check is never a verdict
        raise ClaimError(f"claim '{claim['id']}': check '{reading['check']}' failed: {type(err).__name__}: {err}"
                         ) from err
    holds, truth = result.holds, (bool, np.bool_)
    if not (holds is None or isinstance(holds, truth) or (
            isinstance(holds, Mapping) and holds and all(isinstance(h, truth) for h in holds.values()))):
        raise ClaimError(f"claim '{claim['id']}': check '{reading['check']}' answered holds = {holds!r}")
    return replace(result, holds=holds if holds is None else {k: bool(h) for k, h in holds.items()}
                   if isinstance(holds, Mapping) else bool(holds))


def figures_named(text: str) -> set[str]:
    """The figures ``text`` names: ``Fig. 3``, ``Fig. 3 (a)``, ``Figs. 4 and 5``, ``Figs. 3, 4 and 5``."""
    runs = re.findall(r"Figs?\.\s*((?:\d(?:\s*\([a-c]\))?(?:,\s*|\s+and\s+)?)+)", text)
    return {digit for run in runs for digit in re.findall(r"\d", run)}


def _said(holds) -> str:
    return (f"holds under {sum(holds.values())} of the {len(holds)} readings of a grid" if isinstance(holds, Mapping)
            else "nothing to compute" if holds is None else "holds" if holds else "fails")


def _joined(pairs: list[tuple[str, str]]) -> str:
    """One text per reading, named, or the text once when every reading gives the same."""
    texts = [text for _, text in pairs]
    return texts[0] if len(set(texts)) == 1 else " | ".join(f"[{name}] {text}" for name, text in pairs if text)


def evaluate(claims: list[dict], evidence: Evidence) -> list[dict[str, str]]:
    """One row per claim, with exactly the columns of :data:`~.rule.COLUMNS`; :class:`ClaimError` on a failing check."""
    rows, findings = [], {}
    for claim in claims:
        results = [(reading, verdict(claim, reading, evidence)) for reading in claim["readings"]]
        declared = [resolved(reading["check"]) for reading, _ in results]
        kind, status = row_status((c.law, c.fitted, c.threshold, r.holds) for c, (_, r) in zip(declared, results))
        paper = claim["paper_value"]
        paper = (next((r.paper_value for _, r in results if r.paper_value), "") if paper is None
                 else "[" + ", ".join(fmt(x) for x in paper) + "]" if isinstance(paper, list) else fmt(paper))
        named = [reading["reading"] for reading, _ in results]
        figures = ("" if len(named) == 1 else f"no figure decides between the readings: {claim['figures_tried']}"
                   if status == UNDETERMINED else f"the figures: {claim['figures_tried']}")
        rows.append({
            "claim_id": claim["id"],
            "source": claim["source"],
            "origin": claim["origin"],
            "quote": claim.get("quote", ""),
            "part": claim.get("part", ""),
            "finding": findings.setdefault(claim["quote"], claim["id"]) if claim["origin"] == "paper" else "",
            "evidence": kind,
            "statement": claim["statement"],
            "readings": "; ".join(reading["reading"] + (f' (the paper: "{reading["words"]}")' if "words" in reading
                                                        else "") + ": " + _said(r.holds) for reading, r in results),
            "paper_value": paper,
            "replicated_value": _joined([(n, r.replicated_value) for n, (_, r) in zip(named, results)]),
            "tolerance": _joined([(n, "" if r["tolerance"] is None else fmt(r["tolerance"]))
                                  for n, (r, _) in zip(named, results)]),
            "status": status,
            "note": "; ".join(filter(None, (_joined([(n, r.note) for n, (_, r) in zip(named, results)]), figures))),
        })
    return rows
