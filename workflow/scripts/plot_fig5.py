"""Glue: rule plot_fig5 -> escapement.pipeline.plot.plot_fig5."""

from escapement.pipeline.plot import plot_fig5

plot_fig5(  # noqa: F821
    snakemake.params.labels, list(snakemake.input.nc), snakemake.input.scores, snakemake.output.png,
    snakemake.output.pdf, snakemake.log[0],
)
