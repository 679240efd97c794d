"""The job of rule ``check_claims``: the claims register evaluated on the replication's outputs (``claims.csv``),
and the limits its axis claims judged (``panel_limits.csv``). A check that fails fails the job, naming the claim."""

from __future__ import annotations

from collections.abc import Mapping

from ..io.netcdf import read_netcdf, write_csv
from ..plotting.autoscale import VARIANTS
from ..plotting.panel_axes import scene_axes
from ..verdict.engine import SCHEMA, evaluate, load_claims
from ..verdict.evidence import Evidence
from ..verdict.rule import COLUMNS
from ..verdict.scores import CLAIM_AUTOSCALE, panel_candidates, read_scores
from .logs import logged
from .tables import LIMIT_COLUMNS

__all__ = ["check_claims"]


def check_claims(
    register: str, fig3: Mapping[str, str], fig4: str, fig5: Mapping[str, str], checks: str, readings: str,
    output: str, limits: str, log: str, schema: str = SCHEMA, settings: Mapping | None = None,
) -> None:
    """The register evaluated on the outputs (``fig3`` and ``fig5`` by label), the readings' scores and the runs of
    ``settings``' checks block, to ``output``; to ``limits``, the limits of each printed panel a claim names."""
    with logged(log, "check_claims") as logger:
        fig3_data, fig5_data = ({label: read_netcdf(path) for label, path in paths.items()} for paths in (fig3, fig5))
        fig4_data = read_netcdf(fig4)
        evidence = Evidence(fig3=fig3_data, fig4=fig4_data, fig5=fig5_data, checks=read_netcdf(checks),
                            axes=scene_axes(fig3_data, fig4_data, fig5_data, VARIANTS[CLAIM_AUTOSCALE]),
                            readings=panel_candidates(read_scores(readings)))
        claims = load_claims(register, schema, None if settings is None else [
            name for name, entry in settings["checks"].items() if isinstance(entry, Mapping)])
        panels = dict.fromkeys((claim["id"], str(r["args"]["figure"]), str(r["args"]["panel"])) for claim in claims
                               for r in claim["readings"] if {"figure", "panel"} <= set(r["args"]))
        rows = evaluate(claims, evidence)
        for row in rows:
            logger.info("%s: %s: %s", row["claim_id"], row["status"], row["replicated_value"])
        write_csv(rows, COLUMNS, output)
        write_csv([{"claim_id": claim, "figure": figure, "panel": panel, "axis": axis, "low": float(low),
                    "high": float(high)} for claim, figure, panel in panels
                   for axis, (low, high) in evidence.axes[(figure, panel)].items()], LIMIT_COLUMNS, limits)
