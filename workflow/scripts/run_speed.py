"""Glue: rule run_speed -> escapement.pipeline.studies.run_speed, with the floors of benchmarks/floor.py."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).parents[1]))  # noqa: F821  the repository, which holds benchmarks/

from benchmarks.floor import floor_rows  # noqa: E402

from escapement.pipeline.studies import run_speed  # noqa: E402

run_speed(  # noqa: F821
    snakemake.params.scene,  # noqa: F821
    snakemake.params.speed,  # noqa: F821
    snakemake.output.csv,  # noqa: F821
    snakemake.output.headline,  # noqa: F821
    snakemake.log[0],  # noqa: F821
    floors=floor_rows,
)
