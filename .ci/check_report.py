"""Open the Snakemake report in headless Chromium and check, in the rendered DOM, that its landing
page shows the verdict: the claims table with one visible row per claim of results/claims.csv, and
the stress table with one per row of results/stress/summary.csv.

Usage: python .ci/check_report.py results/report.html
"""

import csv
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path


class Tables(HTMLParser):
    """Rows of the tables with an id, as lists of cell texts."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: dict[str, list[list[str]]] = {}
        self._table: str | None = None
        self._row: list[str] | None = None
        self._cell: list[str] | None = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "table" and attrs.get("id"):
            self._table = attrs["id"]
            self.rows[self._table] = []
        elif tag == "tr" and self._table:
            self._row = []
        elif tag == "td" and self._row is not None:
            self._cell = []

    def handle_endtag(self, tag):
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
        if self._cell is not None:
            self._cell.append(data)


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
    with open("results/claims.csv", newline="") as handle:
        claims = [row["claim_id"] for row in csv.DictReader(handle)]
    with open("results/stress/summary.csv", newline="") as handle:
        stress = [row["regime"] for row in csv.DictReader(handle)]
    shown_claims = [row[0] for row in tables.rows.get("claims", [])]
    shown_stress = [row[0] for row in tables.rows.get("stress", [])]
    problems = []
    if shown_claims != claims:
        problems.append(f"claims table: {len(shown_claims)} rows rendered, {len(claims)} claims in results/claims.csv")
    if shown_stress != stress:
        problems.append(f"stress table: {len(shown_stress)} rows rendered, {len(stress)} cases in the summary")
    if problems:
        sys.exit("the report's landing page does not show the verdict: " + "; ".join(problems))
    print(f"the report's landing page shows {len(claims)} claims and {len(stress)} stress cases")


if __name__ == "__main__":
    main(sys.argv[1])
