"""Provenance: the commit, marked dirty only when a source file differs from it."""

from __future__ import annotations

import subprocess

import pytest

from escapement.io.provenance import SOURCES, git_commit


def _git(where, *args):
    return subprocess.run(["git", "-C", str(where), *args], capture_output=True, text=True, check=True).stdout


@pytest.fixture
def repository(tmp_path):
    _git(tmp_path, "init", "-q")
    _git(tmp_path, "config", "user.email", "test@example.org")
    _git(tmp_path, "config", "user.name", "test")
    (tmp_path / "src/pkg").mkdir(parents=True)
    (tmp_path / "src/pkg/model.py").write_text("x = 1\n")
    (tmp_path / "figures").mkdir()
    (tmp_path / "figures/fig.png").write_bytes(b"png")
    (tmp_path / "README.md").write_text("readme\n")
    _git(tmp_path, "add", ".")
    _git(tmp_path, "commit", "-q", "-m", "first")
    return tmp_path


def test_a_clean_tree_gives_the_bare_commit(repository):
    head = _git(repository, "rev-parse", "HEAD").strip()
    assert git_commit(repository / "src/pkg") == head


def test_documents_and_figures_the_workflow_writes_do_not_make_it_dirty(repository):
    (repository / "README.md").write_text("regenerated\n")
    (repository / "figures/fig.png").write_bytes(b"other png")
    assert not git_commit(repository / "src/pkg").endswith("+dirty")


def test_an_edited_source_file_makes_it_dirty_from_any_folder(repository):
    (repository / "src/pkg/model.py").write_text("x = 2\n")
    for start in (repository, repository / "src/pkg", repository / "figures"):
        assert git_commit(start).endswith("+dirty")


def test_the_sources_are_the_inputs_of_the_workflow():
    assert {"src", "workflow", "config", "Snakefile"} <= set(SOURCES)
    assert not {"README.md", "REPLICATION.md", "figures"} & set(SOURCES)
