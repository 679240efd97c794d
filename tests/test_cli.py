"""The command line, ``escapement solve`` and ``python -m escapement solve``: its output, its refusals, its
exit statuses, its defaults (the workflow's Fig. 3 (a)) and the console script the install makes."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import uuid
from pathlib import Path

import pytest

from escapement import cli
from escapement.io.atomic import WriteError
from escapement.io.netcdf import read_netcdf

#: the program's name in the messages of the in-process runs below
PROG = "escapement"


def main(argv: list[str]) -> int:
    """The command line run in this process, named as the console script names it."""
    return cli.main(argv, prog=PROG)

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
    assert lines[1].split("\t") == ["cycle", "impact_time", "velocity_before_impact", "period", "largest_displacement"]
    assert len(lines) == 5
    # by default from rest at -1 m (w = 1), a free arc to the first impact at a1 = -0.1 m:
    # v^2 = x0^2 - a1^2 = 0.99, and it takes arccos(a1 / x0) = arccos(0.1) s
    assert float(lines[2].split("\t")[2]) == pytest.approx(math.sqrt(0.99), rel=1e-15)
    assert float(lines[2].split("\t")[1]) == pytest.approx(math.acos(0.1), rel=1e-15)


def test_a_release_on_the_right_passes_both_impacts_before_the_first_cycle(capsys):
    assert main(["solve", "--x0", "1", "--cycles", "3"]) == COMPLETED
    lines = capsys.readouterr().out.splitlines()
    # from rest at 1 m (symmetric, w = 1): v^2 before the first impact at a1 is
    # (1 - b)^2 (x0^2 - a1^2) + 2 f (a2 - a1) = 0.81 * 0.99 + 0.3
    assert float(lines[2].split("\t")[2]) == pytest.approx(math.sqrt(0.81 * 0.99 + 0.3), rel=1e-15)


def test_a_run_that_leaves_the_regime_ends_with_its_outcome(capsys):
    assert main(["solve", "--x0", "0.05", "--cycles", "3"]) == LEFT_REGIME
    assert capsys.readouterr().out.startswith("# stopped: the escapement stopped")


def test_netcdf_output_is_the_fig3_dataset(tmp_path, capsys):
    path = tmp_path / "run.nc"
    assert main(["solve", "--F", "0.5", "--x0", "3", "--cycles", "4", "--netcdf", str(path)]) == COMPLETED
    ds = read_netcdf(path, ("cycle", "velocity_before_impact", "period", "largest_displacement"))
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
    assert err.startswith(f"{PROG} solve: {option} {value!r} is invalid: {option} must be "), err
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
    lambda tmp: str(tmp / "new_dir") + os.sep, lambda tmp: str(tmp / "a") + "\0.nc",
    lambda tmp: str(tmp) + os.sep + ".",
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
    assert err.startswith(f"{PROG} solve: --netcdf {path!r}: ") and "no space left" in err


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
    assert err.startswith(f"{PROG} solve: --cycles ") and "n_cycles" not in err
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
    assert err.startswith(f"{PROG} solve: {option} ") and f"{option} must be " in err
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


# --- the defaults: the workflow's Fig. 3 (a) -------------------------------------------------------

REPO = Path(__file__).resolve().parents[1]


def workflow_fig3a() -> dict:
    """Fig. 3 (a) as the workflow runs it: the scene its rule simulate_fig3 is given for case ``a``."""
    import yaml

    from escapement.pipeline.config import fig3_scene

    with open(REPO / "config" / "config.yaml") as f:
        return fig3_scene(yaml.safe_load(f), "a")


def test_the_defaults_are_the_workflows_fig3a():
    scene = workflow_fig3a()
    args = cli._parser(PROG).parse_args(["solve"])
    options = {name: value for name, value in vars(args).items() if name not in ("command", "netcdf")}
    # every key of the scene is an option whose default is the scene's value; the options the scene
    # leaves out (a3, a4, v0) keep the model's own defaults: -a1, -a2, from rest
    cycles = scene.pop("n_cycles")
    expected = {**scene, "cycles": cycles, "a3": None, "a4": None, "v0": 0.0}
    assert options == expected
    assert scene["x0"] == -1.0 and expected["amplitude"] == "amplitude_h0"  # the release and amplitude the help names


def test_the_default_netcdf_file_is_the_workflows_fig3a(tmp_path, capsys):
    from escapement.pipeline.simulate import simulate_poincare

    cycles = 6
    ours, theirs = tmp_path / "cli.nc", tmp_path / "case_a.nc"
    assert main(["solve", "--cycles", str(cycles), "--netcdf", str(ours)]) == COMPLETED
    simulate_poincare({**workflow_fig3a(), "n_cycles": cycles}, str(theirs), str(tmp_path / "simulate_fig3_a.log"))
    a, b = read_netcdf(ours), read_netcdf(theirs)
    assert sorted(a.variables) == sorted(b.variables) and "amplitude_h0" in a.variables
    for name in a.variables:
        assert a[name].identical(b[name]), name
    when = ("date_created", "history")  # the time of writing, to the second
    assert {k: v for k, v in a.attrs.items() if k not in when} == {k: v for k, v in b.attrs.items() if k not in when}
    assert a.attrs["scene"] == "fig3" and a.attrs["n_cycles"] == cycles
    assert a["amplitude_h0"].attrs["long_name"].startswith("Step-1 amplitude")
    assert a.sizes["cycle"] == cycles


# --- the console script and --version ---------------------------------------------------------------

SCRIPT = Path(sys.executable).parent / "escapement"


def run_script(*args: str) -> subprocess.CompletedProcess:
    assert SCRIPT.is_file(), f"{SCRIPT} is missing: install the package (pip install -e .) to make the console script"
    return subprocess.run([str(SCRIPT), *args], capture_output=True, text=True)


def test_the_install_declares_the_console_script():
    from importlib.metadata import entry_points

    (script,) = entry_points(group="console_scripts", name="escapement")
    assert script.value == "escapement.cli:main"


def test_the_console_script_behaves_as_the_module():
    for args in (["solve", "--cycles", "3"], ["solve", "--x0", "0.05", "--cycles", "2"]):
        script, module = run_script(*args), run_process(*args)
        assert (script.returncode, script.stdout, script.stderr) == (module.returncode, module.stdout, module.stderr)
    assert run_script("solve", "--cycles", "3").stdout.count("\n") == 5


def test_each_program_is_named_as_typed():
    script, module = run_script("solve", "--b", "3"), run_process("solve", "--b", "3")
    assert script.returncode == module.returncode == INVALID_INPUT
    assert script.stderr == "escapement solve: --b 3.0 is invalid: --b must be in the open interval (0, 2)\n"
    assert module.stderr == "python -m escapement solve: --b 3.0 is invalid: --b must be in the open interval (0, 2)\n"
    assert run_script("solve", "--help").stdout.startswith("usage: escapement solve ")
    assert "Example: escapement solve" in run_script("solve", "--help").stdout
    assert run_process("--help").stdout.startswith("usage: python -m escapement ")


@pytest.mark.parametrize("run", [run_script, run_process], ids=["console script", "module"])
def test_version_prints_the_installed_distributions_version(run):
    from importlib.metadata import version

    result = run("--version")
    assert (result.returncode, result.stderr) == (0, "")
    assert result.stdout == f"escapement {version('escapement')}\n"
    assert version("escapement") != "0+unknown"


def test_version_in_process(capsys):
    from importlib.metadata import version

    assert main(["--version"]) == COMPLETED
    assert capsys.readouterr().out == f"escapement {version('escapement')}\n"


@pytest.mark.parametrize("argv0, name", [
    ("/opt/env/bin/escapement", "escapement"), ("escapement-dev", "escapement-dev"),
    (str(Path(cli.__file__).with_name("__main__.py")), "python -m escapement"), ("-c", "escapement"),
])
def test_without_a_name_the_program_takes_the_one_it_was_started_by(argv0, name, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", [argv0])
    assert cli.main(["solve", "--b", "3"]) == INVALID_INPUT
    assert capsys.readouterr().err.startswith(f"{name} solve: --b 3.0 is invalid")
