"""Glue: rule run_stress -> escapement.pipeline.jobs.run_stress."""

from escapement.pipeline.jobs import run_stress

run_stress(snakemake.input.long_run, snakemake.output.csv, snakemake.log[0])  # noqa: F821
