"""The generated README.md and REPLICATION.md must equal the committed ones, measured values masked."""

import subprocess
import sys
from pathlib import Path

from escapement.pipeline.facts import mask_measured

stale = []
for name in ("README.md", "REPLICATION.md"):
    committed = subprocess.run(["git", "show", f"HEAD:{name}"], capture_output=True, text=True, check=True).stdout
    if mask_measured(committed) != mask_measured(Path(name).read_text()):
        stale.append(name)
if stale:
    sys.exit(f"stale: {', '.join(stale)} (rerun snakemake and commit them)")
print("README.md and REPLICATION.md match the workflow's output")
