"""Glue: rule render_docs -> escapement.pipeline.render.render_docs."""

from escapement.pipeline.render import render_docs

render_docs(  # noqa: F821
    claims=snakemake.input.claims,
    benchmark=snakemake.input.benchmark,
    long_run=snakemake.input.long_run,
    long_run_timing=snakemake.input.long_run_timing,
    stability=snakemake.input.stability,
    stability_timing=snakemake.input.stability_timing,
    stress=snakemake.input.stress,
    readings=snakemake.input.readings,
    templates=list(snakemake.input.templates),
    outputs=[snakemake.output.readme, snakemake.output.replication],
    measured_template=snakemake.input.timings_template,
    measured_output=snakemake.output.timings,
    verdict_output=snakemake.output.verdict,
    replication_html_output=snakemake.output.replication_html,
    log=snakemake.log[0],
)
