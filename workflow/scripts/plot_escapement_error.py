"""Glue: rule plot_escapement_error -> escapement.pipeline.plot.plot_escapement_error."""

from escapement.pipeline.plot import plot_escapement_error

plot_escapement_error(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
