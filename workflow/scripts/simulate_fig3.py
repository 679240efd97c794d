"""Glue: rule simulate_fig3 -> escapement.pipeline.simulate.simulate_poincare."""

from escapement.pipeline.simulate import simulate_poincare

simulate_poincare(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
