"""Glue: rule render_docs -> escapement.jobs.render_docs."""

from escapement.jobs import render_docs

render_docs(  # noqa: F821
    snakemake.input.claims,
    list(snakemake.input.templates),
    [snakemake.output.readme, snakemake.output.replication],
    snakemake.log[0],
)
