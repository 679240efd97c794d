"""Glue: rules work_precision(_full) -> escapement.pipeline.studies.run_work_precision."""

from escapement.pipeline.studies import run_work_precision

run_work_precision(snakemake.params.scene, snakemake.params.settings, snakemake.output.csv, snakemake.log[0])
