"""Glue: rule plot_fig4 -> escapement.pipeline.plot.plot_fig4."""

from escapement.pipeline.plot import plot_fig4

plot_fig4(  # noqa: F821
    snakemake.input.nc, snakemake.input.scores, snakemake.output.png, snakemake.output.pdf, snakemake.log[0]
)
