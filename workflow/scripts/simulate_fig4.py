"""Glue: rule simulate_fig4 -> escapement.jobs.simulate_shock."""

from escapement.jobs import simulate_shock

simulate_shock(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
