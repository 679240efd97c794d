"""The verdict's words: a check's status weighed by the kind of evidence it rests on, and the register
refusing a row without an origin, a finding or a kind of evidence from the vocabulary."""

from __future__ import annotations

import pytest
import yaml

from escapement.paper.claims import load_claims
from escapement.paper.vocabulary import EVIDENCE, STATUSES, weighed


@pytest.mark.parametrize("evidence, found, expected", [
    ("independent", "reproduced", "reproduced"),
    ("independent", "not_reproduced", "not_reproduced"),
    ("by_construction", "reproduced", "consistent"),
    ("fitted", "reproduced", "consistent"),
    # a fitted reading that still misses: no reading of the grid reaches the claim
    ("fitted", "partially_reproduced", "partially_reproduced"),
    ("fitted", "not_reproduced", "not_reproduced"),
    ("independent", "undetermined", "undetermined"),
    ("none", "reproduced", "untestable"),
    ("none", "untestable", "untestable"),
])
def test_an_agreement_by_construction_or_by_choice_is_only_consistent(evidence, found, expected):
    assert weighed(found, evidence) == expected


def test_every_weighed_status_is_a_status_and_unknown_words_are_refused():
    assert {weighed(s, e) for s in STATUSES for e in EVIDENCE} <= set(STATUSES)
    with pytest.raises(ValueError, match="status = 'fine' must be one of reproduced, partially_reproduced"):
        weighed("fine", "independent")
    with pytest.raises(ValueError, match="evidence = 'strong' must be one of independent, by_construction"):
        weighed("reproduced", "strong")


def _register(tmp_path, **over):
    claim = {"id": "c", "source": "S", "origin": "paper", "finding": "period", "evidence": "independent",
             "statement": "s", "paper_value": None, "tolerance": 1e-8, "tolerance_reason": "r", "check": "fixed_point",
             "args": {"case": "a"}}
    path = tmp_path / "claims.yaml"
    path.write_text(yaml.safe_dump({"version": 1, "claims": [{**claim, **over}]}))
    return path


@pytest.mark.parametrize("over, message", [
    ({"origin": "elsewhere"}, "has origin = 'elsewhere'; it must be one of paper, beyond"),
    ({"evidence": "strong"}, "has evidence = 'strong'; it must be one of independent, by_construction, fitted, none"),
    ({"finding": "The Period"}, "has finding = 'The Period'; it must be a name of lower-case letters"),
    ({"finding": 3}, "has finding = 3"),
])
def test_the_register_refuses_a_row_outside_the_vocabulary(tmp_path, over, message):
    with pytest.raises(ValueError, match=message):
        load_claims(_register(tmp_path, **over))


def test_the_register_refuses_a_row_without_its_weight(tmp_path):
    path = _register(tmp_path)
    data = yaml.safe_load(path.read_text())
    del data["claims"][0]["evidence"]
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(ValueError, match="claim 0 lacks 'evidence'"):
        load_claims(path)
    assert load_claims(_register(tmp_path))[0]["finding"] == "period"
