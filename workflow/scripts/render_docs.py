"""Glue: rule render_docs -> escapement.pipeline.render.render_docs."""

from escapement.pipeline.render import render_docs

render_docs(  # noqa: F821
    snakemake.input.claims,
    snakemake.input.benchmark,
    snakemake.input.long_run,
    snakemake.input.stability,
    snakemake.input.stress,
    list(snakemake.input.templates),
    [snakemake.output.readme, snakemake.output.replication],
    snakemake.log[0],
)
