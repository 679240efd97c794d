"""Glue: rule simulate_escapement_error -> escapement.pipeline.simulate.simulate_escapement_error."""

from escapement.pipeline.simulate import simulate_escapement_error

simulate_escapement_error(
    snakemake.params.model,  # noqa: F821
    snakemake.params.forces,  # noqa: F821
    snakemake.params.zones,  # noqa: F821
    snakemake.output.nc,  # noqa: F821
    snakemake.log[0],  # noqa: F821
)
