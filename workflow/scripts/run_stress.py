"""Glue: rule run_stress -> escapement.jobs.run_stress."""

from escapement.jobs import run_stress

run_stress(snakemake.input.long_run, snakemake.output.csv, snakemake.log[0])  # noqa: F821
