"""The claims register evaluated: each of the paper's claims checked under every reading of its words.

``claims.yaml`` (beside this module) lists the claims, checked against ``claims.schema.yaml``
(:func:`load_claims`). :func:`evaluate` runs each reading's check (registered by its decorator in the
modules imported below) and gives one row per claim, with exactly the columns of :data:`COLUMNS`: the
status follows from the readings' outcomes and the kind of evidence from what the checks consume, by the
rules of :mod:`escapement.verdict.rule`, never from the register; rows that quote one sentence are its
parts and share its finding, named after the first of them.

* a reading whose scene left the escapement regime (its ``outcome`` is not ``completed``) fails, with the
  scene's outcome message, and its check is not run;
* a check that raises is a defect of the code or of its inputs, never a verdict: :func:`evaluate` raises
  :class:`ClaimError` naming the claim, chained to the original error.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

import jsonschema
import numpy as np
import yaml

from ..paper.printed_axes import PANELS
# the modules of the checks, one per part of the paper: importing them registers their checks in CHECKS
from . import beyond, figure_axes, sec2_model, sec3_equations, sec3_map, sec3_period, sec3_steps  # noqa: F401
from . import sec4_fig3, sec4_fig4, sec4_fig5, sec5_conclusions  # noqa: F401
from .evidence import CHECKS, COMPLETED, Evidence, Verdict, fmt, runs_left_regime
from .rule import UNDETERMINED, evidence_of, status_of, weakest, weighed

__all__ = ["CHECKS", "COLUMNS", "SCHEMA", "ClaimError", "Evidence", "Verdict", "evaluate", "fmt", "load_claims"]

COLUMNS = ["claim_id", "source", "origin", "quote", "part", "finding", "evidence", "statement", "readings",
           "paper_value", "replicated_value", "tolerance", "status", "note"]
#: the register and its JSON Schema, package data beside this module
REGISTER, SCHEMA = (Path(__file__).with_name(name) for name in ("claims.yaml", "claims.schema.yaml"))
#: the reading of a claim checked under one reading only
AS_STATED = "as stated"


class ClaimError(RuntimeError):
    """A check could not compute its verdict on a claim; the message names the claim."""


def _schema(path: str | os.PathLike) -> dict:
    """The register's schema, with the names of the registered checks."""
    schema = yaml.safe_load(Path(path).read_text())
    schema["$defs"]["check"]["properties"]["check"] = {"enum": sorted(CHECKS)}
    return schema


def load_claims(path: str | os.PathLike, schema: str | os.PathLike = SCHEMA, settings: Mapping | None = None
                ) -> list[dict]:
    """The claims of the register at ``path``, checked against ``schema``, each with its ``readings`` (one,
    ``as stated``, for a claim checked under one reading); ValueError naming the claim if the register is
    malformed, if two claims share an id, if two parts of one sentence share a name, if a reading's words are
    not the paper's, if the figures tried leave out a printed figure, or if a check lacks its args (the five things
    a schema cannot say). Args that name their
    ``runs`` take them from ``settings`` (the configuration's ``model`` and ``checks`` blocks)."""
    data = yaml.load(Path(path).read_text(), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    error = jsonschema.exceptions.best_match(jsonschema.Draft202012Validator(_schema(schema)).iter_errors(data))
    if error is not None:
        where = list(error.absolute_path)
        claim = data["claims"][where[1]] if where[:1] == ["claims"] and len(where) > 1 else {}
        name = f"claim '{claim['id']}'" if isinstance(claim, dict) and "id" in claim else "/".join(map(str, where))
        message = (f"{error.instance!r} is a value this claim may not have" if error.validator is None else
                   f"{error.instance!r} is not a registered check" if where[-1:] == ["check"] else error.message)
        raise ValueError(f"{path}: {name}: {message} (at {'/'.join(map(str, where[2:])) or 'the claim'})")
    seen: dict[str, set] = {"id": set(), "part": set()}
    paper = [*data.get("sentences", {}).values(), *data.get("cited", {}).values()]
    for claim in data["claims"]:
        if "readings" in claim and (missed := set(FIGURES) - figures_named(claim["figures_tried"])):
            raise ValueError(f"{path}: claim '{claim['id']}': its figures_tried names no Fig. "
                             f"{', '.join(sorted(missed))}: every printed figure is tried before a row may say that "
                             "none decides")
        for reading in claim.get("readings", []):
            if not any(reading["words"] in text for text in (claim.get("quote", ""), *paper)):
                raise ValueError(f"{path}: claim '{claim['id']}': the words {reading['words']!r} of the reading "
                                 f"{reading['reading']!r} are in neither its quote nor a sentence the register cites")
        keys = [("id", claim["id"])] + ([("part", (claim["quote"], claim.get("part")))] if "quote" in claim else [])
        for key, value in keys:
            if value in seen[key]:
                raise ValueError(f"{path}: claim '{claim['id']}': a second claim with this {key} ({value!r}); "
                                 "the rows that quote one sentence name each its part")
            seen[key].add(value)
        if "readings" not in claim:
            spec = {k: claim.pop(k) for k in ("check", "args", "tolerance", "tolerance_reason") if k in claim}
            claim["readings"] = [{"reading": AS_STATED, **spec}]
        for reading in claim["readings"]:
            reading["args"] = _resolved(reading.get("args", {}), settings, f"{path}: claim '{claim['id']}'")
            missing = [a for a in CHECKS[reading["check"]].args if a not in reading["args"]]
            if missing:
                raise ValueError(f"{path}: claim '{claim['id']}': the check '{reading['check']}' needs the args "
                                 f"{', '.join(missing)}")
    return data["claims"]


def _resolved(args: Mapping, settings: Mapping | None, where: str) -> dict:
    """A reading's args with ``runs: <name>`` replaced by the settings of those runs, the ``checks`` block's entry
    ``name`` of the configuration, on the model's M, K and b: the runs' numbers are stated once, in config/."""
    if "runs" not in args:
        return dict(args)
    name, blocks = args["runs"], {k for k, v in (settings or {}).get("checks", {}).items() if isinstance(v, Mapping)}
    if name not in blocks:
        raise ValueError(f"{where}: runs {name!r} must name an entry of the configuration's checks block"
                         + (f", one of {', '.join(sorted(blocks))}" if blocks else ""))
    model = {key: settings["model"][key] for key in ("M", "K", "b")}
    return {**model, **settings["checks"][name], **{k: v for k, v in args.items() if k != "runs"}}


def verdict(claim: Mapping, reading: Mapping, evidence: Evidence) -> Verdict:
    """The verdict of the check of one ``reading`` of the claim; :class:`ClaimError` naming the claim if the
    check fails or answers no outcome."""
    registered, spec = CHECKS[reading["check"]], {**claim, **reading}
    try:
        for name, ds in registered.scenes(spec, evidence).items():  # one rule for a run that left the regime
            if "case" in ds.dims and (left := runs_left_regime(ds, registered.answers)) is not None:
                return left  # a table of runs of the checks dataset
            if "case" not in ds.dims and (outcome := ds.attrs["outcome"]) != COMPLETED:
                return Verdict(f"not evaluated: {name} left the escapement regime ({outcome})", False,
                               note=f"{name} ended with outcome '{outcome}': {ds.attrs['outcome_message']}; the "
                                    "claim concerns the escapement regime")
        result = registered.function(spec, evidence)
    except Exception as err:  # re-raised naming the claim: a failing check is never a verdict
        raise ClaimError(f"claim '{claim['id']}': check '{registered.name}' failed: {type(err).__name__}: {err}"
                         ) from err
    holds, truth = result.holds, (bool, np.bool_)
    if not (holds is None or isinstance(holds, truth) or (
            isinstance(holds, Mapping) and holds and all(isinstance(h, truth) for h in holds.values()))):
        raise ClaimError(f"claim '{claim['id']}': check '{registered.name}' answered holds = {holds!r}")
    return replace(result, holds=holds if holds is None else {k: bool(h) for k, h in holds.items()}
                   if isinstance(holds, Mapping) else bool(holds))


#: the figures whose printed axes could tell readings apart
FIGURES = sorted({p.figure for p in PANELS})


def figures_named(text: str) -> set[str]:
    """The figures ``text`` names: ``Fig. 3``, ``Fig. 3 (a)``, ``Figs. 4 and 5``, ``Figs. 3, 4 and 5``."""
    runs = re.findall(r"Figs?\.\s*((?:\d(?:\s*\([a-c]\))?(?:,\s*|\s+and\s+)?)+)", text)
    return {digit for run in runs for digit in re.findall(r"\d", run)}


def _outcomes(name: str, holds) -> tuple[list, str]:
    """The outcomes of one reading (a grid's, if the check walked one), and them in words."""
    if isinstance(holds, Mapping):
        return list(holds.values()), f"{name}: holds under {sum(holds.values())} of the {len(holds)} readings of a grid"
    return [holds], f"{name}: " + ("nothing to compute" if holds is None else "holds" if holds else "fails")


def _joined(pairs: list[tuple[str, str]]) -> str:
    """One text per reading, named, or the text once when every reading gives the same."""
    texts = [text for _, text in pairs]
    return texts[0] if len(set(texts)) == 1 else " | ".join(f"[{name}] {text}" for name, text in pairs if text)


def evaluate(claims: list[dict], evidence: Evidence) -> list[dict[str, str]]:
    """One row per claim, with exactly the columns of :data:`COLUMNS`; :class:`ClaimError` on a failing check."""
    rows, findings = [], {}
    for claim in claims:
        results = [(reading, verdict(claim, reading, evidence)) for reading in claim["readings"]]
        outcomes, words, kinds = [], [], []
        for reading, result in results:
            cited = f' (the paper: "{reading["words"]}")' if "words" in reading else ""
            found, said = _outcomes(reading["reading"] + cited, result.holds)
            outcomes += found
            words.append(said)
            c = CHECKS[reading["check"]]
            kinds.append(evidence_of(c.law, c.fitted, c.threshold, result.holds))
        kind = weakest(kinds)
        paper = claim["paper_value"]
        if paper is None:
            paper = next((r.paper_value for _, r in results if r.paper_value), "")
        elif isinstance(paper, list):
            paper = "[" + ", ".join(fmt(x) for x in paper) + "]"
        named = [reading["reading"] for reading, _ in results]
        status = weighed(status_of(outcomes), kind)
        figures = ("" if len(named) == 1 else f"; no figure decides between the readings: {claim['figures_tried']}"
                   if status == UNDETERMINED else f"; the figures: {claim['figures_tried']}")
        rows.append({
            "claim_id": claim["id"],
            "source": claim["source"],
            "origin": claim["origin"],
            "quote": claim.get("quote", ""),
            "part": claim.get("part", ""),
            "finding": findings.setdefault(claim["quote"], claim["id"]) if claim["origin"] == "paper" else "",
            "evidence": kind,
            "statement": claim["statement"],
            "readings": "; ".join(words),
            "paper_value": fmt(paper) if not isinstance(paper, str) else paper,
            "replicated_value": _joined([(n, r.replicated_value) for n, (_, r) in zip(named, results)]),
            "tolerance": _joined([(n, "" if r["tolerance"] is None else fmt(r["tolerance"]))
                                  for n, (r, _) in zip(named, results)]),
            "status": status,
            "note": _joined([(n, r.note) for n, (_, r) in zip(named, results)]) + figures,
        })
    return rows
