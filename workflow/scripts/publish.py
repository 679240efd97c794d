"""Glue: rule publish -> escapement.pipeline.publish.publish."""

from escapement.pipeline.publish import publish

publish(list(snakemake.input.published), list(snakemake.output.tracked), snakemake.log[0])  # noqa: F821
