"""Check what a reader of the Snakemake report sees, in a window of 1280 x 800 pixels.

The landing page, drawn by headless Chromium at scroll 0: the verdict's headline (the paragraph with the id
``headline``) whole in the viewport (the window less the browser's bars: 1280 x 713 pixels) and not covered, saying
what the headline of results/replication/claims.csv says.
The category Verdict, each item the document the report shows in a frame (the HTML its data URI holds, without
scripts, so its markup is what the frame draws): the claims register (results/replication/docs/verdict.html) with
one row per claim of results/replication/claims.csv and one per stress case of results/replication/stress.csv;
REPLICATION.md (results/replication/docs/replication.html) with every heading of
results/replication/docs/REPLICATION.md as a heading, each of its tables as a table and each fenced code block as
a <pre> block. The text of scripts and hidden elements does not count.

Usage: python .ci/check_report.py results/report.html
"""

import base64
import json
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path

from escapement.io.netcdf import read_csv
from escapement.pipeline.tables import STRESS_COLUMNS, read_claims
from escapement.verdict.tally import headline

WINDOW = (1280, 800)
HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
FENCE = re.compile(r"^(```|~~~)")
TABLE_RULE = re.compile(r"^\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)+\|?\s*$")
NOT_SHOWN = {"script", "style", "template", "noscript"}
ITEMS = {"verdict": "results/replication/docs/verdict.html", "replication": "results/replication/docs/replication.html"}
# Run in the landing page once it has drawn: where the headline is, whether it is what a reader sees at its first
# line (no other element over it) and visible, and its text; written to the title, which the dumped DOM keeps.
PROBE = """<script>
addEventListener("load", () => setTimeout(() => {
  const headline = document.getElementById("headline");
  const box = headline && headline.getBoundingClientRect();
  const hit = box && document.elementFromPoint(box.left + 2, box.top + 2);
  document.title = JSON.stringify({width: innerWidth, height: innerHeight, box: box,
    seen: Boolean(hit && headline.contains(hit) && headline.checkVisibility({opacityProperty: true})),
    text: headline && headline.innerText});
}, 2000));
</script>
"""


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
    of tables without an id and of <pre> blocks; all outside scripts and hidden elements; and the title."""

    def __init__(self) -> None:
        super().__init__()
        self.title = ""
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
        if tag == "title":
            self._heading = []
        elif re.fullmatch(r"h[1-6]", tag):
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
        if tag == "title" and self._heading is not None:
            self.title = "".join(self._heading)
            self._heading = None
        elif re.fullmatch(r"h[1-6]", tag) and self._heading is not None:
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


def landing(browser: str, report: str) -> dict:
    """What the probe finds on the landing page, drawn by headless Chromium in the window."""
    with tempfile.TemporaryDirectory() as scratch:
        page = Path(scratch, "report.html")
        page.write_text(report + PROBE, encoding="utf-8")
        dom = subprocess.run(
            [browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--window-size=%d,%d" % WINDOW, "--virtual-time-budget=10000", "--dump-dom", page.as_uri()],
            capture_output=True, text=True, timeout=300, check=True,
        ).stdout
    shown = Tables()
    shown.feed(dom)
    if not shown.title.startswith("{"):
        sys.exit("the report's landing page did not finish drawing (its probe found nothing)")
    return json.loads(shown.title)


def item(results: dict, path: str) -> Tables:
    """The document the report shows in a frame for the item ``path``: the HTML its data URI holds, which has no
    scripts, so its markup is what the frame draws."""
    if results[path]["mime_type"] != "text/html":
        sys.exit(f"the report offers {path} as a download ({results[path]['mime_type']}), not as a page")
    shown = Tables()
    shown.feed(base64.b64decode(results[path]["data_uri"].split(",", 1)[1]).decode("utf-8"))
    return shown


def report_data(report: str, name: str) -> dict:
    """The JSON the report embeds as the script variable ``name``."""
    return json.loads(re.search(rf'<script id="{name}">\s*var {name} = (.*);$', report, re.M).group(1))


def landing_problems(probe: dict, claims: list[dict]) -> list[str]:
    box, problems = probe["box"], []
    if box is None:
        return ["no element with the id headline"]
    if not (0 <= box["top"] <= box["bottom"] <= probe["height"] and 0 <= box["left"] <= box["right"] <= probe["width"]):
        problems.append("the headline is not whole in the {width} x {height} viewport at scroll 0: ".format(**probe)
                        + "top {top:.0f}, bottom {bottom:.0f}, left {left:.0f}, right {right:.0f} px".format(**box))
    if not probe["seen"]:
        problems.append("the headline is hidden or covered by another element")
    if normalised(headline(claims)) not in normalised(probe["text"]):
        problems.append(f"the headline is not the claims' headline: {probe['text']!r}")
    return problems


def main(path: str) -> None:
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        sys.exit("chromium is not installed (Debian package: chromium)")
    report = Path(path).read_text(encoding="utf-8")
    results, categories = report_data(report, "results"), report_data(report, "categories")
    verdict_items = {entry for subcategory in categories.get("Verdict", {}).values() for entry in subcategory}
    missing = [entry for entry in ITEMS.values() if entry not in verdict_items]
    if missing:
        sys.exit(f"the report's category Verdict lacks {missing}")
    probe = landing(browser, report)
    claims = read_claims("results/replication/claims.csv")
    problems = landing_problems(probe, claims)
    if problems:
        sys.exit("the report's landing page does not show the verdict: " + "; ".join(problems))
    stress = [row["regime"] for row in read_csv("results/replication/stress.csv", STRESS_COLUMNS)]
    register = item(results, ITEMS["verdict"])
    shown_claims = [row[0] for row in register.rows.get("claims", [])]
    shown_stress = [row[0] for row in register.rows.get("stress", [])]
    if shown_claims != [row["claim_id"] for row in claims]:
        problems.append(f"claims table: {len(shown_claims)} rows rendered, {len(claims)} claims in "
                        "results/replication/claims.csv")
    if shown_stress != stress:
        problems.append(f"stress table: {len(shown_stress)} rows rendered, {len(stress)} cases in the summary")
    if problems:
        sys.exit("the report's claims register does not show the verdict: " + "; ".join(problems))
    headings, md_tables, md_fences = markdown_outline(Path("results/replication/docs/REPLICATION.md").read_text())
    document = item(results, ITEMS["replication"])
    missing = [heading for heading in headings if heading not in document.headings]
    if missing:
        problems.append(f"{len(missing)} of its {len(headings)} headings not shown as headings: {missing}")
    if document.anonymous_tables < md_tables:
        problems.append(f"{document.anonymous_tables} tables rendered, {md_tables} in the document")
    if document.pre_blocks < md_fences:
        problems.append(f"{document.pre_blocks} code blocks rendered, {md_fences} in the document")
    if problems:
        sys.exit("the report does not show REPLICATION.md: " + "; ".join(problems))
    print(f"the report's landing page shows the verdict's headline {probe['box']['top']:.0f} px below the top of the "
          f"{probe['width']} x {probe['height']} viewport; its "
          f"claims register {len(claims)} claims and {len(stress)} stress cases; REPLICATION.md its "
          f"{len(headings)} headings, {md_tables} tables and {md_fences} code blocks")


if __name__ == "__main__":
    main(sys.argv[1])
