"""Glue: the simulation rules -> escapement.pipeline.simulate (a scene's settings, or a map's chunks, to a dataset)."""

from escapement.pipeline.simulate import gather, simulate

if "parts" in snakemake.input.keys():
    gather(snakemake.params.kind, snakemake.input.parts, snakemake.input.get("timings", []), dict(snakemake.output),
           snakemake.log[0], snakemake.rule)
else:
    simulate(snakemake.params.kind, snakemake.params.scene, dict(snakemake.output), snakemake.log[0], snakemake.rule)
