"""The verdict: the claims register evaluated on the replication's netCDF outputs, written as
``results/replication/claims.csv``.

:func:`check_claims` is the job of the workflow rule ``check_claims``; :func:`read_claims_csv`
reads the table back for the documents.  A check that fails makes the job fail, naming the claim
(:class:`escapement.paper.claims.ClaimError`); it never becomes a row of the table.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..io.netcdf import read_netcdf
from ..model.quantities import MODEL_KEYS
from ..paper.claims import Evidence, evaluate, load_claims
from .claims_csv import read_claims_csv, write_claims_csv
from .logs import logged
from .readings import scene_axes
from .scores import panel_candidates, read_scores

__all__ = ["FIG3_VARIABLES", "FIG4_VARIABLES", "FIG5_VARIABLES", "CHECKS_VARIABLES", "check_claims",
           "write_claims_csv", "read_claims_csv"]

#: The variables the checks read from each output; a file lacking one is named by read_netcdf.
FIG3_VARIABLES = ("cycle", "velocity_before_impact", "period", "event_time", "event_kind", "event_position",
                  "event_velocity_before", "event_velocity_after", *MODEL_KEYS, "x0")
FIG4_VARIABLES = ("t", "velocity", "acceleration", "impact_time", "velocity_before", "impulse", "energy_dissipated",
                  "velocity_window", "acceleration_window", *MODEL_KEYS, "x0")
FIG5_VARIABLES = ("t", "displacement", "velocity", "impact_time", "velocity_before_impact", "period",
                  "largest_displacement", *MODEL_KEYS)
CHECKS_VARIABLES = ("label", "group", "outcome", "outcome_message", "x0", "velocity", "period", "multiplier",
                    "multiplier_eq21", "largest_displacement", "largest_speed", "first_period", "floquet_major",
                    "floquet_minor", "cycles_to_converge", *MODEL_KEYS)


def check_claims(
    register: str, schema: str, fig3: Mapping[str, str], fig4: str, fig5: Mapping[str, str], checks: str,
    readings: str, output: str, log: str,
) -> None:
    """Evaluate the register on the outputs (``fig3`` and ``fig5`` keyed by their configured labels)
    and the score table of the candidate readings (``readings``), and write the table; raise, naming
    the claim, when a check fails."""
    with logged(log, "check_claims") as logger:
        fig3_data = {label: read_netcdf(path, FIG3_VARIABLES) for label, path in fig3.items()}
        fig4_data = read_netcdf(fig4, FIG4_VARIABLES)
        fig5_data = {label: read_netcdf(path, FIG5_VARIABLES) for label, path in fig5.items()}
        evidence = Evidence(
            fig3=fig3_data,
            fig4=fig4_data,
            fig5=fig5_data,
            checks=read_netcdf(checks, CHECKS_VARIABLES),
            axes=scene_axes(fig3_data, fig4_data, fig5_data),
            readings=panel_candidates(read_scores(readings)),
        )
        rows = evaluate(load_claims(register, schema), evidence)
        for row in rows:
            logger.info("%s: %s: %s", row["claim_id"], row["status"], row["replicated_value"])
        write_claims_csv(rows, output)

