"""Helpers of the end-to-end tests: copies of the repository, Snakemake in a subprocess, dry-run plans.

The copies run a reduced configuration (:func:`reduce`: few cycles, a small map, a short
benchmark), so that every rule and every file format is exercised in seconds. The full
configuration runs in CI's Quick start.
"""

from __future__ import annotations

import ast
import json
import os
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
    config["existence_map"]["a3"]["n"] = 10
    config["existence_map"]["F"]["n"] = 8
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


#: what a workflow script is run with before its first line: Snakemake's object, of which the imports use only
#: ``scriptdir``
_STUB = "import types\nsnakemake = types.SimpleNamespace(scriptdir={scriptdir!r})\n"
_LIST = ("\nimport json as _json, sys as _sys\n"
         "print(_json.dumps(sorted({m.__file__ for n, m in list(_sys.modules.items())\n"
         "    if n.partition('.')[0] in ('escapement', 'benchmarks') and getattr(m, '__file__', None)})))\n")


def loaded_files(where: Path, script: str, also: tuple[str, ...] = ()) -> tuple[set[str], set[str]]:
    """The files of the package and of the benchmarks that a fresh interpreter has loaded once it has run
    ``script``'s statements up to its last import (with a stand-in for Snakemake's object), and once it has
    then imported the modules ``also``; relative to ``where``, whose package (``where/src``) is the one loaded."""
    path = where / script
    tree = ast.parse(path.read_text())
    last = max(i for i, node in enumerate(tree.body) if isinstance(node, (ast.Import, ast.ImportFrom)))
    code = _STUB.format(scriptdir=str(path.parent)) + ast.unparse(ast.Module(tree.body[: last + 1], [])) + _LIST
    code += "".join(f"import {name}\n" for name in also) + _LIST
    env = {**os.environ, "PYTHONPATH": str(where / "src")}
    result = subprocess.run([sys.executable, "-c", code], cwd=where, env=env, capture_output=True, text=True,
                            check=True)
    before, after = (json.loads(line) for line in result.stdout.splitlines()[-2:])
    return {os.path.relpath(f, where) for f in before}, {os.path.relpath(f, where) for f in after}
