#!/usr/bin/env bash
# Snakemake runs this inside the conda environment of environment.yml once it has created it, from
# its working directory (the clone's root): it installs the package itself, editable, with the
# pinned setuptools that environment.yml already holds and without dependencies (environment.yml
# holds them all, hash-checked), so nothing is fetched unchecked.
set -euo pipefail
python -m pip install --no-deps --no-build-isolation --editable .
