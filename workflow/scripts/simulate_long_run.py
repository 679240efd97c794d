"""Glue: rule simulate_long_run -> escapement.pipeline.jobs.simulate_long_run."""

from escapement.pipeline.jobs import simulate_long_run

simulate_long_run(snakemake.params.scene, snakemake.output.nc, snakemake.log[0])  # noqa: F821
