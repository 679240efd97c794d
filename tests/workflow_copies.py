"""What the end-to-end tests share: copies of the repository, Snakemake runs, dry-run plans.

Snakemake and the scripts whose imports are listed run in forks of an interpreter that has imported Snakemake,
or NumPy, xarray and Matplotlib, once (:mod:`forks`): as in a new process, without the time of those imports.

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
from pathlib import Path

import yaml
from forks import Forks

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


#: the interpreters of the forks, one for each set of modules imported once and each environment
_FORKS: dict[tuple[tuple[str, ...], str | None], Forks] = {}
#: what Snakemake's command line imports to read a workflow and plan it (its plugins, its report among them)
SNAKEMAKE_MODULES = ("snakemake.cli", "snakemake.api", "snakemake.scheduling.job_scheduler", "snakemake.profiles",
                     "snakemake.report.html_reporter", "snakemake.storage", "snakemake.assets", "snakemake.utils",
                     "jsonschema", "nbformat", "requests", "PIL.Image", "docutils.core", "smart_open", "platformdirs")
#: the libraries the workflow's scripts import, none of them the project's
SCRIPT_MODULES = ("numpy", "pandas", "xarray", "netCDF4", "matplotlib", "mpmath", "yaml", "jsonschema", "markdown")


def forks(modules: tuple[str, ...], pythonpath: str | None = None) -> Forks:
    """The interpreter that imports ``modules`` once, in this process's environment (its ``PYTHONPATH``
    replaced by ``pythonpath`` if given); started at its first use, it ends with this process."""
    env = dict(os.environ) if pythonpath is None else {**os.environ, "PYTHONPATH": pythonpath}
    key = (modules, env.get("PYTHONPATH"))
    if key not in _FORKS:
        _FORKS[key] = Forks(modules, env)
    return _FORKS[key]


def snakemake(where: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    result = forks(SNAKEMAKE_MODULES).run(where, module="snakemake", args=args)
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
    """The files of the package and of the benchmarks that a new interpreter has loaded once it has run
    ``script``'s statements up to its last import (with a stand-in for Snakemake's object), and once it has
    then imported the modules ``also``; relative to ``where``, whose package (``where/src``) is the one loaded.
    The interpreter is a fork of one that has imported only libraries outside the project (``SCRIPT_MODULES``),
    so every file of the package it loads, it loads itself."""
    path = where / script
    tree = ast.parse(path.read_text())
    last = max(i for i, node in enumerate(tree.body) if isinstance(node, (ast.Import, ast.ImportFrom)))
    code = _STUB.format(scriptdir=str(path.parent)) + ast.unparse(ast.Module(tree.body[: last + 1], [])) + _LIST
    code += "".join(f"import {name}\n" for name in also) + _LIST
    result = forks(SCRIPT_MODULES, str(where / "src")).run(where, code=code)
    result.check_returncode()
    before, after = (json.loads(line) for line in result.stdout.splitlines()[-2:])
    return {os.path.relpath(f, where) for f in before}, {os.path.relpath(f, where) for f in after}
