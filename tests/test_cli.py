"""The command line, ``escapement solve`` and ``python -m escapement solve``: its table (the names of the netCDF file
and ``to_dataframe``), its files (the command in the netCDF history), its refusals (one line before any work), its
exit statuses and its defaults (the replication's Fig. 3 (a), from config/paper.yaml)."""

from __future__ import annotations

import csv
import errno
import math
import os
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
import yaml

from escapement import cli
from escapement.io.netcdf import read_netcdf

PROG = "escapement"
COMPLETED, LEFT_REGIME, INVALID_INPUT, CANNOT_WRITE = 0, 1, 2, 3
REPO = Path(__file__).resolve().parents[1]


def main(argv: list[str]) -> int:
    return cli.main(argv, prog=PROG)


def test_the_table_prints_the_cycle_table_s_columns_by_value_and_a_run_that_leaves_the_regime_its_outcome(capsys):
    assert main(["solve", "--cycles", "3"]) == COMPLETED
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "# completed: completed 3 cycles"
    assert lines[1].split("\t") == ["cycle", "impact_time", "velocity_before_impact", "period", "largest_displacement"]
    # by default from rest at -1 m (w = 1), a free arc to the first impact at a1 = -0.1 m:
    # v^2 = x0^2 - a1^2 = 0.99, and it takes arccos(a1 / x0) = arccos(0.1) s
    first = lines[2].split("\t")
    assert float(first[2]) == pytest.approx(math.sqrt(0.99), rel=1e-15)
    assert float(first[1]) == pytest.approx(math.acos(0.1), rel=1e-15) and len(lines) == 5
    assert main(["solve", "--x0", "0.05", "--cycles", "3"]) == LEFT_REGIME
    assert capsys.readouterr().out.startswith("# stopped: the escapement stopped")


def test_any_run_it_solves_it_saves_as_netcdf_and_csv_with_the_same_names(tmp_path, capsys):
    nc, table = tmp_path / "run.nc", tmp_path / "cycles.csv"
    args = ["solve", "--M", "2", "--K", "3", "--v0", "0.5", "--cycles", "4", "--netcdf", str(nc), "--csv", str(table)]
    assert main(args) == COMPLETED
    ds = read_netcdf(nc)
    with open(table) as handle:
        rows = list(csv.DictReader(handle))
    assert list(rows[0]) == ["cycle", "impact_time", "velocity_before_impact", "period", "largest_displacement"]
    for name in list(rows[0])[1:]:
        assert [float(r[name]) for r in rows] == ds[name].values.tolist()
    assert float(ds["v0"]) == 0.5 and float(ds["M"]) == 2.0 and ds.attrs["scene"] == "run"
    assert "Fig." not in ds.attrs["title"] and ds.attrs["history"].endswith(f": {PROG} {' '.join(args)}")
    assert f"wrote {nc}, {table}" in capsys.readouterr().out


def _hostile_paths(tmp_path: Path) -> dict[str, str]:  # paths that name no file to write, made in tmp_path
    (tmp_path / "a_file").write_text("")
    (tmp_path / "a_folder").mkdir()
    (tmp_path / "loop").symlink_to("loop")
    (tmp_path / "to_a_folder").symlink_to("a_folder")
    os.mkfifo(tmp_path / "fifo")
    return {"tmp": str(tmp_path), "parent_is_a_file": str(tmp_path / "a_file" / "out.nc")}


@pytest.mark.parametrize("args, option, status, requirement", [
    *[([option, value], option, INVALID_INPUT, "") for option, value in (
        ("--M", "0"), ("--b", "2.5"), ("--a2", "-0.2"), ("--x0", "nan"), ("--cycles", "0"), ("--cycles", "1e12"),
        ("--F", "one"))],
    (["--netcdf", "{tmp}/missing/out.nc"], "--netcdf", CANNOT_WRITE, "a file in an existing directory"),
    (["--netcdf", "{tmp}/a/b/c/out.nc"], "--netcdf", CANNOT_WRITE, "a file in an existing directory"),
    (["--csv", "{parent_is_a_file}"], "--csv", CANNOT_WRITE, "a file in an existing directory"),
    (["--netcdf", "{tmp}"], "--netcdf", INVALID_INPUT, "not of a directory"),
    (["--csv", "{tmp}/to_a_folder"], "--csv", INVALID_INPUT, "not of a directory"),
    (["--csv", "{tmp}/out.csv/"], "--csv", INVALID_INPUT, "not of a directory"),
    (["--netcdf", ""], "--netcdf", INVALID_INPUT, "not empty"),
    (["--csv", "/dev/null"], "--csv", INVALID_INPUT, "not of a device, pipe or socket"),
    (["--netcdf", "{tmp}/fifo"], "--netcdf", INVALID_INPUT, "not of a device, pipe or socket"),
    (["--netcdf", "{tmp}/loop"], "--netcdf", CANNOT_WRITE, "writable (Too many levels of symbolic links)"),
    (["--netcdf", "{tmp}/" + "x" * 300], "--netcdf", CANNOT_WRITE, "writable (File name too long)"),
    # two outputs in one file, however spelt: both options and the value named
    (["--netcdf", "{tmp}/x", "--csv", "{tmp}/x"], "--csv", INVALID_INPUT, "another file than --netcdf '{tmp}/x'"),
    (["--netcdf", "{tmp}/x", "--csv", "{tmp}/./a_folder/../x"], "--csv", INVALID_INPUT,
     "another file than --netcdf '{tmp}/x': both name {tmp}/x"),
])
def test_every_bad_input_is_one_line_before_any_work(args, option, status, requirement, tmp_path, capsys,
                                                     monkeypatch):
    monkeypatch.setattr(cli, "solve_exact", lambda *a, **k: pytest.fail("the solver ran before the refusal"))
    paths = _hostile_paths(tmp_path)
    before = sorted(tmp_path.rglob("*"))
    args = [a.format(**paths) for a in args]
    assert main(["solve", *args]) == status
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"{PROG} solve: {option} ") and f"{option} must be" in err
    if requirement:  # an output: its path as typed, and what it must be
        assert err.startswith(f"{PROG} solve: {option} {args[args.index(option) + 1]!r} is invalid: {option} must be ")
        assert requirement.format(**paths) in err
    assert sorted(tmp_path.rglob("*")) == before


@pytest.mark.parametrize("patched, error", [
    ("NamedTemporaryFile", errno.EACCES),  # the check's own file: a read-only file system, or folder for all but root
    ("mkstemp", errno.ENOSPC),  # the write's own temporary file, after the check's: a full disk, once solved
])
def test_an_output_that_cannot_be_written_is_one_line_and_leaves_no_file(patched, error, tmp_path, capsys,
                                                                        monkeypatch):
    def fail(*args, **kwargs):
        raise OSError(error, os.strerror(error))

    if patched == "NamedTemporaryFile":
        monkeypatch.setattr(cli, "solve_exact", lambda *a, **k: pytest.fail("the solver ran before the refusal"))
    monkeypatch.setattr(tempfile, patched, fail)
    for option in ("--netcdf", "--csv"):
        assert main(["solve", "--cycles", "2", option, str(tmp_path / "out")]) == CANNOT_WRITE
        out, err = capsys.readouterr()
        assert out == "" and err.count("\n") == 1 and err.endswith(f"{os.strerror(error)})\n")
        assert err.startswith(f"{PROG} solve: {option} '{tmp_path}/out' is invalid: {option} must be writable (")
    assert list(tmp_path.iterdir()) == []


def test_a_read_only_folder_is_one_line_before_any_work(tmp_path, capsys, monkeypatch):
    folder = tmp_path / "read_only"
    folder.mkdir(mode=0o555)
    try:
        (folder / "probe").write_text("")
    except PermissionError:
        pass
    else:
        pytest.skip("this user writes into a read-only folder (root)")
    monkeypatch.setattr(cli, "solve_exact", lambda *a, **k: pytest.fail("the solver ran before the refusal"))
    assert main(["solve", "--netcdf", str(folder / "out.nc")]) == CANNOT_WRITE
    assert capsys.readouterr().err.endswith("--netcdf must be writable (Permission denied)\n")


def test_an_output_that_is_a_symbolic_link_is_written_through_it(tmp_path, capsys):
    (tmp_path / "data").mkdir()
    (tmp_path / "run.nc").symlink_to("data/run.nc")
    (tmp_path / "cycles.csv").symlink_to(tmp_path / "data" / "cycles.csv")
    (tmp_path / "data" / "cycles.csv").write_text("old")
    args = ["solve", "--cycles", "2", "--netcdf", str(tmp_path / "run.nc"), "--csv", str(tmp_path / "cycles.csv")]
    assert main(args) == COMPLETED
    assert (tmp_path / "run.nc").is_symlink() and (tmp_path / "cycles.csv").is_symlink()
    assert read_netcdf(tmp_path / "data" / "run.nc").sizes["cycle"] == 2
    assert (tmp_path / "data" / "cycles.csv").read_text().startswith("cycle,impact_time")
    assert sorted(p.name for p in (tmp_path / "data").iterdir()) == ["cycles.csv", "run.nc"]


def test_a_ctrl_c_during_the_write_leaves_no_file(tmp_path, monkeypatch):
    import xarray as xr

    to_netcdf = xr.Dataset.to_netcdf

    def interrupted(self, *args, **kwargs):
        signal.raise_signal(signal.SIGINT)
        return to_netcdf(self, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", interrupted)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # Python's own, whatever the runner's
    try:
        with pytest.raises(KeyboardInterrupt):
            main(["solve", "--cycles", "2", "--netcdf", str(tmp_path / "run.nc"), "--csv", str(tmp_path / "c.csv")])
    finally:
        signal.signal(signal.SIGINT, previous)
    assert list(tmp_path.iterdir()) == []


def test_the_defaults_are_the_replication_s_fig3a():
    paper = yaml.safe_load((REPO / "config/paper.yaml").read_text())
    expected = {**paper["model"], **paper["fig3"]["cases"]["a"]}
    assert {k: cli.DEFAULTS[k] for k in expected} == expected and cli.DEFAULT_CYCLES == paper["fig3"]["n_cycles"]


def test_the_module_and_the_console_script_are_one_command_with_four_documented_exit_statuses():
    module = subprocess.run([sys.executable, "-m", "escapement", "solve", "--help"], capture_output=True, text=True)
    script = subprocess.run([str(Path(sys.executable).with_name("escapement")), "--version"], capture_output=True,
                            text=True)
    assert module.returncode == 0 and "--v0 VALUE" in module.stdout and "Example: python -m escapement solve" in \
        module.stdout
    section = module.stdout[module.stdout.index("exit status:"):]
    assert [line.split()[0] for line in section.splitlines()[1:] if line[:4].strip().isdigit()] == ["0", "1", "2", "3"]
    assert script.returncode == 0 and script.stdout.startswith("escapement ")


def test_a_closed_standard_output_is_exit_status_3():
    # some 250 kB of table, more than a pipe holds: the write fails once head has gone
    result = subprocess.run(f"{sys.executable} -m escapement solve --cycles 3000 | head -c 10 > /dev/null; "
                            "echo ${PIPESTATUS[0]}", shell=True, capture_output=True, text=True, executable="/bin/bash")
    assert result.stdout.strip() == "3" and "Traceback" not in result.stderr


def test_a_standard_output_closed_from_the_start_is_one_line_and_exit_status_3():
    result = subprocess.run(f"{sys.executable} -m escapement solve >&-", shell=True, capture_output=True, text=True,
                            executable="/bin/bash")
    assert result.returncode == 3 and result.stderr.strip().splitlines() == [
        "python -m escapement: cannot write standard output: it is closed (redirect it to a file or /dev/null)"]
