"""Glue: rule publish -> escapement.pipeline.publish.publish."""

from escapement.pipeline.publish import publish

publish(snakemake.params.published, snakemake.log[0])
