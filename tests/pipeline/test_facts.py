"""Measured values (wall times) never reach a document git tracks."""

import pytest

from escapement.pipeline.docs import render
from escapement.pipeline.facts import Fact

FACTS = {"ratio": Fact("581", measured=True), "error": Fact("1e-16")}


def test_a_tracked_document_shows_deterministic_facts():
    assert render("error {{ fact.error }}", [], "README.md", FACTS).endswith("error 1e-16")


def test_a_tracked_document_may_not_show_a_measured_fact():
    with pytest.raises(ValueError, match=r"README.md: \{\{ fact.ratio \}\} is a measured value"):
        render("ratio {{ fact.ratio }}", [], "README.md", FACTS)


def test_the_timings_document_shows_measured_facts():
    assert render("ratio {{ fact.ratio }}", [], "timings.md", FACTS, measured=True).endswith("ratio 581")
