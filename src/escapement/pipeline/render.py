"""The job that writes the documents from their templates and the results: README.md and REPLICATION.md
(deterministic numbers only: the publish step compares them with the tracked ones), timings.md (the measured
times too), the HTML of the report (the verdict's headline for its landing page, and the claims register and
REPLICATION.md as documents of their own), and the ReScience C article (:mod:`escapement.pipeline.article`)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from ..io.netcdf import read_netcdf, write_text
from .article import write_article
from .docs import html_document, landing_html, markdown_html, markdown_table, render, verdict_html
from .facts import collect_facts
from .logs import logged
from ..verdict.scores import best_readings_table, read_scores
from .tables import read_claims, read_stress, read_timings, read_work_precision
from ..verdict.tally import findings_table, vocabulary_table

__all__ = ["render_docs"]


def render_docs(inputs: Mapping[str, str], outputs: Mapping[str, str], log: str) -> None:
    """Render the templates ``inputs["readme"]``, ``inputs["replication"]`` (deterministic facts) and
    ``inputs["timings"]`` (measured ones too) to the outputs of the same names, the report's landing text
    (``outputs["landing"]``, a fragment) and the claims register and REPLICATION.md as HTML documents
    (``outputs["verdict"]``, ``outputs["replication_html"]``), from the claims table, the benchmark, the long run,
    the stability map, the stress table and the readings' scores of ``inputs``; and the article
    (``outputs["article_*"]``) from them, the checks dataset, its template, bibliography and figures."""
    with logged(log, "render_docs") as logger:
        rows = read_claims(inputs["claims"])
        facts, measured = collect_facts(
            read_work_precision(inputs["benchmark"]), read_netcdf(inputs["long_run"]),
            read_netcdf(inputs["stability"]), read_timings(inputs["long_run_timing"]),
            read_timings(inputs["stability_timing"]))
        stress = read_stress(inputs["stress"])
        readings = best_readings_table(read_scores(inputs["readings"]))
        tables = {
            "stress": markdown_table(stress, ["regime", "outcome", "check", "passed", "detail"]),
            "findings": markdown_table(findings_table(rows), ["finding", "sentence", "verdict", "rows"]),
            "vocabulary": markdown_table(vocabulary_table(), ["word", "meaning"]),
            "readings": markdown_table(readings,
                                       ["figure", "panel", "printed limits", "limits reproduced",
                                        "best-supported readings"]),
        }
        for name, known in (("readme", facts), ("replication", facts), ("timings", {**facts, **measured})):
            template = inputs[name]
            text = render(Path(template).read_text(encoding="utf-8"), template, rows, known, tables)
            write_text(text, outputs[name])
            if name == "replication":
                write_text(html_document("Replication report", markdown_html(text)), outputs["replication_html"])
        write_text(landing_html(rows, stress), outputs["landing"])
        verdict = "<h1>The verdict</h1>\n" + verdict_html(rows, stress)
        write_text(html_document("The verdict", verdict), outputs["verdict"])
        title = write_article(rows, facts, readings, {**{k: v for k, v in inputs.items() if k.startswith("figure_")},
                                            "checks": inputs["checks"], "citation": inputs["citation"],
                                            "template": inputs["article"], "bibliography": inputs["bibliography"]},
                              {k.removeprefix("article_"): v for k, v in outputs.items() if k.startswith("article_")})
        logger.info("the article: %s", title)
