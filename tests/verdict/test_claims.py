"""The claims engine: the register against its schema and the paper's text, its checks named and resolved, the one
rule applied to the readings' outcomes and the rows it gives, the checks run on scenes of the exact solver (the Fig. 3
cases) and a synthetic checks dataset, or replaced by stubs whose outcomes the test chooses.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import importlib
import os
import pkgutil
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import escapement.verdict
from escapement.model.parameters import Parameters
from escapement.verdict import engine as cl
from escapement.verdict.evidence import Check, Evidence, Verdict, names, no_scene, run
from escapement.verdict.rule import COLUMNS
from escapement.solvers.exact import solve_exact
from verdict.test_check_boundaries import (GEOMETRY, RUNS, bounded, first_swings, made, phase_shift, register_row,
                                         return_map, runs)

REGISTER = cl.REGISTER
REPO = Path(__file__).resolve().parents[2]


@functools.cache
def register() -> list[dict]:
    return cl.load_claims(REGISTER, runs=RUNS)


@functools.cache
def written() -> dict:
    """The register as written (before the loader adds its readings)."""
    return yaml.load(REGISTER.read_text(), Loader=yaml.CSafeLoader)


def quoted() -> list[str]:
    """The sentences the claims quote, whitespace collapsed."""
    return [" ".join(c["quote"].split()) for c in written()["claims"] if "quote" in c]


def listed() -> list[str]:
    """The sentences the register lists as stating no result, whitespace collapsed."""
    return [" ".join(e["sentence"].split()) for e in written()["no_result"]]


def claim_of(claim_id: str) -> dict:
    return next(c for c in register() if c["id"] == claim_id)


def checks_named() -> set[str]:
    return {r["check"] for c in register() for r in c["readings"]}


# --- the register ----------------------------------------------------------------------------------


def test_each_check_of_the_package_is_named_by_the_register_as_module_function_where_it_is_defined():
    """The register names every check the modules of escapement.verdict declare, each by the module that defines
    it, and nothing else."""
    assert checks_named() == {
        f"{info.name}.{name}" for info in pkgutil.iter_modules(escapement.verdict.__path__)
        for name, value in vars(importlib.import_module(f"escapement.verdict.{info.name}")).items()
        if isinstance(value, Check) and value.function.__module__ == f"escapement.verdict.{info.name}"}


def test_the_register_gives_the_fig3_cases_of_the_configuration():
    labels = {str(c) for c in yaml.safe_load((REPO / "config" / "paper.yaml").read_text())["fig3"]["cases"]}
    for c in register():
        for r in c["readings"]:
            named = [r["args"]["case"]] if "case" in r["args"] else r["args"].get("cases", [])
            assert {str(x) for x in named} <= labels, c["id"]


def test_every_quote_and_cited_sentence_is_the_papers_text_and_every_cited_one_admits_a_reading():
    """Each quote and each cited sentence of the register, whitespace collapsed, is found in the paper's text as
    extracted (its path in ESCAPEMENT_PAPER_TEXT, the variable of the other verbatim tests)."""
    cited = written()["cited"]
    words = [r["words"] for c in written()["claims"] for r in c.get("readings", [])]
    assert all(any(w in sentence for w in words) for sentence in cited.values())
    path = os.environ.get("ESCAPEMENT_PAPER_TEXT")
    if not path:
        pytest.skip("ESCAPEMENT_PAPER_TEXT does not name the paper's text file")
    text = " ".join(Path(path).read_text().split())
    for sentence in {*quoted(), *cited.values()}:
        assert " ".join(sentence.split()) in text, sentence


#: the headings of Secs. 3-5 in the paper's text, which open no sentence
HEADINGS = (r"\d(?:\.\d)?\. (?:The dynamics of the model|Impulsive differential equation|Poincare map|Solution of "
            r"the system|The stability|Simulation results|Conclusions) ")


def sentences_of_secs_3_to_5(text: str) -> list[str]:
    """The sentences of Secs. 3-5 of the paper's text, whitespace collapsed: from Sec. 3's heading to Appendix A,
    without the running heads, the page numbers, the headings and the figures' printed text (ticks, axis titles and
    captions, between Sec. 4's first paragraph and its text on Fig. 4). A sentence ends at '.', '?' or '!', or at an
    equation's number ('(16)', '(9a)'), before a word that starts with a capital letter: an equation is a part of
    the sentence that introduces it."""
    body = text[text.index("3. The dynamics of the model"):text.index("Appendix A:")]
    body = re.sub(r"^(J\. Mao et al\. / .*|\d+)$", "", body, flags=re.M)
    body = re.sub(r"(?<=convergence properties\.).*(?=Figure 4 shows)", "", body, flags=re.S)
    return re.findall(r"\S.*?(?:[.?!]|\(\d\d?[a-e]?\))(?=\s+[A-Z]|$)", re.sub(HEADINGS, "", " ".join(body.split())))


def test_every_sentence_of_secs_3_to_5_is_quoted_by_a_claim_or_listed_as_stating_no_result():
    """Each sentence of Secs. 3-5 (:func:`sentences_of_secs_3_to_5`) holds a claim's quote or a listed sentence, or
    lies in a quote (the extraction runs a few sentences together around their equations, and a claim may quote
    only the equation of its sentence); each listed sentence is one of them, whole."""
    path = os.environ.get("ESCAPEMENT_PAPER_TEXT")
    if not path:
        pytest.skip("ESCAPEMENT_PAPER_TEXT does not name the paper's text file")
    sentences = sentences_of_secs_3_to_5(Path(path).read_text())
    assert sentences[0].startswith("In order to study the dynamics of the escapement")
    assert sentences[-1] == "The result indicates that the model can describe the system properly."
    missed = [s for s in sentences if not any(t in s or s in t for t in (*quoted(), *listed()))]
    assert not missed, missed
    assert set(listed()) <= set(sentences), set(listed()) - set(sentences)


def test_each_sentence_stating_no_result_says_why_and_none_is_also_quoted(tmp_path):
    """The sentences listed as stating no result, each with why (the schema refuses one without), none of them
    quoted by a claim, in whole or in part, and none listed twice."""
    entries = written()["no_result"]
    assert entries and all(e["sentence"].strip() and e["why"].strip() for e in entries)
    assert [s for s in listed() if any(q in s or s in q for q in quoted())] == []
    assert len(set(listed())) == len(entries)
    path = tmp_path / "claims.yaml"
    path.write_text(yaml.dump({**written(), "no_result": [{"sentence": entries[0]["sentence"]}]}, allow_unicode=True))
    with pytest.raises(ValueError, match=f"^{path}: no_result/0: 'why' is a required property \\(at the entry\\)$"):
        cl.load_claims(path)


def test_reason_and_conclusion_are_parts_never_readings():
    """A sentence that gives a reason for its conclusion is checked in two rows of its own, its parts, never as
    two readings of one row; and Eq. (24)'s two forms, its parts, are read in one convention (their checks differ
    only in the form)."""
    for c in register():
        for r in c["readings"]:
            assert not re.search(r"\b(reason|conclusion|inference)\b", r["reading"]), c["id"]
    for reason, conclusion in (("eq8_map_reason", "eq8_trivial_multiplier"),
                               ("lipschitz_reason", "solution_exists_unique")):
        assert claim_of(reason)["part"].endswith("(the reason)"), reason
        assert claim_of(conclusion)["part"].endswith("(the conclusion)"), conclusion
        assert claim_of(reason)["quote"] == claim_of(conclusion)["quote"]
    first, second = (claim_of(i)["readings"] for i in ("eq24_impact_perturbation", "eq24_second_form"))
    assert len(first) == len(second) == 1 and claim_of("eq24_second_form")["quote"] == claim_of(
        "eq24_impact_perturbation")["quote"]
    assert {**first[0]["args"], "form": None} == {**second[0]["args"], "form": None}


#: the claims of the register the refusals below mutate, in the register's order (a register of its own)
SMALL = ("eq4_jump_set", "eq16_map", "eq16_derivation", "eq19_fixed_point_case_a", "eq19_fixed_point_case_b",
         "eq20_map_derivative", "eq20_derivation", "fig5_recovery_small_K_faster", "airy_symmetric_impulse")
RECOVERY = "fig5_recovery_small_K_faster"
#: each refusal of the loader: a mutation of the small register, and the message, which names the claim
REFUSALS = [
    (lambda by: by["eq16_map"].pop("tolerance"), "claim 'eq16_map': .*'tolerance' is a required property"),
    (lambda by: by["eq16_map"].pop("tolerance_reason"), "claim 'eq16_map': 'tolerance_reason' is a required"),
    (lambda by: by["eq16_map"].update(tolerance_reason="  "), "claim 'eq16_map': '  ' does not match"),
    (lambda by: by["eq4_jump_set"].update(tolerance_reason="a reason"),
     "claim 'eq4_jump_set': 'a reason' is a value this claim may not have"),
    (lambda by: by["eq16_map"].update(tolerance=-1e-13), "claim 'eq16_map': .*less than the minimum of 0"),
    (lambda by: by["eq16_map"].update(tolerance=True), "claim 'eq16_map': True is not of type"),
    (lambda by: by["eq16_map"].pop("quote"), "claim 'eq16_map': 'quote' is a required property"),
    (lambda by: by["airy_symmetric_impulse"].update(quote="a sentence"),
     "claim 'airy_symmetric_impulse': 'a sentence' is a value this claim may not have"),
    (lambda by: by["eq16_map"].update(origin="elsewhere"), "claim 'eq16_map': 'elsewhere' is not one of"),
    # the status, the kind of evidence and the finding are computed, never typed into the register
    *[(lambda by, key=key: by["eq16_map"].update({key: "x"}), f"claim 'eq16_map': .*'{key}' was unexpected")
      for key in ("status", "evidence", "finding")],
    (lambda by: by[RECOVERY].pop("figures_tried"), f"claim '{RECOVERY}': 'figures_tried' is a required property"),
    (lambda by: by[RECOVERY].update(check="sec3_map.fixed_point"),
     f"claim '{RECOVERY}': 'sec3_map.fixed_point' is a value this claim may not have"),
    # what the schema cannot say
    (lambda by: by["airy_symmetric_impulse"].update(id="eq16_map"), "claim 'eq16_map': a second claim with this id"),
    (lambda by: by["eq19_fixed_point_case_b"].update(part="case (a)"),
     "claim 'eq19_fixed_point_case_b': a second claim with this part"),
    (lambda by: by["eq19_fixed_point_case_b"].update(quote=by["eq19_fixed_point_case_b"]["quote"] + "."),
     "claim 'eq19_fixed_point_case_a': 1 claim\\(s\\) quote its sentence and it names a part: "),
    (lambda by: by["eq4_jump_set"].update(quote=by["eq19_fixed_point_case_a"]["quote"]),
     "claim 'eq4_jump_set': 3 claim\\(s\\) quote its sentence and it names no part: "),
    (lambda by: by["eq16_map"].update(check="nonsense"),
     "claim 'eq16_map': check = 'nonsense' must name a check of escapement.verdict as module.function$"),
    (lambda by: by["eq16_map"].update(check="engine.evaluate"), "claim 'eq16_map': check = 'engine.evaluate' must"),
    (lambda by: by["eq19_fixed_point_case_a"].pop("args"),
     "claim 'eq19_fixed_point_case_a': the check 'sec3_map.fixed_point' needs the args case$"),
    (lambda by: by["eq20_map_derivative"]["args"].update(runs="existance"),
     "claim 'eq20_map_derivative': runs 'existance' must name a run of the configuration's checks block, one of "
     "airy, asymmetric, b, b_continued, common_force, existence, "),
    (lambda by: by[RECOVERY]["readings"][0].update(words="the speed of recovery"),
     f"claim '{RECOVERY}': the words 'the speed of recovery' of the reading 'in seconds' are in no quote and no "
     "sentence the register cites$"),
    (lambda by: by[RECOVERY].update(figures_tried="Fig. 5 is a phase diagram; Fig. 3 shows one point per cycle"),
     f"claim '{RECOVERY}': its figures_tried names no Fig. 4: every printed figure is tried"),
]


def test_a_malformed_register_is_refused_naming_the_claim(tmp_path):
    """Each refusal of :data:`REFUSALS` on a small register of the register's own claims, which loads as it is."""
    path = tmp_path / "claims.yaml"

    def loaded(mutate=lambda by: None, runs=RUNS):
        data = copy.deepcopy({**written(), "claims": [c for c in written()["claims"] if c["id"] in SMALL]})
        mutate({c["id"]: c for c in data["claims"]})
        path.write_text(yaml.dump(data, Dumper=yaml.CSafeDumper, allow_unicode=True))
        return cl.load_claims(path, runs=runs)

    assert [c["id"] for c in loaded()] == list(SMALL)
    for mutate, message in REFUSALS:
        with pytest.raises(ValueError, match=f"^{path}: {message}"):
            loaded(mutate)
    assert [c["id"] for c in loaded(lambda by: by["eq20_map_derivative"]["args"].update(runs="existance"),
                                    runs=None)] == list(SMALL)  # no configuration given, no run refused


def test_a_reading_names_its_runs_and_gives_only_the_args_its_check_declares():
    """The runs a reading reads are named by the args its check declares among its runs, each a run of the
    configuration's checks block, which alone states their settings: a reading of runs gives no arg its check does
    not declare (no position, force, release or count of a run's)."""
    named = set()
    for claim in register():
        for reading in claim["readings"]:
            check = cl.resolved(reading["check"])
            assert not check.runs or set(reading["args"]) <= {*check.runs, *check.args}, claim["id"]
            named.update(n for arg in check.runs for n in names(reading, arg))
    assert named == set(RUNS)  # every run of the configuration is read, and only those


# --- the one rule, on the register's own claims -------------------------------------------------------


def stubbed(monkeypatch, outcome) -> None:
    """Every check the register names replaced by one reading no scene, answering ``outcome(claim id, reading)``."""
    def answer(spec, ev):
        return Verdict(f"{spec['reading']}", outcome(spec["id"], spec["reading"]))

    for name in checks_named():
        module, function = name.split(".")
        monkeypatch.setattr(importlib.import_module(f"escapement.verdict.{module}"), function,
                            dataclasses.replace(cl.resolved(name), function=answer, scenes=no_scene, runs=()))


def test_changing_one_readings_outcome_changes_the_status(monkeypatch):
    """fig5_recovery_small_K_faster under its three readings: holds under every one, reproduced; under
    some, undetermined (and no figure decides); under none, not reproduced."""
    claim = claim_of(RECOVERY)
    readings = [r["reading"] for r in claim["readings"]]
    for holding, status in ((readings, "reproduced"), (readings[1:], "undetermined"), ([], "not_reproduced"),
                            (readings[:1], "undetermined")):
        stubbed(monkeypatch, lambda claim_id, reading, holding=holding: reading in holding)
        row = cl.evaluate([claim], Evidence({}, None, {}, None))[0]
        assert row["status"] == status, holding
        assert row["readings"] == "; ".join(f'{r} (the paper: "{w}"): {"holds" if r in holding else "fails"}'
                                            for r, w in zip(readings, (r["words"] for r in claim["readings"])))
        decides = "no figure decides between the readings" if status == "undetermined" else "the figures"
        assert row["note"].endswith(f"{decides}: {claim['figures_tried']}")
    assert cl.figures_named("Fig. 3 (a), Figs. 4 and 5") == {"3", "4", "5"} == set(cl.FIGURES)
    assert cl.figures_named("Figs. 3, 4 and 5; Fig. 2 is a sketch") == {"2", "3", "4", "5"}


def test_an_agreement_on_fitted_or_constructed_evidence_is_consistent_and_a_fitted_disagreement_undetermined(
        monkeypatch):
    """The kind of evidence is the weakest of the row's readings', from what their checks declare they
    consume; the register names none. A failure under a chosen reading mirrors the agreement: no verdict."""
    for holds, statuses in ((True, ("reproduced", "consistent", "consistent")),
                            (False, ("not_reproduced", "undetermined", "not_reproduced"))):
        stubbed(monkeypatch, lambda claim_id, reading, holds=holds: holds)
        rows = cl.evaluate([claim_of(i) for i in ("eq16_map", "fig5a_axes", "eq10_impact_a1")],
                           Evidence({}, None, {}, None))
        assert [r["evidence"] for r in rows] == ["independent", "fitted", "by_construction"]
        assert tuple(r["status"] for r in rows) == statuses
    stubbed(monkeypatch, lambda claim_id, reading: None)
    assert cl.evaluate([claim_of("model_describes_system")], Evidence({}, None, {}, None))[0]["status"] == "untestable"


def test_rows_of_one_sentence_share_its_finding_and_rows_beyond_the_paper_have_none(monkeypatch):
    stubbed(monkeypatch, lambda claim_id, reading: True)
    rows = cl.evaluate(register(), Evidence({}, None, {}, None))
    assert list(rows[0]) == COLUMNS
    first: dict[str, str] = {}
    for row in rows:
        if row["origin"] == "paper":
            assert row["finding"] == first.setdefault(row["quote"], row["claim_id"])
        else:
            assert row["finding"] == "" and row["quote"] == ""
    by_id = {row["claim_id"]: row for row in rows}
    assert {by_id[i]["finding"] for i in ("fig3_period_a", "fig3_period_b", "period_is_natural_period")} == {
        "fig3_period_a"}


# --- what the checks consume: the kind of evidence --------------------------------------------------


class Fitted(Exception):
    """A check read a scene or a score fitted to the printed axes."""


class Guarded:
    """Evidence whose fitted parts (the Fig. 4 and Fig. 5 scenes, the autoscaled axes, the scores of the
    candidate readings) refuse to be read."""

    def __init__(self, ev: Evidence):
        self._ev = ev

    def __getattr__(self, name):
        if name in ("fig4", "fig5", "axes", "readings"):
            raise Fitted(name)
        return getattr(self._ev, name)


def solved_fig3(F: float, x0: float, n: int = 50) -> xr.Dataset:
    """A Fig. 3 scene from the exact solver, with the variables the checks read."""
    p = Parameters(**GEOMETRY, F=F)
    run = solve_exact(p, x0, n_cycles=n, record_trajectory=False)
    e, c = run.events, run.cycles
    return xr.Dataset(
        {"velocity_before_impact": ("cycle", c.velocity_before_impact), "period": ("cycle", c.period),
         "event_time": ("event", e.t), "event_kind": ("event", e.kind), "event_position": ("event", e.x),
         "event_velocity_before": ("event", e.v_before), "event_velocity_after": ("event", e.v_after),
         **{k: ((), v) for k, v in {**p.as_dict(), "x0": x0}.items()}},
        coords={"cycle": np.arange(1, n + 1)}, attrs={"outcome": "completed", "outcome_message": "completed"})


def checks_dataset(star: float = 1.25) -> xr.Dataset:
    """Every run the register's checks read, shaped as the checks dataset: the table's groups, given here, the first
    swings, the return map and the runs from the section at ``star`` (the converged speed of Fig. 3 (a)) by hand, and
    the other runs of the configuration as the checks scene makes them."""
    rows = [{"group": "paper", "label": "fig3a"}, {"group": "paper", "label": "fig3b", "F": 0.5},
            {"group": "initial_conditions", "x0": 3.0}, {"group": "asymmetric", "a3": 0.2, "a4": -0.02}]
    rows += [{"group": g, "b": b, "multiplier_eq21": (1 - b) ** 4, "multiplier": (1 - b) ** 4} for b in (0.1, 0.5)
             for g in ("b", "b_continued")]
    rows += [{"group": g, "F": F} for g in ("symmetric", "forces") for F in (0.5, 1.0)]
    rows += [{"group": "releases", "x0": x0, "first_period": 6.3 + x0} for x0 in (-1.0, 1.0)]
    rows += [{"group": "common_force", "K": K, "F": F, "x0": -1.0, "velocity": 1.2}
             for F in (0.5, 1.0) for K in (0.1, 1.0, 10.0)]
    made_here = ("existence", "release_boundary", "release_inside_eq5", "grazing", "airy", "windows",
                 "section_crossings", "springs", "short_releases")
    return xr.merge([runs(*rows), first_swings(), return_map(), phase_shift(star), *(made(n) for n in made_here)])


@functools.cache
def scenes(side: float) -> Evidence:
    fig3 = {"a": solved_fig3(1.0, side * 1.0), "b": solved_fig3(0.5, side * 3.0)}
    return Evidence(fig3=fig3, fig4=None, fig5={},
                    checks=checks_dataset(float(fig3["a"]["velocity_before_impact"].values[-1])))


def test_a_check_that_declares_no_fitted_input_reads_none_and_answers_alike_from_either_release_side():
    """Every reading of the register whose check declares no fitted input runs to its end on evidence whose fitted
    parts refuse to be read (so no check can rest on them and be counted independent), and answers alike from
    either side of the release of Fig. 3, which was chosen from the printed axes."""
    for claim in register():
        for reading in claim["readings"]:
            if cl.resolved(reading["check"]).fitted is None:  # raises, naming the claim, if it reads a fitted part
                sides = [cl.verdict(claim, reading, Guarded(scenes(side))).holds for side in (-1.0, 1.0)]
                assert sides[0] == sides[1], (claim["id"], reading["reading"])


# --- the evaluation's refusals and its answer to a motion that left the regime ------------------------


def test_a_check_that_raises_or_answers_no_outcome_fails_the_evaluation_naming_the_claim(monkeypatch):
    from escapement.verdict import sec3_map
    claim = claim_of("eq16_map")
    for function, cause in ((lambda spec, ev: 1 / 0, ZeroDivisionError), (lambda spec, ev: Verdict("x", "yes"), None)):
        monkeypatch.setattr(sec3_map, "map_eq16", dataclasses.replace(sec3_map.map_eq16, function=function))
        with pytest.raises(cl.ClaimError, match="claim 'eq16_map': check 'sec3_map.map_eq16' ") as info:
            cl.evaluate([claim], scenes(-1.0))
        assert cause is None or isinstance(info.value.__cause__, cause)
    with pytest.raises(cl.ClaimError, match="claim 'eq19_fixed_point_case_a'.*case 'c'"):
        cl.evaluate([{**claim_of("eq19_fixed_point_case_a"), "readings": [
            {**claim_of("eq19_fixed_point_case_a")["readings"][0], "args": {"case": "c"}}]}], scenes(-1.0))


@pytest.mark.parametrize("outcome", ["stopped", "chattering", "turned_back_in_zone", "event_limit"])
def test_every_check_fails_when_a_scene_or_a_run_it_reads_left_the_regime_unless_the_outcome_is_an_answer(outcome):
    """One rule, in the engine: a check that reads a scene that left the escapement regime fails with the scene's
    message; one that reads runs of the checks dataset (tables of runs) fails when one left it, unless the check
    declares that outcome one of its answers (chattering for the stability over b, every outcome for whether the
    runs converge)."""
    left = solved_fig3(1.0, -1.0, n=2).assign_attrs(outcome=outcome, outcome_message=f"{outcome}: a message")
    checks = checks_dataset()
    checks = checks.assign(outcome=checks["outcome"].where(False, outcome),
                           outcome_message=checks["outcome_message"].where(False, f"{outcome}: m"))
    ev = Evidence(fig3={"a": left, "b": left}, fig4=left, fig5={"1": left.assign(K=1.0)}, checks=checks)
    judged = set()
    for claim in register():
        for reading in claim["readings"]:
            check, spec = cl.resolved(reading["check"]), {**claim, **reading}
            read = check.scenes(spec, ev).values()
            table = [n for arg in check.runs for n in names(spec, arg) if "group" in run(ev, n)]
            result = cl.verdict(claim, reading, ev) if read or table else None
            if read:
                assert result.holds is False, claim["id"]
                assert result.replicated_value.endswith(f"left the escapement regime ({outcome})"), claim["id"]
                assert f"{outcome}: a message" in result.note, claim["id"]
            elif table:
                answered = outcome in check.answers
                assert result.replicated_value.startswith("not evaluated: ") is not answered, claim["id"]
                assert answered or (result.holds is False and f"{outcome}: m" in result.note), claim["id"]
                judged.add(reading["check"].split(".")[1])
    assert {"multiplier_paper_cases", "multiplier_only_b", "stable_velocity_scaling", "runs_converge"} <= judged


def test_a_printed_period_is_judged_at_half_a_unit_of_its_last_printed_digit():
    """The tolerance of a printed number is half a unit of its last printed digit: for the printed 6.2832 s,
    5e-5 s, derived here from the printed text; a period just inside it reproduces the claim, one just
    outside does not, so a tolerance loosened in the register or applied wrongly fails."""
    printed = "6.2832"
    half_unit = 0.5 * 10.0 ** -len(printed.split(".")[1])
    for claim_id in ("fig3_period_a", "fig3_period_b"):
        row = register_row(claim_id, half_unit)
        assert float(row["paper_value"]) == float(printed)
        bounded(row, lambda off, row=row: Evidence({row["args"]["case"]: solved_fig3(1.0, -1.0, n=2).assign(
            period=("cycle", [6.3, float(printed) + off]))}, None, {}, None), margin=1e-3)


#: each module of the checks, in the paper's order, with the sources (the register's ``source``) it holds
PARTS = (
    ("sec2_model", r"^Sec\. 2\b"),
    ("sec3_equations", r"^Eqs?\. \((2|3[abc]|4|5)\)|^Secs?\. 3\.3"),
    ("sec3_steps", r"^Eqs?\. \(1[0-5]\)"),
    ("sec3_map", r"^Eqs?\. \((7|8|1[6-9]|2[01])\)|^Sec\. 3\.4"),
    ("sec3_period", r"^Eqs?\. \(2[2-5]"),
    ("sec4_fig3", r"^Sec\. 4"),
    ("sec4_fig4", r"^Sec\. 4; Fig\. 4"),
    ("sec4_fig5", r"^Sec\. 4; Fig\. 5"),
    ("sec5_conclusions", r"^(Sec\. 5|Abstract)"),
    ("figure_axes", r"^Fig\. [345]\b"),
    ("beyond", r"beyond the paper"),
    ("derivations", r": the derivation$"),
)


def part_of(source: str) -> int:
    """The index in :data:`PARTS` of the part of the paper ``source`` names: of the patterns it matches, the last
    (the narrowest: ``Sec. 4; Fig. 4`` is Fig. 4's, not Sec. 4's)."""
    found = [i for i, (_, pattern) in enumerate(PARTS) if re.search(pattern, source)]
    assert found, f"no module of the checks holds the source {source!r}"
    return found[-1]


def test_a_checks_module_follows_from_the_source_of_its_claims():
    """Each check sits in the module of the earliest part of the paper among the sources of the claims that use it,
    so a reader finds a claim's check from its source; ``evidence.untestable`` alone, the check of every claim the
    paper gives nothing to compute against, sits with the evidence."""
    users: dict[str, list[str]] = {}
    for claim in register():
        for reading in claim["readings"]:
            users.setdefault(reading["check"], []).append(claim["source"])
    expected = {name: PARTS[min(part_of(s) for s in sources)][0] for name, sources in users.items()}
    assert {name: name.split(".")[0] for name in users} == {**expected, "evidence.untestable": "evidence"}
    assert part_of("Sec. 4; Fig. 4") == 6 and part_of("Sec. 4; Fig. 3 (beyond the paper)") == 10
