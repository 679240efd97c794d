"""Glue: rule simulate_checks -> escapement.pipeline.simulate.simulate_checks."""

from escapement.pipeline.simulate import simulate_checks

simulate_checks(snakemake.params.cases, snakemake.params.n_cycles, snakemake.output.nc, snakemake.log[0])  # noqa: F821
