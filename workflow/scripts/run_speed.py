"""Glue: rule run_speed -> escapement.pipeline.studies.run_speed."""

from escapement.pipeline.studies import run_speed

run_speed(  # noqa: F821
    snakemake.params.scene,  # noqa: F821
    snakemake.params.speed,  # noqa: F821
    snakemake.output.csv,  # noqa: F821
    snakemake.output.headline,  # noqa: F821
    snakemake.log[0],  # noqa: F821
)
