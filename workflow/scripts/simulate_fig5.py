"""Glue: rule simulate_fig5 -> escapement.pipeline.jobs.simulate_phase."""

from escapement.pipeline.jobs import simulate_phase

simulate_phase(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
