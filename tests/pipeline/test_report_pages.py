"""The HTML of the report: the landing text short and headed by the verdict's counts, the claims register and
REPLICATION.md documents of their own."""

from escapement.pipeline.docs import html_document, landing_html, markdown_html, verdict_html

WEIGHT = {"origin": "paper", "evidence": "independent", "statement": "s", "paper_value": "1", "tolerance": ""}
ROWS = [{"claim_id": f"c{i}", "source": "Eq. (1)", "finding": f"f{i}", **WEIGHT, "replicated_value": "1",
         "status": "reproduced", "note": "a < b"} for i in range(80)]
STRESS = [{"case": "c1", "regime": "r", "outcome": "completed", "check": "k", "passed": "yes", "detail": ""}]


def test_the_landing_text_is_the_headline_and_the_stress_count_without_the_tables():
    text = landing_html(ROWS, STRESS)
    assert text.startswith('<p id="headline"><strong>The verdict.</strong> Full replication: 80 of 80 findings ')
    assert "1 stress cases</strong>" in text
    assert "<table" not in text and len(text) < 2000


def test_a_document_has_its_title_escaped_and_its_body_whole():
    body = verdict_html(ROWS, STRESS)
    page = html_document("A <b> & c", body)
    assert page.startswith("<!DOCTYPE html>") and "<title>A &lt;b&gt; &amp; c</title>" in page
    assert body in page and page.rstrip().endswith("</body>\n</html>")
    assert '<meta charset="utf-8">' in html_document("t", markdown_html("# T\n"))
