"""Glue: rule check_claims -> escapement.pipeline.verdict.check_claims."""

from escapement.pipeline.verdict import check_claims

check_claims(
    snakemake.input.register,
    dict(zip(snakemake.params.fig3_labels, snakemake.input.fig3)),
    snakemake.input.fig4,
    dict(zip(snakemake.params.fig5_labels, snakemake.input.fig5)),
    snakemake.input.checks,
    snakemake.input.readings,
    snakemake.output.csv,
    snakemake.log[0],
    schema=snakemake.input.schema,
)
