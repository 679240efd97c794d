"""Glue: rule simulate_stability_chunk -> escapement.pipeline.simulate.simulate_stability_chunk."""

from escapement.pipeline.simulate import simulate_stability_chunk

b_values, f_values = snakemake.params.axes  # noqa: F821
simulate_stability_chunk(
    snakemake.params.model, b_values, f_values, snakemake.output.nc, snakemake.output.timing, snakemake.log[0]  # noqa: F821
)
