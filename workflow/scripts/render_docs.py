"""Glue: rule render_docs -> escapement.pipeline.render.render_docs."""

from escapement.pipeline.render import render_docs

render_docs(  # noqa: F821
    snakemake.input.claims,
    snakemake.input.benchmark,
    snakemake.input.long_run,
    snakemake.input.long_run_timing,
    snakemake.input.stability,
    snakemake.input.stability_timing,
    snakemake.input.stress,
    list(snakemake.input.templates),
    [snakemake.output.readme, snakemake.output.replication],
    snakemake.input.timings_template,
    snakemake.output.timings,
    snakemake.output.verdict,
    snakemake.log[0],
)
