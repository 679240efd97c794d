"""Glue: rule stability_map -> escapement.pipeline.tables.merge_stability."""

from escapement.pipeline.tables import merge_stability

merge_stability(list(snakemake.input.chunks), snakemake.output.nc, snakemake.output.timing, snakemake.log[0])
