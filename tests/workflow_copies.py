"""What the end-to-end tests share: copies of the repository with a reduced replication, and Snakemake run as
a process of its own, in a session of its own, so that the whole tree of its jobs is killed when the test ends
early (a failure, a time limit, Ctrl-C) and no process outlives the suite."""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[1]
PARTS = ["Snakefile", "config", "profiles", "workflow", "src", "benchmarks", "README.md", "REPLICATION.md",
         "figures", "article", "CITATION.cff", ".gitattributes", "environment/environment.yml"]
SNAKEMAKE = Path(sys.executable).with_name("snakemake")
#: the longest a Snakemake command of the tests may take before it is killed (the reduced run takes ~20 s)
TIMEOUT = 240


def copy_repository(dest: Path) -> Path:
    for part in PARTS:
        source = REPO / part
        if source.is_dir():
            shutil.copytree(source, dest / part, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        elif source.exists():
            (dest / part).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, dest / part)
    return dest


def reduce(paper: dict) -> None:
    """Shrink every scene of the replication to a few cycles and samples; the rules, formats and checks stay."""
    paper["fig3"]["n_cycles"] = 12
    paper["fig4"]["samples_per_second"] = 50
    paper["fig5"].update(n_cycles=12, samples_per_period=16)
    paper["checks"]["n_cycles"] = 40
    paper["benchmark"].update(n_cycles=5, min_seconds=0.01, slow_settings={"Radau": [1e-6]})
    paper["speed"]["headline"].update(n_cycles=5, target=1e-6, settings={"DOP853": [1e-9]})
    paper["speed"]["floor"].update(exact_cycles=[10], ensemble_trajectories=10, ensemble_cycles=2,
                                   stream_cycles=[100, 1000])
    paper["long_run"].update(n_cycles=2000, ivp_cycles=10)
    paper["escapement_error"]["F"]["n"] = 3
    paper["existence_map"]["a3"]["n"] = 10
    paper["existence_map"]["F"]["n"] = 8
    paper["stability_map"].update(b={"start": 0.0, "stop": 2.0, "n": 12}, F={"start": 0.01, "stop": 2.0, "n": 12})


def edit_paper(where: Path, edit) -> None:
    path = where / "config/paper.yaml"
    paper = yaml.safe_load(path.read_text())
    edit(paper)
    path.write_text(yaml.safe_dump(paper))


def reduced_copy(dest: Path) -> Path:
    where = copy_repository(dest)
    edit_paper(where, reduce)
    return where


#: a sitecustomize module that, in each job's process, writes the name and file of each module it loaded on exit
TRACER = """
import atexit, os, sys

def _loaded():
    job = getattr(sys.modules.get("__main__"), "snakemake", None)
    if job is not None:
        loaded = sorted(f"{name}\\t{m.__file__}" for name, m in list(sys.modules.items())
                        if getattr(m, "__file__", None))
        name = f"{job.rule}-{os.getpid()}.txt"
        with open(os.path.join(os.environ["ESCAPEMENT_TRACE"], name), "w") as handle:
            handle.write("\\n".join(loaded))

atexit.register(_loaded)
"""


def snakemake(where: Path, *args: str, check: bool = True, timeout: float = TIMEOUT,
              trace: Path | None = None) -> subprocess.CompletedProcess:
    """``snakemake ARGS`` in ``where``, its jobs running the copy's package (``src`` first on the path), each job's
    loaded modules listed in ``trace`` (a folder) if given; its process group killed if it outlives ``timeout`` or
    the test stops."""
    path = [str(where / "src")]
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    if trace is not None:
        trace.mkdir(parents=True, exist_ok=True)
        (trace / "sitecustomize.py").write_text(TRACER)
        path.insert(0, str(trace))
        env["ESCAPEMENT_TRACE"] = str(trace)
    env["PYTHONPATH"] = os.pathsep.join(path)
    process = subprocess.Popen([str(SNAKEMAKE), *args], cwd=where, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, start_new_session=True, env=env)
    try:
        stdout, stderr = process.communicate(timeout=timeout)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
    result = subprocess.CompletedProcess(process.args, process.returncode, stdout, stderr)
    if check and result.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{stdout[-3000:]}\n{stderr[-3000:]}")
    return result


def planned_jobs(where: Path, *args: str) -> dict[str, int]:
    """The rules a dry run would execute, with their job counts (from the job stats table)."""
    out = snakemake(where, "--dry-run", "--cores", "2", *args).stdout
    if "Nothing to be done" in out:
        return {}
    table = out.split("Job stats:")[1].split("total")[0]
    return {m[0]: int(m[1]) for m in re.findall(r"^(\w+)\s+(\d+)\s*$", table, re.M) if m[0] != "job"}


def tracked_state(where: Path) -> dict[str, bytes]:
    """Every file of the copy outside results/ and Snakemake's records, by its bytes."""
    return {str(p.relative_to(where)): p.read_bytes() for p in sorted(where.rglob("*"))
            if p.is_file() and p.relative_to(where).parts[0] not in ("results", ".snakemake")
            and "__pycache__" not in p.parts}
