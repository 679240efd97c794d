"""Glue: rules render_docs and render_article -> escapement.pipeline.docs and escapement.pipeline.article."""

from escapement.pipeline.article import write_article
from escapement.pipeline.docs import render_docs

job = {"render_docs": render_docs, "render_article": write_article}[snakemake.rule]
job(dict(snakemake.input), dict(snakemake.output), snakemake.log[0], snakemake.params["paper"])
