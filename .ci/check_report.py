"""Open the Snakemake report in headless Chromium and check, in the rendered DOM, that its landing
page shows the verdict: the claims table with one visible row per claim of results/replication/claims.csv, and
the stress table with one per row of results/replication/stress.csv; and that it shows REPLICATION.md
(results/replication/docs/REPLICATION.md) rendered as HTML: every heading of the document as a heading, each of
its tables as a table and each fenced code block as a <pre> block. The text of the report's
scripts (which embed the same HTML as data) and hidden elements do not count.

Usage: python .ci/check_report.py results/report.html
"""

import csv
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path


HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
FENCE = re.compile(r"^(```|~~~)")
TABLE_RULE = re.compile(r"^\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)+\|?\s*$")
NOT_SHOWN = {"script", "style", "template", "noscript"}


def normalised(text: str) -> str:
    return " ".join(text.split())


def markdown_outline(text: str) -> tuple[list[str], int, int]:
    """The headings (their text, inline markup removed), the number of pipe tables and the number
    of fenced code blocks of a Markdown document."""
    headings, tables, fences, in_fence = [], 0, 0, False
    for line in text.splitlines():
        if FENCE.match(line):
            fences += not in_fence
            in_fence = not in_fence
        elif in_fence:
            continue
        elif match := HEADING.match(line):
            headings.append(normalised(re.sub(r"[`*]", "", match.group(2))))
        elif TABLE_RULE.match(line):
            tables += 1
    return headings, tables, fences


class Tables(HTMLParser):
    """Rows of the tables with an id, as lists of cell texts; the texts of the headings, the number
    of tables without an id and of <pre> blocks; all outside scripts and hidden elements."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: dict[str, list[list[str]]] = {}
        self.headings: list[str] = []
        self.anonymous_tables = 0
        self.pre_blocks = 0
        self._table: str | None = None
        self._row: list[str] | None = None
        self._cell: list[str] | None = None
        self._heading: list[str] | None = None
        self._skipped: tuple[str, int] | None = None  # (tag, depth) of the element not shown

    def _starts_hidden(self, tag, attrs) -> bool:
        style = (attrs.get("style") or "").replace(" ", "")
        return tag in NOT_SHOWN or "hidden" in attrs or "display:none" in style or "visibility:hidden" in style

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if self._skipped is not None:
            if tag == self._skipped[0]:
                self._skipped = (tag, self._skipped[1] + 1)
            return
        if self._starts_hidden(tag, attrs):
            self._skipped = (tag, 1)
            return
        if re.fullmatch(r"h[1-6]", tag):
            self._heading = []
        elif tag == "pre":
            self.pre_blocks += 1
        elif tag == "table" and not attrs.get("id"):
            self.anonymous_tables += 1
        if tag == "table" and attrs.get("id"):
            self._table = attrs["id"]
            self.rows[self._table] = []
        elif tag == "tr" and self._table:
            self._row = []
        elif tag == "td" and self._row is not None:
            self._cell = []

    def handle_endtag(self, tag):
        if self._skipped is not None:
            if tag == self._skipped[0]:
                depth = self._skipped[1] - 1
                self._skipped = (tag, depth) if depth else None
            return
        if re.fullmatch(r"h[1-6]", tag) and self._heading is not None:
            self.headings.append(normalised("".join(self._heading)))
            self._heading = None
        if tag == "td" and self._cell is not None:
            self._row.append("".join(self._cell).strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            if self._row:
                self.rows[self._table].append(self._row)
            self._row = None
        elif tag == "table":
            self._table = None

    def handle_data(self, data):
        if self._skipped is not None:
            return
        if self._cell is not None:
            self._cell.append(data)
        if self._heading is not None:
            self._heading.append(data)


def main(report: str) -> None:
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        sys.exit("chromium is not installed (Debian package: chromium)")
    dom = subprocess.run(
        [browser, "--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=20000", "--dump-dom",
         Path(report).resolve().as_uri()],
        capture_output=True, text=True, timeout=300, check=True,
    ).stdout
    tables = Tables()
    tables.feed(dom)
    with open("results/replication/claims.csv", newline="") as handle:
        claims = [row["claim_id"] for row in csv.DictReader(handle)]
    with open("results/replication/stress.csv", newline="") as handle:
        stress = [row["regime"] for row in csv.DictReader(handle)]
    shown_claims = [row[0] for row in tables.rows.get("claims", [])]
    shown_stress = [row[0] for row in tables.rows.get("stress", [])]
    problems = []
    if shown_claims != claims:
        problems.append(f"claims table: {len(shown_claims)} rows rendered, {len(claims)} claims in "
                        "results/replication/claims.csv")
    if shown_stress != stress:
        problems.append(f"stress table: {len(shown_stress)} rows rendered, {len(stress)} cases in the summary")
    if problems:
        sys.exit("the report's landing page does not show the verdict: " + "; ".join(problems))
    headings, md_tables, md_fences = markdown_outline(Path("results/replication/docs/REPLICATION.md").read_text())
    missing = [heading for heading in headings if heading not in tables.headings]
    if missing:
        problems.append(f"{len(missing)} of its {len(headings)} headings not shown as headings: {missing}")
    if tables.anonymous_tables < md_tables:
        problems.append(f"{tables.anonymous_tables} tables rendered, {md_tables} in the document")
    if tables.pre_blocks < md_fences:
        problems.append(f"{tables.pre_blocks} code blocks rendered, {md_fences} in the document")
    if problems:
        sys.exit("the report's landing page does not show REPLICATION.md: " + "; ".join(problems))
    print(f"the report's landing page shows {len(claims)} claims and {len(stress)} stress cases, and "
          f"REPLICATION.md with its {len(headings)} headings, {md_tables} tables and {md_fences} code blocks")


if __name__ == "__main__":
    main(sys.argv[1])
