"""End-to-end without a run: what the workflow plans (dry runs on a copy of the repository, or on one
whose outputs are marked up to date), what it refuses before any job, and what each kind of job imports.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from workflow_copies import copy_repository, edit_config, loaded_files, planned_jobs, snakemake


# One problem of each kind the configuration check finds (a model rule, the schema, two scenes that
# collide); tests/pipeline/test_config.py has every message, without starting Snakemake.
@pytest.mark.parametrize(
    "edit, words",
    [
        (lambda c: c["model"].update(M=0.0), ["model.M = 0.0 is invalid: M must be a number > 0 (kg)"]),
        (lambda c: c["fig4"].update(colour="red"), ["fig4.colour = 'red' is invalid: colour is not a key of fig4"]),
        (lambda c: c["fig5"].update(K=[1.0, 1.0000001, 10.0]), ["would both write K_1.nc"]),
    ],
)
def test_an_invalid_configuration_stops_before_any_job(tmp_path, edit, words):
    where = copy_repository(tmp_path)
    edit_config(where, edit)
    result = snakemake(where, "--cores", "2", check=False)
    assert result.returncode != 0
    message = result.stdout + result.stderr
    for word in words:
        assert word in message
    assert not (where / "results").exists()
    assert not list((where / "figures").glob("*")) if (where / "figures").exists() else True


def test_a_yaml_error_in_the_configuration_is_named_with_its_line(tmp_path):
    where = copy_repository(tmp_path)
    path = where / "config/config.yaml"
    lines = path.read_text().splitlines()
    number = next(i for i, line in enumerate(lines) if line.startswith("fig4:")) + 1
    lines.insert(number, "  F: [0.5")
    path.write_text("\n".join(lines) + "\n")
    result = snakemake(where, "--dry-run", check=False)
    assert result.returncode != 0
    assert f"config/config.yaml, line {number + 2}, column " in result.stdout + result.stderr
    assert "not valid YAML" in result.stdout + result.stderr


def test_the_default_profile_is_used(tmp_path):
    where = copy_repository(tmp_path)
    result = snakemake(where, "--dry-run")
    assert "Using workflow specific profile profiles/default" in result.stdout + result.stderr
    assert "rerun-incomplete" in (where / "profiles/default/config.yaml").read_text()


def test_the_slurm_profile_plans_every_job(tmp_path):
    where = copy_repository(tmp_path)
    result = snakemake(where, "--workflow-profile", "profiles/slurm", "--dry-run")
    assert "Using workflow specific profile profiles/slurm" in result.stdout + result.stderr
    assert "simulate_fig3" in result.stdout and "plot_fig5" in result.stdout


@pytest.fixture(scope="module")
def touched_run(tmp_path_factory):
    """A copy whose outputs exist, empty, and are marked up to date without running any job
    (``--touch``): enough for dry runs, in seconds."""
    where = copy_repository(tmp_path_factory.mktemp("touched"))
    summary = snakemake(where, "--summary").stdout
    for line in summary.splitlines()[1:]:
        path = where / line.split("\t")[0]
        if line.strip() and not path.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
            path.touch()
    snakemake(where, "--touch", "--cores", "1")
    assert planned_jobs(where) == {}
    return where


SIMULATIONS = {"simulate_fig3": 2, "simulate_fig4": 1, "simulate_fig5": 3, "simulate_checks": 1,
               "simulate_long_run": 1, "simulate_stability_chunk": 2, "simulate_escapement_error": 1,
               "simulate_existence_map": 1}
PLOTS = {"plot_fig3": 1, "plot_fig4": 1, "plot_fig5": 1, "plot_work_precision": 1, "plot_long_run": 1,
         "plot_stability_map": 1, "plot_escapement_error": 1, "plot_existence_map": 1}


def _planned_after_an_edit(where: Path, module: str) -> dict[str, int]:
    """The jobs a dry run plans once a comment is appended to ``module``; the file is restored."""
    path = where / "src/escapement" / module
    original, stat = path.read_bytes(), path.stat()
    path.write_bytes(original + b"\n# an edit\n")
    try:
        return planned_jobs(where)
    finally:
        path.write_bytes(original)
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))


def test_a_plotting_edit_replans_the_plots_and_documents_only(touched_run):
    planned = _planned_after_an_edit(touched_run, "plotting/paper_figures.py")
    assert {rule: planned.get(rule) for rule in PLOTS} == PLOTS
    assert planned["publish"] == 1 and "render_docs" not in planned  # the documents do not show the drawing code
    for rule in (*SIMULATIONS, "run_work_precision", "run_stress", "merge_stability"):
        assert rule not in planned, planned
    assert planned_jobs(touched_run) == {}


def test_a_solver_edit_replans_the_simulations(touched_run):
    planned = _planned_after_an_edit(touched_run, "solvers/exact.py")
    assert {rule: planned.get(rule) for rule in SIMULATIONS} == SIMULATIONS
    assert planned["run_work_precision"] == 1 and planned["run_stress"] == 1
    assert planned_jobs(touched_run) == {}


def test_a_pipeline_plot_edit_replans_no_simulation(touched_run):
    planned = _planned_after_an_edit(touched_run, "pipeline/plot.py")
    assert {rule: planned.get(rule) for rule in PLOTS} == PLOTS
    assert not set(planned) & {*SIMULATIONS, "run_work_precision", "run_stress", "merge_stability"}, planned


@pytest.fixture(scope="module")
def simulations_load(touched_run) -> dict[str, set[str]]:
    """The files of the package that each simulation's script loads, measured once in a new interpreter."""
    return {rule: loaded_files(touched_run, f"workflow/scripts/{rule}.py")[0] for rule in SIMULATIONS}


@pytest.mark.parametrize("module, replanned", [
    ("paper/claims.py", {"check_claims", "render_docs"}),  # the claims engine
    ("paper/register.py", {"check_claims", "render_docs"}),  # the claims register
    ("plotting/paper_figures.py", {"plot_fig3", "plot_fig4", "plot_fig5"}),
    ("studies/stress.py", {"run_stress"}),  # the stress cases
])
def test_an_edit_outside_the_simulations_code_replans_no_simulation(touched_run, simulations_load, module,
                                                                     replanned):
    """The simulations replanned are those whose scripts load the module, measured in a new interpreter;
    for these modules, none: the 10^6-cycle run and the stability map stay."""
    path = f"src/escapement/{module}"
    loading = {rule for rule in SIMULATIONS if path in simulations_load[rule]}
    planned = _planned_after_an_edit(touched_run, module)
    assert {rule for rule in planned if rule in SIMULATIONS} == loading, planned
    assert replanned <= set(planned), planned
    assert not loading, f"{path} is loaded by {sorted(loading)}"


@pytest.mark.parametrize(
    "modules, absent",
    [
        # the figures draw the axes the claims score (the printed axes, the candidates' scores), not the claims
        (["plot", "tables"], ["escapement.io.scenes", "escapement.io.dataset", "escapement.paper.claims",
                              "escapement.paper.registry", "escapement.solvers", "escapement.studies"]),
        (["simulate", "studies"], ["escapement.plotting", "matplotlib"]),
        (["simulate"], ["scipy.integrate"]),  # the exact solver's jobs load no SciPy integrator
        (["render"], ["escapement.plotting", "matplotlib", "scipy.integrate"]),
        (["verdict"], ["escapement.plotting.paper_figures", "escapement.plotting.style"]),  # autoscale only
    ],
)
def test_each_kind_of_job_imports_only_what_its_rules_depend_on(modules, absent):
    """What the rules' code inputs assume, checked in a fresh interpreter."""
    code = "import sys\n" + "".join(f"import escapement.pipeline.{m}\n" for m in modules)
    code += f"print(sorted(set({absent!r}) & set(sys.modules)))"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"
