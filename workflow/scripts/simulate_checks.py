"""Glue: rule simulate_checks -> escapement.jobs.simulate_checks."""

from escapement.jobs import simulate_checks

simulate_checks(snakemake.params.cases, snakemake.params.n_cycles, snakemake.output.nc, snakemake.log[0])  # noqa: F821
