"""Glue: rule merge_stability -> escapement.jobs.merge_stability."""

from escapement.jobs import merge_stability

merge_stability(list(snakemake.input.chunks), snakemake.output.nc, snakemake.log[0])  # noqa: F821
