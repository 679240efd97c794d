"""Glue: rule run_stress -> escapement.pipeline.studies.run_stress."""

from escapement.pipeline.studies import run_stress

run_stress(snakemake.input.long_run, snakemake.output.csv, snakemake.log[0])
