"""Publishing the tracked files: copied only where their content changed."""

from __future__ import annotations

import os

from escapement.pipeline.publish import mark_stale, publish


def test_a_changed_file_is_copied_and_an_unchanged_one_keeps_its_bytes(tmp_path):
    (tmp_path / "results").mkdir()
    new_a, new_b = tmp_path / "results/a.png", tmp_path / "results/b.md"
    new_a.write_bytes(b"figure, new")
    new_b.write_bytes(b"text")
    old_a, old_b = tmp_path / "a.png", tmp_path / "b.md"
    old_a.write_bytes(b"figure, old")
    old_b.write_bytes(b"text")
    os.utime(old_b, (1, 1))
    inode = old_b.stat().st_ino
    publish([str(new_a), str(new_b)], [str(old_a), str(old_b)], str(tmp_path / "publish.log"))
    assert old_a.read_bytes() == b"figure, new"
    assert old_b.read_bytes() == b"text" and old_b.stat().st_ino == inode  # not rewritten...
    assert old_b.stat().st_mtime > 1  # ...but newer than what it is copied from, for Snakemake
    log = (tmp_path / "publish.log").read_text()
    assert f"{old_a}: updated" in log and f"{old_b}: unchanged" in log


def test_a_missing_target_is_created(tmp_path):
    source = tmp_path / "s.md"
    source.write_text("x")
    publish([str(source)], [str(tmp_path / "sub/t.md")], str(tmp_path / "log"))
    assert (tmp_path / "sub/t.md").read_text() == "x"


def test_mark_stale_dates_files_back_without_touching_their_content(tmp_path):
    path = tmp_path / "README.md"
    path.write_text("readme")
    mark_stale([str(path), str(tmp_path / "absent.md")])
    assert path.stat().st_mtime == 0 and path.read_text() == "readme"
