"""The job that writes the documents from their templates and the results: README.md and
REPLICATION.md (tracked by git: deterministic numbers only), timings.md (the measured times), and
for the report's landing page the verdict and REPLICATION.md as HTML."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ..io.netcdf import read_netcdf
from .docs import markdown_html, markdown_table, render, verdict_html, write_text
from .facts import collect_facts
from .logs import logged
from .scores import best_readings_table, read_scores
from .tables import read_stress, read_timings, read_work_precision
from .claims_csv import read_claims_csv
from .tally import findings_table, vocabulary_table

__all__ = ["render_docs"]


def render_docs(
    claims: str, benchmark: str, long_run: str, long_run_timing: str, stability: str, stability_timing: str,
    stress: str, readings: str, templates: Sequence[str], outputs: Sequence[str], measured_template: str,
    measured_output: str, verdict_output: str, replication_html_output: str, log: str,
) -> None:
    """Render each of ``templates`` to the matching ``outputs`` with deterministic facts only,
    ``measured_template`` to ``measured_output`` with the wall times too, and for the report's
    landing page the verdict as HTML to ``verdict_output`` and the output named REPLICATION.md as
    HTML to ``replication_html_output``. ``readings`` is the score table of the readings of the
    printed axes (:mod:`escapement.pipeline.readings`), summarised per panel in REPLICATION.md."""
    with logged(log, "render_docs"):
        rows = read_claims_csv(claims)
        facts = collect_facts(
            read_work_precision(benchmark),
            read_netcdf(long_run, ("cycle", "drift_exact", "drift_closed_form", "drift_ivp", "error_time_exact",
                                  "error_time_closed_form", "error_time_ivp", "closed_form_difference",
                                  "max_velocity_deviation", "max_period_deviation")),
            read_netcdf(stability, ("b", "F", "multiplier", "multiplier_eq21", "outcome")),
            read_timings(long_run_timing),
            read_timings(stability_timing),
        )
        stress_rows = read_stress(stress)
        tables = {
            "stress": markdown_table(stress_rows, ["regime", "outcome", "check", "passed", "detail"]),
            "findings": markdown_table(findings_table(rows), ["finding", "verdict", "rows"]),
            "vocabulary": markdown_table(vocabulary_table(), ["word", "meaning"]),
            "readings": markdown_table(best_readings_table(read_scores(readings)),
                                       ["figure", "panel", "printed limits", "limits reproduced",
                                        "best-supported readings"]),
        }
        documents = {}
        for template, output in zip(templates, outputs, strict=True):
            documents[Path(output).name] = render(Path(template).read_text(), rows, template, facts, tables)
            write_text(documents[Path(output).name], output)
        write_text(render(Path(measured_template).read_text(), rows, measured_template, facts, tables, measured=True),
                   measured_output)
        write_text(verdict_html(rows, stress_rows), verdict_output)
        write_text(markdown_html(documents["REPLICATION.md"]), replication_html_output)
