"""The command line, ``python -m escapement solve``."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from escapement.cli import main
from escapement.io.netcdf import read_netcdf


def test_help_lists_every_parameter_with_its_units():
    result = subprocess.run([sys.executable, "-m", "escapement", "solve", "--help"], capture_output=True, text=True)
    assert result.returncode == 0
    for option, unit in (("--M", "kg"), ("--K", "N/m"), ("--F", "N"), ("--a1", "m"), ("--v0", "m/s")):
        assert option in result.stdout and unit in result.stdout
    assert "Example: python -m escapement solve" in result.stdout


def test_solve_prints_the_outcome_and_the_per_cycle_table(capsys):
    assert main(["solve", "--cycles", "3"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "# completed: completed 3 cycles"
    assert lines[1].split("\t") == ["cycle", "impact_time", "velocity_before_impact", "period", "amplitude"]
    assert len(lines) == 5
    # from rest at 1 m (symmetric, w = 1): v^2 before the first impact at a1 is
    # (1 - b)^2 (x0^2 - a1^2) + 2 f (a2 - a1) = 0.81 * 0.99 + 0.3
    assert float(lines[2].split("\t")[2]) == pytest.approx(math.sqrt(0.81 * 0.99 + 0.3), rel=1e-15)


def test_an_invalid_parameter_is_refused_naming_it(capsys):
    assert main(["solve", "--b", "2.5"]) == 2
    assert "b = 2.5 is invalid: b must be in the open interval (0, 2)" in capsys.readouterr().err


def test_a_run_that_leaves_the_regime_ends_with_its_outcome(capsys):
    assert main(["solve", "--x0", "0.05", "--cycles", "3"]) == 1
    assert capsys.readouterr().out.startswith("# stopped: the escapement stopped")


def test_netcdf_output_is_the_fig3_dataset(tmp_path, capsys):
    path = tmp_path / "run.nc"
    assert main(["solve", "--F", "0.5", "--x0", "3", "--cycles", "4", "--netcdf", str(path)]) == 0
    ds = read_netcdf(path, ("cycle", "velocity_before_impact", "period", "amplitude"))
    assert ds.sizes["cycle"] == 4 and ds["period"].attrs["units"] == "s"
    assert f"wrote {path}" in capsys.readouterr().out
