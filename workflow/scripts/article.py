"""Glue: rule article -> escapement.pipeline.article.write_article."""

from escapement.pipeline.article import write_article

write_article(dict(snakemake.input), dict(snakemake.output), snakemake.log[0])
