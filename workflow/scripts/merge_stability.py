"""Glue: rule merge_stability -> escapement.pipeline.jobs.merge_stability."""

from escapement.pipeline.jobs import merge_stability

merge_stability(list(snakemake.input.chunks), snakemake.output.nc, snakemake.log[0])  # noqa: F821
