"""Glue: the plotting rules -> escapement.pipeline.plot.plot."""

from pathlib import Path

from escapement.pipeline.plot import plot

files = snakemake.params.get("files") or {"": path for path in snakemake.input}  # a kind of several scenes: by label
plot(
    snakemake.params.get("figure") or Path(snakemake.output.png).stem,
    snakemake.wildcards.get("study", "replication"),
    files,
    snakemake.output.png,
    snakemake.output.pdf,
    snakemake.output.svg,
    snakemake.log[0],
)
