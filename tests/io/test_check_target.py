"""Whether a target can be written where it is named, found before any work (:func:`check_target`)."""

from __future__ import annotations

import errno
import os

import pytest

from escapement.io.atomic import WriteError, atomic_path, check_target


def listing(directory) -> list[str]:
    return sorted(p.name for p in directory.iterdir())


def test_a_new_or_existing_file_in_an_existing_directory_passes_and_leaves_nothing(tmp_path):
    (tmp_path / "old.nc").write_text("kept")
    for name in ("new.nc", "old.nc", "no_suffix"):
        check_target(tmp_path / name)
    assert listing(tmp_path) == ["old.nc"] and (tmp_path / "old.nc").read_text() == "kept"


@pytest.mark.parametrize("relative, code", [
    ("missing/out.nc", errno.ENOENT), ("missing/deeper/out.nc", errno.ENOENT),
    ("a_file/out.nc", errno.ENOTDIR), ("a_file/sub/out.nc", errno.ENOTDIR),
    ("a_dir", errno.EISDIR), ("x" * 240 + ".nc", errno.ENAMETOOLONG), ("y" * 300, errno.ENAMETOOLONG),
])
def test_a_target_that_cannot_be_written_is_refused_naming_it_and_nothing_is_made(tmp_path, relative, code):
    (tmp_path / "a_file").write_text("")
    (tmp_path / "a_dir").mkdir()
    before = listing(tmp_path)
    with pytest.raises(WriteError) as caught:
        check_target(tmp_path / relative)
    assert caught.value.errno == code
    assert str(caught.value).startswith(f"{tmp_path / relative}: cannot write: ")
    assert listing(tmp_path) == before and listing(tmp_path / "a_dir") == []


def test_a_named_pipe_is_not_a_file_to_write(tmp_path):
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(WriteError) as caught:
        check_target(tmp_path / "pipe")
    assert caught.value.errno == errno.EINVAL and "not a regular file" in str(caught.value)


@pytest.mark.skipif(os.geteuid() == 0, reason="the superuser writes in a directory without write permission")
def test_a_directory_without_write_permission_is_refused(tmp_path):
    directory = tmp_path / "read_only"
    directory.mkdir()
    directory.chmod(0o555)
    try:
        with pytest.raises(WriteError) as caught:
            check_target(directory / "out.nc")
    finally:
        directory.chmod(0o755)
    assert caught.value.errno == errno.EACCES


def test_the_workflow_writer_still_makes_missing_directories(tmp_path):
    """The check is the command line's; the atomic writer the workflow uses makes the directories."""
    target = tmp_path / "made" / "by" / "writer.txt"
    with atomic_path(target) as tmp:
        tmp.write_text("written")
    assert target.read_text() == "written"
