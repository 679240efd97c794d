"""The job that writes README.md and REPLICATION.md from their templates and the results."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ..io.netcdf import read_netcdf
from .docs import markdown_table, render, write_text
from .facts import collect_facts
from .logs import logged
from .tables import read_stress, read_work_precision
from .verdict import read_claims_csv

__all__ = ["render_docs"]


def render_docs(
    claims: str, benchmark: str, long_run: str, stability: str, stress: str, templates: Sequence[str],
    outputs: Sequence[str], log: str,
) -> None:
    with logged(log, "render_docs"):
        rows = read_claims_csv(claims)
        facts = collect_facts(
            read_work_precision(benchmark),
            read_netcdf(long_run, ("cycle", "drift_exact", "drift_ivp", "error_time_exact", "error_time_ivp")),
            read_netcdf(stability, ("b", "F", "multiplier", "multiplier_eq21", "outcome")),
        )
        tables = {"stress": markdown_table(read_stress(stress), ["regime", "outcome", "check", "passed", "detail"])}
        for template, output in zip(templates, outputs):
            write_text(render(Path(template).read_text(), rows, template, facts, tables), output)
