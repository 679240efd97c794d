"""Glue: rule plot_long_run -> escapement.jobs.plot_long_run."""

from escapement.jobs import plot_long_run

plot_long_run(snakemake.input.nc, snakemake.output.png, snakemake.output.pdf, snakemake.log[0])  # noqa: F821
