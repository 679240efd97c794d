"""Helpers of the end-to-end tests: copies of the repository, Snakemake in a subprocess, dry-run plans.

The copies run a reduced configuration (:func:`reduce`: few cycles, a small map, a short
benchmark), so that every rule and every file format is exercised in seconds. The full
configuration runs in CI's Quick start.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[1]
PARTS = ["Snakefile", "config", "profiles", "workflow", "environment", "src", "benchmarks", "README.md",
         "REPLICATION.md"]


def copy_repository(dest: Path) -> Path:
    for part in PARTS:
        src = REPO / part
        if src.is_dir():
            shutil.copytree(src, dest / part, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        else:
            shutil.copy2(src, dest / part)
    return dest


def snakemake(where: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    result = subprocess.run(
        [sys.executable, "-m", "snakemake", *args], cwd=where, capture_output=True, text=True, timeout=600
    )
    if check and result.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{result.stdout}\n{result.stderr}")
    return result


def planned_jobs(where: Path) -> dict[str, int]:
    """Rules a dry run would execute, with their job counts (from the job stats table)."""
    out = snakemake(where, "--dry-run", "--cores", "2").stdout
    if "Nothing to be done" in out:
        return {}
    table = out.split("Job stats:")[1].split("total")[0]
    return {m[0]: int(m[1]) for m in re.findall(r"^(\w+)\s+(\d+)\s*$", table, re.M) if m[0] != "job"}


def edit_config(where: Path, edit) -> str:
    path = where / "config/config.yaml"
    original = path.read_text()
    config = yaml.safe_load(original)
    edit(config)
    path.write_text(yaml.safe_dump(config))
    return original


REDUCED_FIG3_CYCLES = 12


def reduce(config: dict) -> None:
    """Shrink every scene to a few cycles and samples; the rules, formats and checks stay."""
    config["fig3"]["n_cycles"] = REDUCED_FIG3_CYCLES
    config["fig4"]["samples_per_second"] = 50
    config["fig5"].update(n_cycles=12, samples_per_period=16)
    config["checks"]["n_cycles"] = 40
    config["benchmark"].update(n_cycles=5, min_seconds=0.01)
    config["long_run"].update(n_cycles=2000, ivp_cycles=10)
    config["escapement_error"]["F"]["n"] = 3
    config["stability_map"].update(
        b={"start": 0.0, "stop": 2.0, "n": 12}, F={"start": 0.01, "stop": 2.0, "n": 12}, chunks=2
    )


def reduced_copy(dest: Path) -> Path:
    where = copy_repository(dest)
    edit_config(where, reduce)
    return where


def copy_run(run: Path, dest: Path) -> Path:
    """A copy of a finished run (its outputs, their times and Snakemake's records), for a test that
    damages it: the shared run stays as it was, and nothing has to be rerun to restore it."""
    shutil.copytree(run, dest, symlinks=True)
    return dest
