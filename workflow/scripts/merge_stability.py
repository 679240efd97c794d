"""Glue: rule merge_stability -> escapement.pipeline.tables.merge_stability."""

from escapement.pipeline.tables import merge_stability

merge_stability(
    list(snakemake.input.chunks),  # noqa: F821
    list(snakemake.input.timings),  # noqa: F821
    snakemake.output.nc,  # noqa: F821
    snakemake.output.timing,  # noqa: F821
    snakemake.log[0],  # noqa: F821
)
