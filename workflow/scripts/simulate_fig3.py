"""Glue: rule simulate_fig3 -> escapement.jobs.simulate_poincare."""

from escapement.jobs import simulate_poincare

simulate_poincare(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
