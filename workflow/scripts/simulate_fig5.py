"""Glue: rule simulate_fig5 -> escapement.pipeline.simulate.simulate_phase."""

from escapement.pipeline.simulate import simulate_phase

simulate_phase(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
