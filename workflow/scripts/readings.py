"""Glue: rule readings -> escapement.pipeline.readings.score_readings."""

from escapement.pipeline.readings import score_readings

score_readings(snakemake.output.csv, snakemake.log[0], snakemake.params.settings)
