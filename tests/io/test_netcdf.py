"""netCDF files as written and read: compressed, checksummed, renamed into place, refused by name when damaged;
written through symbolic links; a Ctrl-C during a write ends it at once without a file, and the partial files of a
killed write are removed by the next write of their target."""

import hashlib
import os
import signal
import subprocess
import sys
import threading
import time

import netCDF4
import numpy as np
import pytest
import xarray as xr

from escapement.io.netcdf import (DatasetError, read_netcdf, stale_partials, writable_target, write_csv,
                                  write_netcdf, write_text)


def small_dataset():
    return xr.Dataset({"v": ("t", np.arange(5.0), {"units": "m s-1", "long_name": "velocity"})},
                      coords={"t": ("t", np.linspace(0, 1, 5), {"units": "s", "long_name": "time"})},
                      attrs={"title": "test"})


def test_round_trip_compressed_checksummed_without_fill_value_on_coordinates_and_as_the_umask_says(tmp_path):
    old = os.umask(0o022)
    try:
        path = write_netcdf(small_dataset(), tmp_path / "x.nc", history="a test")
    finally:
        os.umask(old)
    assert (path.stat().st_mode & 0o777) == 0o644
    with netCDF4.Dataset(path) as nc:
        assert "_FillValue" not in nc["t"].ncattrs() and nc["v"].filters()["zlib"] is True
        assert {name: nc[name].filters()["fletcher32"] for name in ("v", "t")} == {"v": True, "t": True}
    back = read_netcdf(path, required=("v", "t"))
    assert back["v"].values.tolist() == [0, 1, 2, 3, 4]
    assert back.attrs["title"] == "test" and back.attrs["history"].endswith(": a test")


def test_a_write_that_fails_leaves_nothing_and_names_the_file(tmp_path, monkeypatch):
    bad = small_dataset()
    bad.attrs["bad"] = {"a dict": "cannot be an attribute"}
    with pytest.raises(Exception):
        write_netcdf(bad, tmp_path / "x.nc")

    def fail(*args, **kwargs):
        raise RuntimeError("NetCDF: Not a valid data type or _FillValue type mismatch")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", fail)
    with pytest.raises(DatasetError, match=r"x\.nc: cannot write the netCDF file \(RuntimeError: NetCDF: Not a valid"):
        write_netcdf(small_dataset(), tmp_path / "x.nc")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("damage, message", [
    (lambda path: path.write_bytes(path.read_bytes()[: path.stat().st_size // 3]), r"x\.nc: damaged \(OSError"),
    (lambda path: path.write_text("this is not netCDF"), r"x\.nc: damaged \(OSError: NetCDF: Unknown file format"),
    (lambda path: path.unlink(), r"x\.nc: no such netCDF file"),
    (lambda path: None, r"x\.nc: lacks the variable\(s\) w"),
], ids=["truncated", "garbage", "missing", "a variable missing"])
def test_a_damaged_or_missing_file_or_variable_is_named_in_the_error(tmp_path, damage, message):
    path = write_netcdf(small_dataset(), tmp_path / "x.nc")
    damage(path)
    with pytest.raises(DatasetError, match=message):
        read_netcdf(path, required=("v", "w"))


def flip_bit(path, pattern: bytes) -> None:
    """Flip one bit of ``path`` inside the only occurrence of ``pattern``."""
    data = bytearray(path.read_bytes())
    assert data.count(pattern) == 1
    data[data.find(pattern) + 10] ^= 0x04
    path.write_bytes(data)


def test_a_flipped_bit_fails_the_checksum_of_an_uncompressed_or_a_compressed_variable(tmp_path):
    """Random bytes do not compress: zlib stores them as they come from the shuffle filter (byte k of every value,
    then byte k + 1), where they can be found (zlib's own check would catch that flip too)."""
    times = np.array([1.2345678901234e10 + i for i in range(5)])  # found in the file by their bytes
    values = np.random.default_rng(1).integers(-(2**62), 2**62, size=512, dtype=np.int64)
    shuffled = np.frombuffer(values.tobytes(), np.uint8).reshape(-1, 8).T.tobytes()[2000:2064]
    for ds, pattern in ((xr.Dataset({"v": ("t", np.arange(5.0))}, coords={"t": ("t", times)}), times.tobytes()),
                        (xr.Dataset({"v": ("n", values)}), shuffled)):
        flip_bit(path := write_netcdf(ds, tmp_path / "x.nc"), pattern)
        with pytest.raises(DatasetError, match=r"x\.nc: damaged \(RuntimeError: NetCDF: HDF error"):
            read_netcdf(path)
    with netCDF4.Dataset(write_netcdf(ds, tmp_path / "x.nc")) as nc:
        assert nc["v"].filters()["zlib"] and nc["v"].filters()["shuffle"]
    # The uncompressed file without the checksum: the flipped bit is read back as data.
    bare = tmp_path / "bare.nc"
    xr.Dataset({"v": ("t", np.arange(5.0))}, coords={"t": ("t", times)}).to_netcdf(
        bare, engine="netcdf4", encoding={"t": {"_FillValue": None}})
    flip_bit(bare, times.tobytes())
    with xr.open_dataset(bare, engine="netcdf4") as back:
        assert (back["t"].values != times).tolist() == [False, True, False, False, False]


#: a process that writes ``sys.argv[1]`` for about half a second (random numbers do not compress)
SLOW_WRITE = """
import sys, numpy as np, xarray as xr
from escapement.io.netcdf import write_netcdf
values = np.random.default_rng(0).random((3, 1_000_000))
write_netcdf(xr.Dataset({f"v{i}": ("n", row) for i, row in enumerate(values)}), sys.argv[1], history="a slow write")
"""


def test_a_ctrl_c_during_a_write_ends_the_process_within_seconds_and_leaves_no_file(tmp_path):
    target = tmp_path / "x.nc"
    proc = subprocess.Popen([sys.executable, "-c", SLOW_WRITE, str(target)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not stale_partials(target):  # the write has begun once its temporary file exists
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.01)
    time.sleep(0.1)  # inside the netCDF library's write
    proc.send_signal(signal.SIGINT)
    sent = time.monotonic()
    try:
        _, err = proc.communicate(timeout=15)
    except subprocess.TimeoutExpired:  # the hang: xarray waits for the lock the interrupt left held
        proc.kill()
        proc.communicate()
        pytest.fail("the process did not end within 15 s of a Ctrl-C")
    assert time.monotonic() - sent < 10
    assert proc.returncode == -signal.SIGINT and err.rstrip().endswith("KeyboardInterrupt")
    assert list(tmp_path.iterdir()) == []


def test_a_ctrl_c_inside_the_write_is_raised_once_it_returns_and_nothing_is_left(tmp_path, monkeypatch):
    to_netcdf, finished = xr.Dataset.to_netcdf, []

    def interrupted(self, *args, **kwargs):
        signal.raise_signal(signal.SIGINT)  # as a Ctrl-C while the netCDF library writes
        result = to_netcdf(self, *args, **kwargs)
        finished.append(True)  # reached only if the interrupt waits for the write
        return result

    monkeypatch.setattr(xr.Dataset, "to_netcdf", interrupted)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # Python's own, whatever the runner's
    try:
        with pytest.raises(KeyboardInterrupt):
            write_netcdf(small_dataset(), tmp_path / "x.nc")
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # put back
    finally:
        signal.signal(signal.SIGINT, previous)
    assert finished == [True] and list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    # outside the main thread, which alone receives signals, a write leaves the signals alone
    done = []
    worker = threading.Thread(target=lambda: done.append(write_netcdf(small_dataset(), tmp_path / "x.nc")))
    worker.start()
    worker.join(timeout=60)
    assert done == [tmp_path / "x.nc"] and read_netcdf(tmp_path / "x.nc")["v"].values.tolist() == [0, 1, 2, 3, 4]


def test_a_ctrl_c_during_a_read_is_not_lost(tmp_path):
    """netCDF4 loses an interrupt that comes while it reads: the reads would go on to the end of the loop."""
    path = write_netcdf(xr.Dataset({"v": ("n", np.random.default_rng(0).random(1_000_000))}), tmp_path / "x.nc")
    read_netcdf(path)
    timer = threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT))  # a Ctrl-C, most likely inside a read
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # Python's own, whatever the runner's
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            for _ in range(400):
                read_netcdf(path)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)


#: a process killed inside a write of ``sys.argv[1]``: its temporary file stays
KILLED_WRITE = """
import os, signal, sys
from escapement.io.netcdf import replaced
with replaced(sys.argv[1]) as tmp:
    tmp.write_text("half a file")
    os.kill(os.getpid(), signal.SIGKILL)
"""


def test_a_killed_write_leaves_a_partial_file_that_the_next_write_of_its_target_alone_removes(tmp_path):
    proc = subprocess.run([sys.executable, "-c", KILLED_WRITE, str(tmp_path / "x.nc")])
    assert proc.returncode == -signal.SIGKILL
    (left,) = stale_partials(tmp_path / "x.nc")
    assert left.name.startswith(".x.nc.") and left.name.endswith(".partial")
    own = [left.name, ".x.nc.z_9.partial"]
    others = [".y.nc.abcd1234.partial",  # another target's
              ".x.nc.gz.abcd1234.partial",  # the target x.nc.gz's
              ".x.nc.abcd1234.partial.kept", "x.nc.abcd1234.partial", ".x.nc.partial", "sub/.x.nc.abcd1234.partial"]
    for name in own[1:] + others:
        (tmp_path / name).parent.mkdir(exist_ok=True)
        (tmp_path / name).write_text("left by a killed write")
    assert [p.name for p in stale_partials(tmp_path / "x.nc")] == sorted(own)
    write_netcdf(small_dataset(), tmp_path / "x.nc")
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file()) == \
        sorted(["x.nc", *others])


def test_a_symbolic_link_is_written_through_and_stays(tmp_path):
    (tmp_path / "data").mkdir()
    link, target = tmp_path / "x.nc", tmp_path / "data" / "x.nc"
    link.symlink_to("data/x.nc")  # dangling until the first write
    for _ in range(2):  # made, then replaced
        write_netcdf(small_dataset(), link)
        assert link.is_symlink() and os.readlink(link) == "data/x.nc" and read_netcdf(target)["v"].size == 5
    write_text("a line\n", tmp_path / "t.txt")
    (tmp_path / "t_link.txt").symlink_to(tmp_path / "t.txt")
    write_csv([{"a": 1}], ["a"], tmp_path / "t_link.txt")
    assert (tmp_path / "t_link.txt").is_symlink() and (tmp_path / "t.txt").read_text() == \
        "# rows: 1; sha256: " + hashlib.sha256(b"a\n1\n").hexdigest() + "\na\n1\n"
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["data", "t.txt", "t_link.txt", "x.nc", "x.nc"]


@pytest.mark.parametrize("write, name, error, words", [
    (lambda path: write_netcdf(small_dataset(), path), "folder", IsADirectoryError, "Is a directory"),
    (lambda path: write_text("x", path), "fifo", FileExistsError, "not a regular file"),
    (lambda path: write_text("x", path), "loop", OSError, "Too many levels of symbolic links"),
    (writable_target, "missing/x.nc", FileNotFoundError, "No such file or directory"),
    (writable_target, "a_file/x.nc", NotADirectoryError, "Not a directory"),
    (writable_target, "x" * 250, OSError, "File name too long"),  # its temporary file's name would be too long
])
def test_a_target_where_no_file_can_be_written_is_refused_before_any_work(tmp_path, write, name, error, words):
    (tmp_path / "folder").mkdir()
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "loop").symlink_to("loop")
    (tmp_path / "a_file").write_text("")
    with pytest.raises(error, match=words):
        write(tmp_path / name)
    assert writable_target(tmp_path / "x.nc") == tmp_path / "x.nc"  # tried with a temporary file, then removed
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", "fifo", "folder", "loop"]
