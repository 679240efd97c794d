"""The last job: copy the figures and documents that git tracks from ``results/`` to their place in
the repository, only where their content changed.

The jobs before it write only under ``results/``, so an interrupted or failed run never touches a
tracked file; this job replaces a tracked file atomically, and leaves it byte-identical (only its
modification time renewed, for Snakemake) when the code did not change what it shows.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Sequence
from pathlib import Path

from ..io.atomic import atomic_path
from .logs import logged

__all__ = ["publish", "mark_stale"]


def publish(sources: Sequence[str], targets: Sequence[str], log: str) -> None:
    """Copy each of ``sources`` to the matching ``targets`` if their bytes differ."""
    with logged(log, "publish") as logger:
        for source, target in zip(sources, targets, strict=True):
            new = Path(source).read_bytes()
            path = Path(target)
            if path.is_file() and path.read_bytes() == new:
                os.utime(path)
                logger.info("%s: unchanged", target)
                continue
            with atomic_path(path) as tmp:
                shutil.copyfile(source, tmp)
            logger.info("%s: updated from %s", target, source)


def mark_stale(targets: Sequence[str]) -> None:
    """Date the tracked files back to the epoch, so that the next run publishes them again.

    Called when a run fails: Snakemake restores a tracked file that a failed job was updating with
    a new modification time, which would otherwise make it look newer than what it is copied from.
    The content is untouched, so git sees no change."""
    for target in targets:
        if Path(target).is_file():
            os.utime(target, (0, 0))
