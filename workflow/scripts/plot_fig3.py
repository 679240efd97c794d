"""Glue: rule plot_fig3 -> escapement.jobs.plot_fig3."""

from escapement.jobs import plot_fig3

plot_fig3(dict(snakemake.input.items()), snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
