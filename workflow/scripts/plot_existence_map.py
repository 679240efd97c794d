"""Glue: rule plot_existence_map -> escapement.pipeline.plot.plot_existence_map."""

from escapement.pipeline.plot import plot_existence_map

plot_existence_map(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
