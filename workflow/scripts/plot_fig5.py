"""Glue: rule plot_fig5 -> escapement.pipeline.jobs.plot_fig5."""

from escapement.pipeline.jobs import plot_fig5

plot_fig5(  # noqa: F821
    snakemake.params.labels, list(snakemake.input.nc), snakemake.output.png, snakemake.output.pdf, snakemake.log[0]
)
