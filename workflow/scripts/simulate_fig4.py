"""Glue: rule simulate_fig4 -> escapement.pipeline.simulate.simulate_shock."""

from escapement.pipeline.simulate import simulate_shock

simulate_shock(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
