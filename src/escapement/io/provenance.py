"""Where a dataset came from: package version, git commit, time of creation."""

from __future__ import annotations

import datetime as _dt
import subprocess
from pathlib import Path

__all__ = ["git_commit", "history_line", "package_version", "provenance_attributes", "source_string"]

DOI = "10.3233/SAV-130800"
REFERENCE = (
    'J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in escapement mechanism", '
    f"Shock and Vibration 20 (2013) 1001-1010, doi:{DOI}"
)


def package_version() -> str:
    from .. import __version__

    return __version__


#: what makes the results: a difference from the commit in any of these marks a run ``+dirty``.
#: The files the workflow itself writes (README.md, REPLICATION.md, figures/) are not among them.
SOURCES = ("src", "workflow", "Snakefile", "config", "environment", "pyproject.toml")


def _top(names: tuple[str, ...]) -> list[str]:
    """Pathspecs from the top of the working tree, whatever folder git runs in."""
    return [f":(top){name}" for name in names]


def git_commit(start: Path | None = None) -> str:
    """The commit of the working tree that holds this package (``unknown`` outside git),
    with ``+dirty`` when a tracked source file (:data:`SOURCES`) differs from it."""
    where = str(start or Path(__file__).resolve().parent)
    try:
        commit = subprocess.run(
            ["git", "-C", where, "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10, check=True
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", where, "status", "--porcelain", "--untracked-files=no", "--", *_top(SOURCES)],
            capture_output=True, text=True, timeout=10, check=True,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return commit + ("+dirty" if dirty else "")


def source_string() -> str:
    return f"escapement {package_version()} (git commit {git_commit()})"


def history_line(what: str) -> str:
    now = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()
    return f"{now}: {what}"


def provenance_attributes(what: str) -> dict:
    """Where and when a file was made: ``source`` (version and commit), ``history``, ``date_created``
    (ISO 8601) and ``product_version`` (the package version)."""
    return {
        "source": source_string(),
        "history": history_line(what),
        "date_created": _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat(),
        "product_version": package_version(),
    }
