"""The article's parts that need no run: the title's rule, the Typst escapes, the journal's metadata from
CITATION.cff, and its tables from typed columns (the article written by a run is tested in tests/test_workflow.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from escapement.pipeline.article import RULE, _axes, _readings, metadata, prefix, string, typ
from escapement.verdict.scores import CLAIM_AUTOSCALE, TICKS

REPO = Path(__file__).resolve().parents[2]
COUNTS = {"reproduced": 0, "consistent": 0, "partially_reproduced": 0, "not_reproduced": 0, "undetermined": 0,
          "untestable": 0}


@pytest.mark.parametrize("held, failed, expected", [((23, 9), (2, 11), "[Re]"), ((5, 1), (6, 0), "[¬Re]"),
                                                    ((3, 3), (0, 7), "[¬Re]"), ((0, 1), (0, 0), "[Re]")])
def test_the_title_says_re_when_the_findings_that_hold_outnumber_those_that_fail(held, failed, expected):
    counts = {**COUNTS, "reproduced": held[0], "consistent": held[1], "partially_reproduced": failed[0],
              "not_reproduced": failed[1], "undetermined": 40, "untestable": 9}  # neither counts
    assert prefix(counts) == expected
    assert "[Re]" in RULE and "[¬Re]" in RULE and "outnumber" in RULE


def test_text_from_the_run_shows_as_it_is_in_typst():
    assert typ("x1(k+1) = sqrt(v^2 - 2 f) [m/s] #1 @a $b_c* <d> // e") == (
        r"x1(k\+1) \= sqrt(v^2 \- 2 f) \[m\/s\] \#1 \@a \$b\_c\* \<d\> \/\/ e")
    assert string('a "quoted" \\ path') == 'a \\"quoted\\" \\\\ path'


def test_the_metadata_has_the_journals_fields_and_invents_no_person():
    citation = yaml.safe_load((REPO / "CITATION.cff").read_text(encoding="utf-8"))
    meta = metadata(citation, "[Re] T", "An abstract.")
    assert list(meta)[:12] == ["title", "authors", "affiliations", "keywords", "code", "data", "replication",
                               "abstract", "bibliography", "type", "domain", "language"]
    assert meta["type"] == "Replication" and meta["language"] == "Python" and meta["title"] == "[Re] T"
    assert [a["name"] for a in meta["authors"]] == [a["name"] for a in citation["authors"]]
    assert meta["replication"][3] == {"doi": "10.3233/SAV-130800"}
    assert meta["code"][0] == {"url": citation.get("repository-code", "")}
    assert meta["journal"][0] == {"name": "ReScience C"} and meta["contributors"][0]["name"] == ""


def test_the_axes_table_cites_the_limits_the_claim_judged_beside_the_printed_ones_never_the_rows_words():
    """Fig. 4's velocity panel: its one scored axis, printed -0.1 to 0.9 m/s, the run's limits from the table beside
    the claims; the row's words carry no number."""
    rows = [{"claim_id": "v_axis", "source": "Fig. 4, velocity panel", "status": "not_reproduced",
             "replicated_value": "words only", "paper_value": "words only"}]
    limits = [{"claim_id": "v_axis", "figure": "4", "panel": "velocity", "axis": "y", "low": "0.1", "high": "0.9"}]
    assert _axes(rows, limits) == (r"[Fig. 4, velocity panel], [Velocity (m\/s): \[\-0.1, 0.9\]], "
                                   r"[Velocity (m\/s): \[0.1, 0.9\]], [not reproduced]")


@pytest.mark.parametrize("same, said", [
    ("r2", r"undetermined: 2 readings tie, plotting different values of 2: #linebreak() r1 #linebreak() r2"),
    ("r1", r"2 equivalent readings (identical values) of 2: #linebreak() r1 \= r2")])
def test_the_readings_table_names_the_readings_tied_at_the_best_score(same, said):
    scores = [{"figure": "5", "panel": "b", "axis": axis, "reading": name, "autoscale": CLAIM_AUTOSCALE,
               "ticks": ticks, "matches": 2, "same_values_as": same if name == "r2" else "r1"}
              for axis in ("x", "y") for name in ("r1", "r2") for ticks in TICKS]
    assert _readings(scores) == f"[5 b], [4 of 4 (4 with the default locator)], [{said}]"
