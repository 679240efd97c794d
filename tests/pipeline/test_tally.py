"""The headline counts findings, not rows: on synthetic rows, and on the committed REPLICATION.md, whose
headline is recounted here from its own table of all claims with code of the test's own."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from escapement.pipeline.tally import findings_table, headline, tally

REPO = Path(__file__).resolve().parents[2]


def row(claim, status, finding="f", evidence="independent", origin="paper") -> dict:
    return {"claim_id": claim, "status": status, "finding": finding, "evidence": evidence, "origin": origin}


ROWS = [
    row("p1", "not_reproduced", "period"),
    row("p2", "not_reproduced", "period"),
    row("p3", "not_reproduced", "period", evidence="fitted"),  # no reading of the grid reaches the axes: apart
    row("ax2", "partially_reproduced", "axes_limit", evidence="fitted"),  # a fitted row is never a finding
    row("m1", "reproduced", "map"),
    row("m2", "reproduced", "map"),
    row("r", "partially_reproduced", "release"),
    row("law", "consistent", "impact_law", evidence="by_construction"),
    row("ax", "consistent", "axes", evidence="fitted"),
    row("u", "undetermined", "matrix"),
    row("t", "untestable", "accuracy", evidence="none"),
    row("airy", "reproduced", "airy", origin="beyond"),
    row("rate", "not_reproduced", "period", origin="beyond"),
]


def test_one_root_cause_counts_once_and_the_rest_apart():
    t = tally(ROWS)
    assert t.paper_rows == 11
    assert t.findings == {"period": "not_reproduced", "map": "reproduced", "release": "partially_reproduced"}
    assert (t.count("reproduced"), t.count("partially_reproduced"), t.count("not_reproduced")) == (1, 1, 1)
    assert (t.by_construction, t.undetermined, t.untestable) == (("law",), ("u",), ("t",))
    assert t.by_choice == {"p3": "not_reproduced", "ax2": "partially_reproduced", "ax": "consistent"}
    assert t.beyond == ("airy", "rate")


def test_the_headline_says_the_counts():
    text = headline(ROWS)
    assert "fill 11 rows" in text and "3 findings: 1 reproduced, 1 partially reproduced and 1 not reproduced" in text
    assert "consistent by construction (the model is built from them): 1;" in text
    assert ("rows under a reading chosen from the same printed axes: 3 (1 consistent with it, 1 partly and 1 not met "
            "by any reading of the grid);") in text
    assert "the claim holds and fails): 1;" in text and "untestable from the paper's evidence: 1." in text
    assert "Beyond the paper, and not counted: 2 rows." in text


def test_a_finding_whose_rows_disagree_counts_at_its_weakest_row_and_says_so():
    rows = [*ROWS, row("m3", "partially_reproduced", "map"), row("r2", "not_reproduced", "release")]
    t = tally(rows)
    assert t.findings["map"] == "partially_reproduced" and t.findings["release"] == "not_reproduced"
    assert t.mixed == ("map", "release")
    assert headline(rows).endswith(
        "The rows of 2 findings disagree (map, release); each is counted at its weakest row.")
    assert "disagree" not in headline(ROWS)
    assert findings_table(rows)[0] == {"finding": "map", "verdict": "partially reproduced (its rows disagree)",
                                       "rows": "`m1`, `m2`, `m3`"}
    with pytest.raises(ValueError, match="claim 'x' has status = 'maybe'"):
        tally([row("x", "maybe")])


def test_the_findings_table_lists_each_finding_once_with_its_rows():
    table = findings_table(ROWS)
    assert [r["finding"] for r in table] == ["map", "release", "period"]
    assert table[2] == {"finding": "period", "verdict": "not reproduced", "rows": "`p1`, `p2`"}


def _committed_table(markdown: str) -> list[dict]:
    """The rows of REPLICATION.md's table of all claims: | `id` | where | finding | evidence | paper | replicated |
    verdict |, the cells split on unescaped bars."""
    rows = []
    for line in markdown.splitlines():
        if line.startswith("| `"):
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
            if len(cells) == 7:
                rows.append({"id": cells[0].strip("`"), "beyond": "(beyond the paper)" in cells[1],
                             "finding": cells[2], "evidence": cells[3], "verdict": cells[6]})
    return rows


def test_the_committed_headline_recounts_from_the_committed_table():
    text = (REPO / "REPLICATION.md").read_text()
    rows = _committed_table(text)
    assert len(rows) >= 56
    verdicts = {"reproduced": "r", "partially reproduced": "p", "**not reproduced**": "n"}
    paper = [r for r in rows if not r["beyond"]]
    findings: dict[str, set] = {}
    for r in paper:
        if r["evidence"] == "independent" and r["verdict"] in verdicts:
            findings.setdefault(r["finding"], set()).add(verdicts[r["verdict"]])
    # in the paper's configuration the rows of one root cause agree: the register groups them rightly
    assert all(len(s) == 1 for s in findings.values()), findings
    assert "its rows disagree" not in text
    kinds = [next(iter(s)) for s in findings.values()]
    expected = (
        f"The paper's claims fill {len(paper)} rows of the register. The rows with an independent verdict come "
        f"down to {len(findings)} findings: {kinds.count('r')} reproduced, {kinds.count('p')} partially reproduced "
        f"and {kinds.count('n')} not reproduced."
    )
    words = " ".join(text.split())
    assert expected in words
    fitted = [r["verdict"] for r in paper if r["evidence"] == "fitted"]
    assert f"consistent by construction (the model is built from them): " \
           f"{sum(r['evidence'] == 'by construction' for r in paper)};" in words
    assert (f"same printed axes: {len(fitted)} ({fitted.count('consistent')} consistent with it, "
            f"{fitted.count('partially reproduced')} partly and {fitted.count('**not reproduced**')} not met") in words
    assert f"the claim holds and fails): {sum(r['verdict'] == 'undetermined' for r in paper)};" in words
    assert f"untestable from the paper's evidence: {sum(r['verdict'] == 'untestable' for r in paper)}." in words
    assert f"Beyond the paper, and not counted: {len(rows) - len(paper)} rows." in words
