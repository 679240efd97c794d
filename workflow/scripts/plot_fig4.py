"""Glue: rule plot_fig4 -> escapement.pipeline.jobs.plot_fig4."""

from escapement.pipeline.jobs import plot_fig4

plot_fig4(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
