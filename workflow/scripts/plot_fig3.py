"""Glue: rule plot_fig3 -> escapement.pipeline.plot.plot_fig3."""

from escapement.pipeline.plot import plot_fig3

plot_fig3(  # noqa: F821
    snakemake.params.labels, list(snakemake.input.nc), snakemake.input.scores, snakemake.output.png,
    snakemake.output.pdf, snakemake.log[0],
)
