"""Glue: the simulation rules -> escapement.pipeline.simulate.simulate (each scene's settings in, its dataset out)."""

from escapement.pipeline.simulate import simulate

simulate(snakemake.params.kind, snakemake.params.scene, dict(snakemake.output), snakemake.log[0], snakemake.rule)
