"""Glue: rule plot_stability_map -> escapement.pipeline.plot.plot_stability_map."""

from escapement.pipeline.plot import plot_stability_map

plot_stability_map(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
