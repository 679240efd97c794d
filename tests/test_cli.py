"""The command line, ``python -m escapement solve``: its output, its refusals and its exit statuses."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import uuid
from pathlib import Path

import pytest

from escapement import cli
from escapement.cli import main
from escapement.io.atomic import WriteError
from escapement.io.netcdf import read_netcdf

#: the exit statuses the command documents
COMPLETED, LEFT_REGIME, INVALID_INPUT, CANNOT_WRITE = 0, 1, 2, 3


def run_process(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "escapement", *args], capture_output=True, text=True, **kwargs)


def test_help_lists_every_parameter_with_its_units():
    result = run_process("solve", "--help")
    assert result.returncode == 0
    for option, unit in (("--M", "kg"), ("--K", "N/m"), ("--F", "N"), ("--a1", "m"), ("--v0", "m/s")):
        assert option in result.stdout and unit in result.stdout
    assert "Example: python -m escapement solve" in result.stdout


def test_help_documents_four_distinct_exit_statuses():
    text = run_process("solve", "--help").stdout
    section = text[text.index("exit status:"):]
    lines = [line.split(None, 1) for line in section.splitlines()[1:] if line[:4].strip().isdigit()]
    codes = {int(code): meaning for code, meaning in lines}
    assert sorted(codes) == [COMPLETED, LEFT_REGIME, INVALID_INPUT, CANNOT_WRITE]
    assert "regime" in codes[LEFT_REGIME] and "invalid input" in codes[INVALID_INPUT]
    assert "cannot be written" in codes[CANNOT_WRITE]


def test_solve_prints_the_outcome_and_the_per_cycle_table(capsys):
    assert main(["solve", "--cycles", "3"]) == COMPLETED
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "# completed: completed 3 cycles"
    assert lines[1].split("\t") == ["cycle", "impact_time", "velocity_before_impact", "period", "amplitude"]
    assert len(lines) == 5
    # from rest at 1 m (symmetric, w = 1): v^2 before the first impact at a1 is
    # (1 - b)^2 (x0^2 - a1^2) + 2 f (a2 - a1) = 0.81 * 0.99 + 0.3
    assert float(lines[2].split("\t")[2]) == pytest.approx(math.sqrt(0.81 * 0.99 + 0.3), rel=1e-15)


def test_a_run_that_leaves_the_regime_ends_with_its_outcome(capsys):
    assert main(["solve", "--x0", "0.05", "--cycles", "3"]) == LEFT_REGIME
    assert capsys.readouterr().out.startswith("# stopped: the escapement stopped")


def test_netcdf_output_is_the_fig3_dataset(tmp_path, capsys):
    path = tmp_path / "run.nc"
    assert main(["solve", "--F", "0.5", "--x0", "3", "--cycles", "4", "--netcdf", str(path)]) == COMPLETED
    ds = read_netcdf(path, ("cycle", "velocity_before_impact", "period", "amplitude"))
    assert ds.sizes["cycle"] == 4 and ds["period"].attrs["units"] == "s"
    assert f"wrote {path}" in capsys.readouterr().out


def test_netcdf_output_replaces_an_existing_file(tmp_path, capsys):
    path = tmp_path / "run.nc"
    path.write_text("an older file")
    assert main(["solve", "--cycles", "2", "--netcdf", str(path)]) == COMPLETED
    assert read_netcdf(path, ("period",)).sizes["cycle"] == 2


def one_line_refusal(capsys, option: str, value: str) -> str:
    """The single line on standard error, which names the option and the value as typed; nothing on
    standard output."""
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith(f"python -m escapement solve: {option} {value!r} is invalid: {option} must be "), err
    return err


@pytest.fixture
def no_solving(monkeypatch):
    """Any call of the solver fails the test: the refusal must come before any work."""
    def refuse(*args, **kwargs):
        raise AssertionError("the solver ran before the refusal")
    monkeypatch.setattr(cli, "solve_exact", refuse)


def _missing(tmp_path: Path) -> str:
    return str(tmp_path / "missing" / "deeper" / "out.nc")


def _parent_is_a_file(tmp_path: Path) -> str:
    (tmp_path / "a_file").write_text("")
    return str(tmp_path / "a_file" / "out.nc")


def _name_too_long(tmp_path: Path) -> str:
    return str(tmp_path / ("x" * 240 + ".nc"))  # within 255 bytes itself; its temporary is not


@pytest.mark.parametrize("make_path", [_missing, _parent_is_a_file, _name_too_long],
                         ids=["missing directory", "parent is a file", "temporary name too long"])
def test_an_output_that_cannot_be_written_is_refused_before_solving(make_path, tmp_path, capsys, no_solving):
    path = make_path(tmp_path)
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main(["solve", "--netcdf", path]) == CANNOT_WRITE
    one_line_refusal(capsys, "--netcdf", path)
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # no directory made, no temporary left


def test_a_missing_directory_at_the_root_is_not_made(capsys, no_solving):
    root = f"/nonexistent-escapement-output-{uuid.uuid4().hex}"  # unique: other runs may share the machine
    path = f"{root}/dir/out.nc"
    assert not os.path.lexists(root)
    assert main(["solve", "--netcdf", path]) == CANNOT_WRITE
    assert "does not exist" in one_line_refusal(capsys, "--netcdf", path)
    assert not os.path.lexists(root)


@pytest.mark.skipif(os.geteuid() == 0, reason="the superuser writes in a directory without write permission")
def test_a_read_only_directory_is_refused_before_solving(tmp_path, capsys, no_solving):
    directory = tmp_path / "read_only"
    directory.mkdir()
    directory.chmod(0o555)
    try:
        assert main(["solve", "--netcdf", str(directory / "out.nc")]) == CANNOT_WRITE
    finally:
        directory.chmod(0o755)
    assert "permission denied" in one_line_refusal(capsys, "--netcdf", str(directory / "out.nc"))


def test_a_directory_no_file_can_be_made_in_is_refused_whoever_runs(capsys, no_solving):
    """/sys takes no new file, not even from the superuser, though its permissions say it does."""
    try:
        fd = os.open("/sys/escapement-probe.nc", os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except OSError:
        pass
    else:
        os.close(fd)
        os.unlink("/sys/escapement-probe.nc")
        pytest.skip("/sys takes new files here")
    assert main(["solve", "--netcdf", "/sys/out.nc"]) == CANNOT_WRITE
    one_line_refusal(capsys, "--netcdf", "/sys/out.nc")


def _fifo(tmp_path: Path) -> str:
    os.mkfifo(tmp_path / "pipe")
    return str(tmp_path / "pipe")


@pytest.mark.parametrize("make_path", [
    lambda tmp: "", lambda tmp: ".", lambda tmp: "..", lambda tmp: str(tmp), lambda tmp: str(tmp) + os.sep,
    lambda tmp: str(tmp / "new_dir") + os.sep, lambda tmp: str(tmp / "a") + "\0.nc", lambda tmp: str(tmp) + os.sep + ".",
    lambda tmp: "/dev/null", _fifo,
], ids=["empty", "dot", "dot-dot", "a directory", "a directory/", "a missing directory/", "NUL", "dir/.",
        "a device", "a named pipe"])
def test_an_output_path_that_names_no_file_is_invalid_input(make_path, tmp_path, capsys, no_solving):
    path = make_path(tmp_path)
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main(["solve", "--netcdf", path]) == INVALID_INPUT
    one_line_refusal(capsys, "--netcdf", path)
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_write_that_fails_after_the_checks_is_one_line_and_its_own_status(tmp_path, capsys, monkeypatch):
    """The disk fills between the check and the write: the writer's error, as one line, exit status 3."""
    import escapement.io.netcdf as netcdf

    def full_disk(ds, path):
        raise WriteError(28, "no space left on device (0 bytes free)", str(path))
    monkeypatch.setattr(netcdf, "write_netcdf", full_disk)
    path = str(tmp_path / "run.nc")
    assert main(["solve", "--cycles", "2", "--netcdf", path]) == CANNOT_WRITE
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"python -m escapement solve: --netcdf {path!r}: ") and "no space left" in err


@pytest.mark.parametrize("args", [
    ("--netcdf", "."), ("--netcdf", ""), ("--netcdf", f"/nonexistent-escapement-output-{uuid.uuid4().hex}/out.nc"),
    ("--cycles", "0"), ("--cycles", "1.5"), ("--b", "two"),
])
def test_a_refused_process_prints_no_traceback(args):
    result = run_process("solve", *args)
    assert result.returncode in (INVALID_INPUT, CANNOT_WRITE)
    assert result.stdout == "" and result.stderr.count("\n") == 1 and "Traceback" not in result.stderr
    assert result.stderr.startswith(f"python -m escapement solve: {args[0]} ")


@pytest.mark.parametrize("value, requirement", [
    ("0", "a positive integer"), ("-7", "a positive integer"), ("10000000000", "at most 1_000_000_000"),
    ("999999999", "at most"), ("2.5", "an integer"), ("ten", "an integer"),
])
def test_a_refused_cycle_count_is_named_by_its_option(value, requirement, capsys):
    assert main(["solve", "--cycles", value]) == INVALID_INPUT
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith("python -m escapement solve: --cycles ") and "n_cycles" not in err
    assert "--cycles must be " in err and requirement in err


@pytest.mark.parametrize("option, value, requirement", [
    ("--b", "2.5", "in the open interval (0, 2)"), ("--b", "nan", "finite"), ("--x0", "1e400", "finite"),
    ("--M", "0", "> 0"), ("--a2", "-0.5", "> a1"), ("--F", "abc", "a number"), ("--v0", "1", "0 with --netcdf"),
])
def test_an_invalid_parameter_is_refused_naming_its_option(option, value, requirement, tmp_path, capsys):
    extra = ["--netcdf", str(tmp_path / "out.nc")] if option == "--v0" else []
    assert main(["solve", option, value, *extra]) == INVALID_INPUT
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith(f"python -m escapement solve: {option} ") and f"{option} must be " in err
    assert requirement in err


def test_a_full_standard_output_is_an_io_error():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with open("/dev/full", "w") as full:
        result = subprocess.run([sys.executable, "-m", "escapement", "solve", "--cycles", "2"], stdout=full,
                                stderr=subprocess.PIPE, text=True)
    assert result.returncode == CANNOT_WRITE
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr


def test_a_closed_pipe_ends_quietly_with_the_io_status():
    process = subprocess.Popen([sys.executable, "-m", "escapement", "solve", "--cycles", "20000"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    process.stdout.readline()
    process.stdout.close()  # the reader goes, as ``| head -1`` does
    stderr = process.stderr.read().decode()
    assert process.wait(timeout=120) == CANNOT_WRITE
    assert "Traceback" not in stderr and "Exception ignored" not in stderr
