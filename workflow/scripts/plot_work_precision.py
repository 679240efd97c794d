"""Glue: rules plot_work_precision(_full) -> escapement.pipeline.jobs.plot_work_precision."""

from escapement.pipeline.jobs import plot_work_precision

plot_work_precision(snakemake.input.csv, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
