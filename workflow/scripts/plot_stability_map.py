"""Glue: rule plot_stability_map -> escapement.pipeline.jobs.plot_stability_map."""

from escapement.pipeline.jobs import plot_stability_map

plot_stability_map(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
