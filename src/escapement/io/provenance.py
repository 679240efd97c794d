"""Where a file came from: the package's version, the commit of the source it was made from (``+dirty`` when a
source file differs from it; in an archive, the one ``git archive`` stamped into :data:`ARCHIVE_COMMIT`), and what
wrote it.
"""

from __future__ import annotations

import datetime as _dt
import shlex
import subprocess
import sys
from pathlib import Path

__all__ = ["ARCHIVE_COMMIT", "command_line", "git_commit", "provenance_attributes"]

#: the commit of an archive, written by ``git archive`` (export-subst); as committed it is the placeholder
ARCHIVE_COMMIT = "$Format:%H$"
#: the repository's top folder, if this package is its source (src/escapement/io/provenance.py)
ROOT = Path(__file__).resolve().parents[3]
#: what makes the results: a difference from the commit in any of these marks a run ``+dirty``
SOURCES = ("src", "workflow", "Snakefile", "config", "environment", "pyproject.toml")


def _git(*args: str) -> str:
    return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True, timeout=10,
                          check=True).stdout.strip()


def git_commit(archive_commit: str = ARCHIVE_COMMIT) -> str:
    """The commit the source was made from: ``<hash> (archive)``, ``<hash>[+dirty]`` in a clone, or ``unknown``."""
    if not archive_commit.startswith("$Format"):
        return f"{archive_commit} (archive)"
    try:
        if Path(_git("rev-parse", "--show-toplevel")).resolve() != ROOT:
            return "unknown"  # this folder lies inside another repository's work tree
        commit = _git("rev-parse", "HEAD")
        dirty = _git("status", "--porcelain", "--untracked-files=no", "--", *SOURCES)
    except (OSError, subprocess.SubprocessError):  # no git program, or not a repository
        return "unknown"
    return commit + ("+dirty" if dirty else "")


def command_line() -> str:
    """The command this process runs, as typed (the program's name without its folder)."""
    return shlex.join([Path(sys.argv[0]).name, *sys.argv[1:]]) if sys.argv and sys.argv[0] else "python"


def provenance_attributes(history: str) -> dict:
    """``source`` (version and commit), ``history`` (time: what wrote the file), ``date_created`` (ISO 8601)
    and ``product_version``."""
    from .. import __version__

    now = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()
    return {"source": f"escapement {__version__} (commit {git_commit()})", "history": f"{now}: {history}",
            "date_created": now, "product_version": __version__}
