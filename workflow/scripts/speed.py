"""Glue: rule speed -> escapement.pipeline.studies.run_speed, with the floors of benchmarks/floor.py."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).parents[1]))  # the repository, which holds benchmarks/

from benchmarks.floor import floor_rows  # noqa: E402

from escapement.pipeline.studies import run_speed  # noqa: E402

run_speed(
    snakemake.params.scene,
    snakemake.params.speed,
    snakemake.output.csv,
    snakemake.output.headline,
    snakemake.log[0],
    floors=floor_rows,
)
