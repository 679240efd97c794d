"""The article's parts that need no run: the title's rule, the Typst escapes, the journal's metadata from
CITATION.cff, and its tables from typed columns (the article written by a run is tested in tests/test_workflow.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from escapement.pipeline.article import RULE, _axes, _readings, _register, metadata, prefix, string, typ
from escapement.verdict.scores import CLAIM_AUTOSCALE, TICKS

REPO = Path(__file__).resolve().parents[2]
COUNTS = {"reproduced": 0, "consistent": 0, "partially_reproduced": 0, "not_reproduced": 0, "undetermined": 0,
          "untestable": 0}


@pytest.mark.parametrize("held, failed, expected", [((23, 9), (2, 11), "[Re]"), ((5, 1), (6, 0), "[¬Re]"),
                                                    ((3, 3), (0, 7), "[¬Re]"), ((4, 9), (5, 0), "[¬Re]"),
                                                    ((1, 0), (0, 0), "[Re]"), ((0, 1), (0, 0), "[¬Re]")])
def test_the_title_says_re_when_the_reproduced_findings_outnumber_those_that_fail(held, failed, expected):
    """A consistent finding confirms nothing: (4, 9) against 5 failures is [¬Re], though 13 hold."""
    counts = {**COUNTS, "reproduced": held[0], "consistent": held[1], "partially_reproduced": failed[0],
              "not_reproduced": failed[1], "undetermined": 40, "untestable": 9}  # neither counts
    assert prefix(counts) == expected
    assert "[Re]" in RULE and "[¬Re]" in RULE and "consistent, undetermined and untestable findings count" in RULE


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
                                   r"[Velocity (m\/s): \[0.1, 0.9\]], [1 of 2 limits], [not reproduced]")


@pytest.mark.parametrize("same, said, tie", [
    ("a3", "[2 of 2], [section a1 | section a3]", "2 of 2 readings tie (undetermined)"),
    ("a1", r"[1 of 2], [from \+x0, section a1; period]", "2 identical of 2 readings lead")])
def test_the_readings_table_says_only_what_the_tied_readings_differ_in(same, said, tie):
    """Two readings at 4 of 4 limits: where they plot different values, only the words they differ in are shown."""
    name = "from +x0, section {}; period".format
    scores = [{"figure": "5", "panel": "b", "axis": axis, "reading": name(section), "autoscale": CLAIM_AUTOSCALE,
               "ticks": ticks, "matches": 2, "same_values_as": name(same if section == "a3" else "a1")}
              for axis in ("x", "y") for section in ("a1", "a3") for ticks in TICKS]
    cells, ties = _readings(scores)
    assert cells == f"[5 b], [4 of 4 (4)], {said}"
    assert ties == {"5 b": tie}


def test_the_register_quotes_a_sentence_once_for_all_its_rows_and_cuts_no_cell():
    quote = "It is also noted that the period for both motions are identical as 6.2832 s, " * 3
    rows = [{"source": "Sec. 4", "origin": "paper", "quote": quote, "part": part, "evidence": "independent",
             "status": "not_reproduced"} for part in ("case (a)", "case (b)")]
    rows.append({"source": "Eq. (25)", "origin": "beyond", "quote": "Airy", "part": "", "evidence": "by_construction",
                 "status": "consistent"})
    cells = _register(rows).split(",\n")
    assert cells[0] == (f"[Sec. 4], table.cell(rowspan: 2)[{quote}], [case (a)], [independent], [not reproduced]")
    assert cells[1] == "[Sec. 4], [case (b)], [independent], [not reproduced]"
    assert cells[2] == ("[Eq. (25) (beyond the paper)], table.cell(rowspan: 1)[Airy], [], [by construction], "
                        "[consistent]")
