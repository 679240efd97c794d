"""Glue: rule simulate_long_run -> escapement.pipeline.simulate.simulate_long_run."""

from escapement.pipeline.simulate import simulate_long_run

simulate_long_run(snakemake.params.scene, snakemake.output.nc, snakemake.output.timing, snakemake.log[0])  # noqa: F821
