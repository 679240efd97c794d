"""Glue: rule merge_stability -> escapement.pipeline.tables.merge_stability."""

from escapement.pipeline.tables import merge_stability

merge_stability(list(snakemake.input.chunks), snakemake.output.nc, snakemake.log[0])  # noqa: F821
