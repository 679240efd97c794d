"""The headline counts sentences, not rows: on synthetic rows of the claims table whose findings are known by
construction."""

from __future__ import annotations

import pytest

from escapement.verdict.tally import findings, findings_table, headline, vocabulary_table


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


def test_the_headline_says_its_rule_and_the_counts():
    text = headline(ROWS)
    assert "quotes 9 sentences of the paper, checked in 14 rows. Each sentence is one finding" in text
    assert "partially reproduced when a part is reproduced and another fails under every reading" in text
    assert ("Of the 9 findings, 1 are reproduced, 2 consistent, 0 partially reproduced, 3 not reproduced, 2 "
            "undetermined and 1 untestable. Beyond the paper, and not counted: 2 rows.") in text


def test_the_findings_table_lists_each_finding_once_with_its_parts():
    table = findings_table(ROWS)
    assert [r["finding"] for r in table] == ["map", "axes", "law", "period", "sets", "stable", "linear", "release",
                                             "accuracy"]
    assert table[4] == {"finding": "sets", "sentence": "The sentence of sets.", "verdict": "not reproduced",
                        "rows": "`s1` (S2: consistent), `s2` (S-bar: not reproduced)"}
    assert table[1]["rows"] == "`ax`"


def test_a_status_outside_the_vocabulary_is_refused():
    with pytest.raises(ValueError, match="claim 'x' has status = 'maybe'"):
        findings([row("x", "maybe", "f")])


def test_the_vocabulary_table_defines_every_word():
    words = [r["word"] for r in vocabulary_table()]
    assert "status: partially reproduced" in words and "evidence: by construction" in words
    assert "origin: beyond" in words and all(r["meaning"] for r in vocabulary_table())
