"""The verdict: the claims register evaluated on the replication's netCDF outputs, written as
``results/replication/claims.csv``.

:func:`check_claims` is the job of the workflow rule ``check_claims``; the documents read the table back
(:func:`escapement.pipeline.tables.read_claims`).  A check that fails makes the job fail, naming the claim
(:class:`escapement.verdict.engine.ClaimError`); it never becomes a row of the table.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..io.netcdf import read_netcdf, write_csv
from ..plotting.autoscale import VARIANTS
from ..plotting.panel_axes import scene_axes
from ..verdict.engine import COLUMNS, SCHEMA, evaluate, load_claims
from ..verdict.evidence import Evidence
from .logs import logged
from ..verdict.scores import CLAIM_AUTOSCALE, panel_candidates, read_scores

__all__ = ["check_claims"]


def check_claims(
    register: str, fig3: Mapping[str, str], fig4: str, fig5: Mapping[str, str], checks: str, readings: str,
    output: str, log: str, schema: str = SCHEMA, settings: Mapping | None = None,
) -> None:
    """Evaluate the register on the outputs (``fig3`` and ``fig5`` keyed by their configured labels)
    and the score table of the candidate readings (``readings``), the runs the register names taken from
    ``settings`` (the configuration's ``model`` and ``checks`` blocks), and write the table; raise, naming
    the claim, when a check fails (a variable an output lacks among the causes)."""
    with logged(log, "check_claims") as logger:
        fig3_data = {label: read_netcdf(path) for label, path in fig3.items()}
        fig4_data = read_netcdf(fig4)
        fig5_data = {label: read_netcdf(path) for label, path in fig5.items()}
        evidence = Evidence(
            fig3=fig3_data,
            fig4=fig4_data,
            fig5=fig5_data,
            checks=read_netcdf(checks),
            axes=scene_axes(fig3_data, fig4_data, fig5_data, VARIANTS[CLAIM_AUTOSCALE]),
            readings=panel_candidates(read_scores(readings)),
        )
        rows = evaluate(load_claims(register, schema, settings), evidence)
        for row in rows:
            logger.info("%s: %s: %s", row["claim_id"], row["status"], row["replicated_value"])
        write_csv(rows, COLUMNS, output)

