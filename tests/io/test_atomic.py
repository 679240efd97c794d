import errno
import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from escapement.io import atomic
from escapement.io.atomic import WriteError, atomic_path, remove_stale_temporaries, write_csv

#: a writer that stops inside atomic_path: it prints its temporary, then waits for a line on stdin
WRITER = """
import sys
from escapement.io.atomic import atomic_path

with atomic_path(sys.argv[1]) as tmp:
    tmp.write_text("half")
    print(tmp, flush=True)
    sys.stdin.readline()
    tmp.write_text("whole")
"""


@pytest.fixture
def writers():
    """Start writers stopped in the middle of an atomic write; those still running at the end are killed."""
    started = []

    def start(target: Path) -> tuple[subprocess.Popen, Path]:
        proc = subprocess.Popen(
            [sys.executable, "-c", WRITER, str(target)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
        )
        started.append(proc)
        line = proc.stdout.readline()  # the writer's temporary, once written; empty if the writer failed
        assert line, proc.stderr.read()
        return proc, Path(line.strip())

    yield start
    for proc in started:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)


def kill_group(proc: subprocess.Popen) -> None:
    """SIGKILL the writer's process group, as a killed pipeline run would be."""
    os.killpg(proc.pid, signal.SIGKILL)


def test_success_replaces_the_target_with_umask_permissions(tmp_path):
    old = os.umask(0o022)
    try:
        with atomic_path(tmp_path / "out.txt") as tmp:
            tmp.write_text("new")
    finally:
        os.umask(old)
    assert (tmp_path / "out.txt").read_text() == "new"
    assert ((tmp_path / "out.txt").stat().st_mode & 0o777) == 0o644
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]


def test_failure_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]


def test_write_csv(tmp_path):
    write_csv([{"a": 1, "b": "x"}], ["a", "b"], tmp_path / "t.csv")
    assert (tmp_path / "t.csv").read_text() == "a,b\n1,x\n"


def test_temporary_names_its_writer_and_keeps_the_suffix_last(tmp_path):
    with atomic_path(tmp_path / "fig4.pdf") as tmp:
        name = tmp.name
        tmp.write_text("x")
    assert re.fullmatch(rf"\.fig4\.pdf\.[A-Za-z0-9-]+-{os.getpid()}\.[a-z0-9_]{{8}}\.partial\.pdf", name)
    with atomic_path(tmp_path / "Snakefile") as tmp:
        assert tmp.name.endswith(".partial.tmp")
        tmp.write_text("x")


def test_killed_writers_temporary_is_removed_by_the_next_write_of_the_target(tmp_path, writers):
    target = tmp_path / "fig4.pdf"
    target.write_text("old")
    proc, tmp = writers(target)
    kill_group(proc)
    proc.wait(timeout=30)
    assert tmp.read_text() == "half"  # a killed writer cannot remove its temporary
    assert target.read_text() == "old"
    with atomic_path(target) as new:
        new.write_text("new")
    assert target.read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig4.pdf"]


def test_killed_writers_temporary_is_removed_by_remove_stale_temporaries(tmp_path, writers):
    proc, tmp = writers(tmp_path / "sub" / "x.nc")
    kill_group(proc)
    proc.wait(timeout=30)
    assert tmp.exists()
    assert remove_stale_temporaries(tmp_path) == []  # not recursive: sub/ is not looked into
    assert tmp.exists()
    assert remove_stale_temporaries(tmp_path, recursive=True) == [tmp]
    assert not tmp.exists()
    assert remove_stale_temporaries(tmp_path / "none") == []


def test_live_writers_temporary_is_kept(tmp_path, writers):
    target = tmp_path / "t.csv"
    proc, tmp = writers(target)
    write_csv([{"a": 1}], ["a"], target)  # another write of the same target, meanwhile
    assert remove_stale_temporaries(tmp_path) == []
    assert tmp.read_text() == "half"
    proc.stdin.write("\n")
    proc.stdin.close()
    assert proc.wait(timeout=60) == 0, proc.stderr.read()
    assert target.read_text() == "whole"  # the live writer's rename still found its temporary
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.csv"]


@pytest.mark.skipif(not Path("/proc/self/stat").exists() or not hasattr(os, "waitid"),
                    reason="needs /proc to tell an ended process, and waitid to wait for it without collecting it")
def test_killed_writer_not_yet_collected_counts_as_ended(tmp_path, writers):
    proc, tmp = writers(tmp_path / "x.txt")
    kill_group(proc)
    # wait for the writer to end without collecting it (WNOWAIT): it stays a zombie, its pid taken
    ended = os.waitid(os.P_PID, proc.pid, os.WEXITED | os.WNOWAIT)
    assert (ended.si_pid, ended.si_code, ended.si_status) == (proc.pid, os.CLD_KILLED, signal.SIGKILL)
    assert Path(f"/proc/{proc.pid}/stat").read_text().rpartition(")")[2].split()[0] == "Z"
    os.kill(proc.pid, 0)  # its pid still exists until it is collected
    assert remove_stale_temporaries(tmp_path) == [tmp]
    proc.wait(timeout=30)


def test_only_temporaries_of_ended_writers_on_this_machine_are_removed(tmp_path):
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait(timeout=60)
    dead, host = proc.pid, atomic._host()
    names = {
        f".x.nc.{host}-{dead}.abcd_123.partial.nc": False,  # ended writer: removed
        f".x.nc.{host}-{os.getpid()}.abcd_123.partial.nc": True,  # live writer
        f".x.nc.{host}x-{dead}.abcd_123.partial.nc": True,  # another machine: cannot be checked
        f".x.nc.{host}-{dead}.abcd_123.partial.csv": True,  # not the target's suffix
        f".x.nc.{host}-0.abcd_123.partial.nc": True,  # pid 0 would mean the process group
        ".x.nc.abcd_123.nc": True,  # no writer named
        "x.partial.nc": True,
    }
    for name in names:
        (tmp_path / name).write_text("")
    removed = remove_stale_temporaries(tmp_path)
    assert removed == [tmp_path / name for name, kept in names.items() if not kept]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(name for name, kept in names.items() if kept)


def test_a_failure_to_read_what_is_copied_is_not_a_write_error(tmp_path):
    with pytest.raises(FileNotFoundError) as info, atomic_path(tmp_path / "copy.txt") as tmp:
        shutil.copyfile(tmp_path / "missing.txt", tmp)
    assert not isinstance(info.value, WriteError)
    assert list(tmp_path.iterdir()) == []


def test_injected_full_disk_names_the_target(tmp_path):
    with pytest.raises(WriteError) as info, atomic_path(tmp_path / "t.csv"):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    assert info.value.errno == errno.ENOSPC
    expected = rf"{re.escape(str(tmp_path / 't.csv'))}: cannot write: no space left on device \(\d+ bytes free\)"
    assert re.fullmatch(expected, str(info.value))
    assert list(tmp_path.iterdir()) == []


# -- a real file system: full, read-only ------------------------------------------------------------------------------


def _mount(point: Path, options: str) -> None:
    subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(point)], check=True, capture_output=True)


@pytest.fixture
def tmpfs(tmp_path):
    """Mount a small tmpfs with the given options (root only); unmounted at the end."""
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    mounted = []

    def mount(options: str) -> Path:
        point = tmp_path / f"mnt{len(mounted)}"
        point.mkdir()
        try:
            _mount(point, options)
        except (OSError, subprocess.CalledProcessError) as err:
            pytest.skip(f"cannot mount a tmpfs here: {err}")
        mounted.append(point)
        return point

    try:
        yield mount
    finally:
        for point in mounted:
            subprocess.run(["umount", str(point)], check=True)


def test_full_disk_names_the_csv_and_the_cause(tmpfs):
    disk = tmpfs("size=64k")
    target = disk / "big.csv"
    target.write_text("old")
    rows = [{"a": "x" * 100}] * 2000  # 200 kB
    with pytest.raises(WriteError) as info:
        write_csv(rows, ["a"], target)
    assert info.value.errno == errno.ENOSPC
    assert str(info.value).startswith(f"{target}: cannot write: no space left on device (")
    assert target.read_text() == "old"
    assert sorted(p.name for p in disk.iterdir()) == ["big.csv"]


def test_read_only_file_system_names_the_target_and_the_cause(tmpfs):
    disk = tmpfs("size=64k,ro")
    with pytest.raises(WriteError) as info:
        write_csv([{"a": 1}], ["a"], disk / "sub" / "t.csv")
    assert info.value.errno == errno.EROFS
    assert str(info.value) == f"{disk / 'sub' / 't.csv'}: cannot write: read-only file system"


def test_file_system_made_read_only_before_the_rename(tmpfs):
    disk = tmpfs("size=64k")
    target = disk / "t.txt"
    target.write_text("old")
    with pytest.raises(WriteError) as info, atomic_path(target) as tmp:
        tmp.write_text("new")
        subprocess.run(["mount", "-o", "remount,ro", str(disk)], check=True)
    assert info.value.errno == errno.EROFS
    assert str(info.value) == f"{target}: cannot write: read-only file system"
    assert any(f"the temporary {tmp} could not be removed" in note for note in info.value.__notes__)
    assert target.read_text() == "old"


#: write one CSV file, in a process of its own
WRITE_CSV = "import sys; from escapement.io.atomic import write_csv; write_csv([{'a': 1}], ['a'], sys.argv[1])"


def test_permission_denied_names_the_target(tmp_path):
    """Root ignores permission bits: as root, the write runs in a process without the capabilities that
    override them, in a directory of another user's."""
    directory = tmp_path / "locked"
    directory.mkdir()
    expected = f"{directory / 't.csv'}: cannot write: permission denied (in {directory})"
    if os.geteuid() != 0:
        directory.chmod(0o500)
        try:
            with pytest.raises(WriteError) as info:
                write_csv([{"a": 1}], ["a"], directory / "t.csv")
        finally:
            directory.chmod(0o700)
        assert info.value.errno == errno.EACCES
        assert str(info.value) == expected
        return
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        pytest.skip("needs setpriv (util-linux) to write as root without overriding permission bits")
    os.chown(directory, 65534, 65534)
    directory.chmod(0o555)
    drop = "-dac_override,-dac_read_search,-fowner"
    command = [setpriv, f"--bounding-set={drop}", sys.executable, "-c", WRITE_CSV, str(directory / "t.csv")]
    proc = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert proc.stderr.strip().splitlines()[-1] == f"escapement.io.atomic.WriteError: {expected}"
    assert list(directory.iterdir()) == []
