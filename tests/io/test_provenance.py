"""Where a file came from: the commit of an archive as git archive stamps it, and of a clone as git tells it (and
only about the repository this package is the source of: a copy inside another repository's work tree is
``unknown``, never that repository's commit)."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from escapement.io import provenance
from escapement.io.provenance import git_commit, provenance_attributes

HASH = "0123456789abcdef0123456789abcdef01234567"
#: the stamp as a clone holds it (an archive holds its commit there instead, which answers before git is asked): the
#: tests of a clone pass it, so that they hold in an archive on a machine with git too
CLONE = "$Format:%H$"
needs_git = pytest.mark.skipif(shutil.which("git") is None, reason="the git program is not installed")


def git(where: Path, *args: str) -> str:
    command = ["git", "-C", str(where), "-c", "user.name=t", "-c", "user.email=t@t", *args]
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout.strip()


def test_an_archive_gives_the_commit_git_stamped_into_the_placeholder_git_archive_substitutes():
    """``.gitattributes`` names the module for export-subst, whose placeholder is ``$Format:%H$``: in a clone the
    placeholder, in an archive the commit git wrote there, given whatever git says."""
    assert git_commit(HASH) == f"{HASH} (archive)"
    text = Path(provenance.__file__).read_text()
    assert re.search(r'^ARCHIVE_COMMIT = "(\$Format:%H\$|[0-9a-f]{40})"$', text, re.M)
    attributes = (provenance.ROOT / ".gitattributes").read_text().splitlines()
    assert "src/escapement/io/provenance.py export-subst" in attributes


def test_a_clone_without_git_says_its_commit_is_unknown(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))  # no git program on PATH
    assert git_commit(CLONE) == "unknown"


@needs_git
def test_a_clone_gives_its_commit_and_dirty_when_a_source_differs(monkeypatch, tmp_path):
    root = tmp_path / "repo"
    (root / "src").mkdir(parents=True)
    (root / "src" / "a.py").write_text("x = 1\n")
    (root / "README.md").write_text("generated\n")
    git(root, "init", "-q")
    git(root, "add", ".")
    git(root, "commit", "-qm", "one")
    head = git(root, "rev-parse", "HEAD")
    monkeypatch.setattr(provenance, "ROOT", root.resolve())
    assert git_commit(CLONE) == head
    (root / "README.md").write_text("regenerated\n")  # a document the workflow writes: not a source
    assert git_commit(CLONE) == head
    (root / "src" / "a.py").write_text("x = 2\n")
    assert git_commit(CLONE) == f"{head}+dirty"


@needs_git
def test_a_copy_inside_another_repository_is_not_that_repository(monkeypatch, tmp_path):
    outer = tmp_path / "outer"
    inner = outer / "archive"
    inner.mkdir(parents=True)
    git(outer, "init", "-q")
    git(outer, "commit", "-q", "--allow-empty", "-m", "outer")
    monkeypatch.setattr(provenance, "ROOT", inner.resolve())
    assert git_commit(CLONE) == "unknown"


def test_the_attributes_name_the_version_the_commit_and_what_wrote_the_file():
    a = provenance_attributes("rule poincare_map: results/x.nc")
    assert a["source"].startswith("escapement ") and "(commit " in a["source"]
    assert a["history"] == f"{a['date_created']}: rule poincare_map: results/x.nc"
