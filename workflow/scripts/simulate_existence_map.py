"""Glue: rule simulate_existence_map -> escapement.pipeline.simulate.simulate_existence_map."""

from escapement.pipeline.simulate import simulate_existence_map

simulate_existence_map(snakemake.params.model, snakemake.params.block, snakemake.output.nc, snakemake.log[0])  # noqa: F821
