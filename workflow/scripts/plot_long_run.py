"""Glue: rule plot_long_run -> escapement.pipeline.plot.plot_long_run."""

from escapement.pipeline.plot import plot_long_run

plot_long_run(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
