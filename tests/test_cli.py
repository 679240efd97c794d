"""The command line, ``escapement solve`` and ``python -m escapement solve``: its table (the names the netCDF file
and ``to_dataframe`` use), its files (any run it can solve, the command in the netCDF file's history), its refusals
(one table of cases, each one line before any work), its exit statuses and its defaults (the replication's
Fig. 3 (a), read from config/paper.yaml)."""

from __future__ import annotations

import csv
import math
import subprocess
import sys
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


def test_the_table_prints_the_cycle_table_s_columns_by_value(capsys):
    assert main(["solve", "--cycles", "3"]) == COMPLETED
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "# completed: completed 3 cycles"
    assert lines[1].split("\t") == ["cycle", "impact_time", "velocity_before_impact", "period", "largest_displacement"]
    # by default from rest at -1 m (w = 1), a free arc to the first impact at a1 = -0.1 m:
    # v^2 = x0^2 - a1^2 = 0.99, and it takes arccos(a1 / x0) = arccos(0.1) s
    first = lines[2].split("\t")
    assert float(first[2]) == pytest.approx(math.sqrt(0.99), rel=1e-15)
    assert float(first[1]) == pytest.approx(math.acos(0.1), rel=1e-15) and len(lines) == 5


def test_a_run_that_leaves_the_regime_ends_with_its_outcome(capsys):
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


def _parent_is_a_file(tmp_path: Path) -> str:
    (tmp_path / "a_file").write_text("")
    return str(tmp_path / "a_file" / "out.nc")


@pytest.mark.parametrize("args, option, status", [
    (["--M", "0"], "--M", INVALID_INPUT),
    (["--b", "2.5"], "--b", INVALID_INPUT),
    (["--a2", "-0.2"], "--a2", INVALID_INPUT),
    (["--x0", "nan"], "--x0", INVALID_INPUT),
    (["--cycles", "0"], "--cycles", INVALID_INPUT),
    (["--cycles", "1e12"], "--cycles", INVALID_INPUT),
    (["--F", "one"], "--F", INVALID_INPUT),
    (["--netcdf", "{tmp}/missing/out.nc"], "--netcdf", CANNOT_WRITE),
    (["--csv", "{parent_is_a_file}"], "--csv", CANNOT_WRITE),
    (["--netcdf", "{tmp}"], "--netcdf", INVALID_INPUT),
])
def test_every_bad_input_is_one_line_before_any_work(args, option, status, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cli, "solve_exact", lambda *a, **k: pytest.fail("the solver ran before the refusal"))
    args = [a.format(tmp=tmp_path, parent_is_a_file=_parent_is_a_file(tmp_path)) for a in args]
    assert main(["solve", *args]) == status
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"{PROG} solve: {option} ") and f"{option} must be" in err


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
    result = subprocess.run(f"{sys.executable} -m escapement solve --cycles 20000 | head -c 10 > /dev/null; "
                            "echo ${PIPESTATUS[0]}", shell=True, capture_output=True, text=True, executable="/bin/bash")
    assert result.stdout.strip() == "3" and "Traceback" not in result.stderr
