"""Glue: the plotting rules -> escapement.pipeline.plot.plot (the figure named by the output's file name)."""

from pathlib import Path

from escapement.pipeline.plot import plot

plot(
    Path(snakemake.output.png).stem,
    snakemake.wildcards.get("study", "replication"),
    list(snakemake.input),
    snakemake.params.get("labels", None),
    snakemake.output.png,
    snakemake.output.pdf,
    snakemake.log[0],
)
