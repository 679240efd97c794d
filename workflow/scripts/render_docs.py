"""Glue: rule render_docs -> escapement.pipeline.render.render_docs."""

from escapement.pipeline.render import render_docs

render_docs(dict(snakemake.input), dict(snakemake.output), snakemake.log[0])
