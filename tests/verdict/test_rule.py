"""The one rule of the verdict, as tables: a claim's status from its readings' outcomes, weighed by the kind
of evidence, a reading's kind of evidence from what its check consumes, and a finding's status from its
parts'."""

from __future__ import annotations

import pytest

from escapement.verdict.rule import EVIDENCE, STATUSES, evidence_of, finding_status, row_status, status_of, weighed


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


@pytest.mark.parametrize("law, fitted, threshold, holds, kind", [
    (None, None, None, True, "independent"),
    (None, None, None, False, "independent"),
    (None, "Fig. 5's force", None, True, "fitted"),
    (None, None, "'clearly' as 2 %", True, "fitted"),
    ("the impact law", None, None, True, "by_construction"),
    ("the impact law", "Fig. 4's scene", None, True, "by_construction"),
    (None, None, None, None, "none"),
])
def test_the_kind_of_evidence_follows_from_what_the_check_consumes(law, fitted, threshold, holds, kind):
    assert evidence_of(law, fitted, threshold, holds) == kind


@pytest.mark.parametrize("status, evidence, weighed_status", [
    ("reproduced", "independent", "reproduced"),
    ("reproduced", "fitted", "consistent"),
    ("reproduced", "by_construction", "consistent"),
    ("undetermined", "by_construction", "undetermined"),
    ("not_reproduced", "fitted", "not_reproduced"),
    ("untestable", "none", "untestable"),
])
def test_an_agreement_by_construction_or_on_fitted_evidence_is_only_consistent(status, evidence, weighed_status):
    assert weighed(status, evidence) == weighed_status


def test_a_rows_evidence_is_its_weakest_readings_and_its_status_every_outcome_weighed():
    fitted, law = (None, "Fig. 5's force", None), ("the impact law", None, None)
    assert row_status([(None, None, None, True), (*fitted, True)]) == ("fitted", "consistent")
    assert row_status([(*fitted, True), (*law, True), (None, None, None, True)]) == ("by_construction", "consistent")
    assert row_status([(None, None, None, {"a": True, "b": False})]) == ("independent", "undetermined")
    assert row_status([(*law, False), (*law, {"a": False})]) == ("by_construction", "not_reproduced")
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
