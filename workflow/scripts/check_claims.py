"""Glue: rule check_claims -> escapement.pipeline.claims.check_claims."""

from escapement.pipeline.claims import check_claims

check_claims(
    snakemake.input.register,
    snakemake.params.fig3,
    snakemake.input.fig4,
    snakemake.params.fig5,
    snakemake.input.checks,
    snakemake.input.readings,
    snakemake.output.csv,
    snakemake.output.limits,
    snakemake.log[0],
    schema=snakemake.input.schema,
    settings=snakemake.params.settings,
)
