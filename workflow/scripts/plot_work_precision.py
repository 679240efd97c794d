"""Glue: rules plot_work_precision(_full) -> escapement.pipeline.plot.plot_work_precision."""

from escapement.pipeline.plot import plot_work_precision

plot_work_precision(
    snakemake.input.csv, snakemake.output.png, snakemake.output.pdf, snakemake.log[0], snakemake.params.case  # noqa: F821
)
