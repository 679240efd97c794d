"""The one rule of the verdict, as tables: a claim's status from its readings' outcomes, weighed by the kind
of evidence, a reading's kind of evidence from what its check consumes, and a finding's status from its
parts'; and the headline, which counts sentences, not rows (on synthetic rows whose findings are known by
construction)."""

from __future__ import annotations

import pytest

from escapement.verdict.rule import EVIDENCE, STATUSES, evidence_of, finding_status, row_status, status_of, weighed
from escapement.verdict.tally import findings, findings_table, headline, vocabulary_table


@pytest.mark.parametrize("outcomes, status", [
    ([True], "reproduced"),
    ([True, True, True], "reproduced"),
    ([True, False], "undetermined"),
    ([False, True, False], "undetermined"),
    ([False], "not_reproduced"),
    ([False, False], "not_reproduced"),
    ([None], "untestable"),
])
def test_a_claim_holds_under_every_reading_some_or_none(outcomes, status):
    assert status_of(outcomes) == status


@pytest.mark.parametrize("outcomes", [[], [None, True]])
def test_no_outcome_or_a_reading_that_computed_nothing_beside_others_is_refused(outcomes):
    with pytest.raises(ValueError, match="every reading computes an outcome, or none does"):
        status_of(outcomes)


#: what a check consumes: a fitted input, a threshold the project chose, a law of the model
FITTED, THRESHOLD, LAW = (None, "Fig. 5's force", None), (None, None, "'clearly' 2 %"), ("the impact law", None, None)


@pytest.mark.parametrize("readings, kind, status", [
    ([(None, None, None, True)], "independent", "reproduced"),
    ([(None, None, None, False)], "independent", "not_reproduced"),
    ([(*FITTED, True)], "fitted", "consistent"),
    ([(*THRESHOLD, True)], "fitted", "consistent"),
    ([(*FITTED, False)], "fitted", "undetermined"),  # a failure under a chosen reading mirrors the agreement
    ([(*THRESHOLD, False)], "fitted", "undetermined"),
    ([(*THRESHOLD, {"1e-09": False, "1e-08": False})], "fitted", "undetermined"),
    ([(None, None, None, False), (*FITTED, False)], "fitted", "undetermined"),
    ([(*LAW, False)], "by_construction", "not_reproduced"),
    ([(*LAW, True)], "by_construction", "consistent"),
    ([("the impact law", "Fig. 4's scene", None, True)], "by_construction", "consistent"),
    ([(*LAW, True), (*LAW, False)], "by_construction", "undetermined"),
    ([(None, None, None, None)], "none", "untestable"),
    # the weakest reading's kind; every outcome of a grid a check walks
    ([(None, None, None, True), (*FITTED, True)], "fitted", "consistent"),
    ([(*FITTED, True), (*LAW, True), (None, None, None, True)], "by_construction", "consistent"),
    ([(None, None, None, {"a": True, "b": False})], "independent", "undetermined"),
    ([(*LAW, False), (*LAW, {"a": False})], "by_construction", "not_reproduced"),
])
def test_the_evidence_follows_from_what_the_checks_consume_and_a_chosen_reading_weighs_agreement_and_failure(
        readings, kind, status):
    assert row_status(readings) == (kind, status)
    if len(readings) == 1:
        assert evidence_of(*readings[0]) == kind


def test_the_weighing_keeps_the_vocabulary():
    assert {weighed(s, e) for s in ("reproduced", "not_reproduced", "undetermined") for e in EVIDENCE} <= set(STATUSES)
    with pytest.raises(ValueError, match="not words of the vocabulary"):
        weighed("fine", "independent")


@pytest.mark.parametrize("parts, status", [
    (["reproduced", "reproduced"], "reproduced"),
    (["reproduced", "consistent"], "consistent"),
    (["reproduced", "undetermined"], "undetermined"),
    (["undetermined", "undetermined"], "undetermined"),
    (["reproduced", "not_reproduced"], "partially_reproduced"),
    (["consistent", "not_reproduced", "undetermined"], "not_reproduced"),  # a consistent part confirms nothing
    (["consistent", "not_reproduced"], "not_reproduced"),
    (["reproduced", "consistent", "not_reproduced"], "partially_reproduced"),
    (["undetermined", "not_reproduced"], "not_reproduced"),
    (["not_reproduced", "not_reproduced"], "not_reproduced"),
    (["untestable", "reproduced"], "undetermined"),  # an untestable part never counts as holding
    (["untestable", "not_reproduced"], "not_reproduced"),
    (["untestable", "reproduced", "not_reproduced"], "partially_reproduced"),
    (["untestable"], "untestable"),
])
def test_a_finding_takes_the_rule_over_its_parts(parts, status):
    assert finding_status(parts) == status


def test_the_finding_rule_is_one_rule_over_every_combination_of_parts():
    """Every combination of up to four part statuses: the order of the parts does not matter; a consistent part
    changes no finding but a reproduced one (to consistent) and an untestable one (to undetermined); partially
    reproduced exactly when a part is reproduced and another not reproduced; reproduced or consistent exactly when
    every part holds."""
    import itertools

    row_statuses = [s for s in STATUSES if s != "partially_reproduced"]  # a row is never partial
    for n in range(1, 5):
        for parts in itertools.combinations_with_replacement(row_statuses, n):
            found = finding_status(parts)
            assert all(finding_status(p) == found for p in itertools.permutations(parts))
            alone = finding_status([*parts, "consistent"])
            assert alone == {"reproduced": "consistent", "untestable": "undetermined"}.get(found, found), parts
            assert (found == "partially_reproduced") == ("reproduced" in parts and "not_reproduced" in parts)
            assert (found in ("reproduced", "consistent")) == (set(parts) <= {"reproduced", "consistent"}), parts


# --- the headline: the findings counted -------------------------------------------------------------


def row(claim, status, finding, part="", origin="paper") -> dict:
    return {"claim_id": claim, "status": status, "finding": finding if origin == "paper" else "", "part": part,
            "origin": origin, "quote": f"The sentence of {finding}." if origin == "paper" else ""}


ROWS = [
    row("p1", "not_reproduced", "period", "case (a)"),
    row("p2", "not_reproduced", "period", "case (b)"),
    row("m1", "reproduced", "map", "case (a)"),
    row("m2", "reproduced", "map", "case (b)"),
    row("s1", "consistent", "sets", "S2"),
    row("s2", "not_reproduced", "sets", "S-bar"),
    row("ax", "consistent", "axes"),
    row("law", "consistent", "law"),
    row("u1", "undetermined", "linear"),
    row("u2", "undetermined", "stable", "b = 0.1"),
    row("u3", "not_reproduced", "stable", "0 < b < 2"),
    row("r1", "undetermined", "release", "the amplitude"),
    row("r2", "reproduced", "release", "the force"),
    row("t", "untestable", "accuracy"),
    row("airy", "reproduced", "", origin="beyond"),
    row("rate", "not_reproduced", "", origin="beyond"),
]
#: each finding's status by the rule, worked out by hand
EXPECTED = {"period": "not_reproduced", "map": "reproduced", "sets": "not_reproduced", "axes": "consistent",
            "law": "consistent", "linear": "undetermined", "stable": "not_reproduced", "release": "undetermined",
            "accuracy": "untestable"}


def test_each_sentence_is_one_finding_with_the_status_of_its_parts():
    found = findings(ROWS)
    assert {name: status for name, (status, _) in found.items()} == EXPECTED
    assert [r["claim_id"] for r in found["period"][1]] == ["p1", "p2"]


def test_the_headline_counts_the_findings_and_names_the_replication_by_them():
    assert headline(ROWS) == ("Partial replication: 1 of 9 findings reproduced, 2 consistent, 0 partially reproduced, "
                              "3 not reproduced, 2 undetermined, 1 untestable (2 rows beyond the paper, not counted).")
    assert headline(ROWS[2:4]).startswith("Full replication: 1 of 1 findings reproduced, 0 consistent")
    assert headline(ROWS[:2] + ROWS[-1:]).startswith("Failed replication: 0 of 1 findings reproduced")
    assert headline(ROWS[:2] + ROWS[-1:]).endswith("(1 row beyond the paper, not counted).")


def test_the_findings_table_lists_each_finding_once_with_its_parts():
    table = findings_table(ROWS)
    assert [r["finding"] for r in table] == ["map", "axes", "law", "period", "sets", "stable", "linear", "release",
                                             "accuracy"]
    assert table[4] == {"finding": "sets", "quote": "The sentence of sets.", "verdict": "not reproduced",
                        "rows": "`s1` (S2: consistent), `s2` (S-bar: not reproduced)"}
    assert table[1]["rows"] == "`ax`"


def test_a_status_outside_the_vocabulary_is_refused():
    with pytest.raises(ValueError, match="claim 'x' has status = 'maybe'"):
        findings([row("x", "maybe", "f")])


def test_the_vocabulary_table_defines_every_word():
    words = [r["word"] for r in vocabulary_table()]
    assert "status: partially reproduced" in words and "evidence: by construction" in words
    assert "origin: beyond" in words and all(r["meaning"] for r in vocabulary_table())


def test_the_rule_the_tally_and_the_scores_load_without_numpy_or_xarray():
    """The documents' jobs read the claims table, its columns and its numbers (fmt), the tally and the scores of the
    readings: a process that imports those three modules loads neither NumPy nor xarray."""
    import subprocess
    import sys
    code = ("import sys, escapement.verdict.rule, escapement.verdict.tally, escapement.verdict.scores; "
            "print(sorted({'numpy', 'xarray', 'pandas'} & set(sys.modules)))")
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout == "[]\n"
