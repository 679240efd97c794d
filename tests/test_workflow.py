"""End-to-end: the workflow run once on a copy of the repository in a temporary directory.

The copy runs a reduced configuration (:func:`workflow_copies.reduce`: few cycles, a small map, a
short benchmark), so that every rule and every file format is exercised in seconds; the tests that
damage a run work on a copy of it. The full configuration runs in CI's Quick start, which also checks
that the documents it regenerates are the committed ones;
:func:`test_the_committed_verdict_is_the_expected_one` ties those documents to the expected verdict.
The plans of dry runs, which need no run, are in ``test_workflow_plans.py``.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from workflow_copies import REDUCED_FIG3_CYCLES, REPO, copy_run, edit_config, planned_jobs, reduced_copy, snakemake

from escapement.io.netcdf import read_netcdf
from escapement.paper.vocabulary import STATUSES

@pytest.fixture(scope="module")
def workflow_run(tmp_path_factory):
    where = reduced_copy(tmp_path_factory.mktemp("workflow"))
    snakemake(where, "--cores", "2")
    return where


OUTPUTS = {
    "results/benchmark/long_run.nc": ("cycle", ["drift_exact", "drift_ivp", "error_time_exact", "error_velocity_ivp"]),
    "results/stability/map.nc": ("b", ["multiplier", "multiplier_eq21", "fixed_point", "outcome", "F"]),
    "results/claims/checks.nc": ("case", ["multiplier", "period", "velocity"]),
    "results/fig3/case_a.nc": ("cycle", ["impact_time", "velocity_before_impact", "period", "amplitude"]),
    "results/fig3/case_b.nc": ("cycle", ["impact_time", "velocity_before_impact", "period", "amplitude"]),
    "results/fig4/shock.nc": (
        "t",
        ["displacement", "velocity", "acceleration", "impact_time", "velocity_before", "velocity_after", "impulse",
         "energy_dissipated"],
    ),
    "results/fig5/K_0.1.nc": ("t", ["displacement", "velocity", "velocity_before_impact", "period", "amplitude"]),
    "results/fig5/K_1.nc": ("t", ["displacement", "velocity", "velocity_before_impact", "period", "amplitude"]),
    "results/fig5/K_10.nc": ("t", ["displacement", "velocity", "velocity_before_impact", "period", "amplitude"]),
    "results/escapement_error/rate.nc": ("F", ["amplitude", "period", "period_formula", "rate", "rate_impacts",
                                                "rate_zones"]),
    "results/stability/existence.nc": ("a3", ["outcome", "converged", "threshold", "threshold_mirror", "F"]),
}


@pytest.mark.parametrize("path", list(OUTPUTS))
def test_every_netcdf_output_holds_its_variables(workflow_run, path):
    coord, names = OUTPUTS[path]
    ds = read_netcdf(workflow_run / path, required=(coord, *names))
    assert "units" in ds[coord].attrs and "long_name" in ds[coord].attrs
    for name in names:
        assert ("units" in ds[name].attrs or "flag_values" in ds[name].attrs) and "long_name" in ds[name].attrs
    assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
    assert ds.attrs.get("outcome", "completed") == "completed"


#: the dimension each variable of the outputs must have, written from the physics (not read from the
#: package): lengths in m, times in s, velocities in m/s, accelerations in m/s2, forces in N, the impulse
#: in N s, energies in J, the daily rate in s/day; counts, ratios and relative errors dimensionless
DIMENSIONS = {
    **dict.fromkeys(["M"], "kg"), **dict.fromkeys(["F", "threshold", "threshold_mirror"], "N"), "K": "N/m",
    **dict.fromkeys(["a1", "a2", "a3", "a4", "x0", "amplitude", "displacement", "event_position", "impact_position",
                     "zone_a1", "zone_a2"], "m"),
    **dict.fromkeys(["t", "period", "first_period", "period_formula", "fixed_point_period", "impact_time",
                     "event_time", "drift_exact", "drift_ivp", "drift_closed_form", "velocity_window",
                     "acceleration_window"], "s"),
    **dict.fromkeys(["v0", "velocity", "velocity_before", "velocity_after", "velocity_before_impact",
                     "event_velocity_before", "event_velocity_after", "largest_speed", "fixed_point",
                     "fixed_point_19", "fixed_point_eq16", "fixed_point_velocity"], "m/s"),
    "acceleration": "m/s2", "impulse": "N s", "energy_dissipated": "J", "samples_per_second": "1/s",
    **dict.fromkeys(["rate", "rate_impacts", "rate_zones", "seconds_per_day"], "s/day"),
    **dict.fromkeys(["b", "case", "cycle", "amplitude_cycle", "cycles_to_converge", "n_cycles", "zone", "tolerance",
                     "multiplier", "multiplier_eq21", "floquet_major", "floquet_minor", "closed_form_difference",
                     "max_period_deviation", "max_period_difference", "max_velocity_deviation", "error_time_exact",
                     "error_time_ivp", "error_time_closed_form", "error_velocity_exact", "error_velocity_ivp",
                     "error_velocity_closed_form"], "1"),
}


def test_every_variable_written_has_the_dimension_of_its_quantity(workflow_run):
    """By value: the units of every variable of every netCDF output convert to the dimension its quantity
    must have (cf_units), so a velocity written in m s-2 fails; a variable without units is a flag or a
    label; a variable not in the table must be added to it with its dimension."""
    from cf_units import Unit

    checked = 0
    for path in sorted((workflow_run / "results").rglob("*.nc")):
        ds = read_netcdf(path)
        for name, variable in ds.variables.items():
            units = variable.attrs.get("units")
            if units is None:
                assert "flag_values" in variable.attrs or variable.dtype.kind in "OSU", f"{path.name}: {name}"
                continue
            assert name in DIMENSIONS, f"{path.name}: {name} ({units}) has no expected dimension in the table"
            got, expected = Unit(units), Unit(DIMENSIONS[name])
            assert got.is_convertible(expected) and got.convert(1.0, expected) == pytest.approx(1.0), (
                f"{path.name}: {name} is in {units}, not in {DIMENSIONS[name]}")
            checked += 1
    assert checked > 100


def test_fig3_has_the_configured_number_of_cycles(workflow_run):
    ds = read_netcdf(workflow_run / "results/fig3/case_a.nc")
    assert ds.sizes["cycle"] == REDUCED_FIG3_CYCLES and float(ds["F"]) == 1.0 and float(ds["x0"]) == -1.0
    assert ds.sizes["amplitude_cycle"] == REDUCED_FIG3_CYCLES + 1  # the Step-1 amplitude: N + 1 values
    assert "t" not in ds.dims


def test_fig4_window_and_fig5_spring_constants(workflow_run):
    ds = read_netcdf(workflow_run / "results/fig4/shock.nc")
    assert (ds["t"].values[0], ds["t"].values[-1]) == (80.0, 87.0)
    for label, k in (("0.1", 0.1), ("1", 1.0), ("10", 10.0)):
        assert float(read_netcdf(workflow_run / f"results/fig5/K_{label}.nc")["K"]) == k


@pytest.mark.parametrize("name", ["fig3", "fig4", "fig5", "work_precision", "long_run", "stability_map",
                                  "escapement_error", "existence_map"])
def test_figures_exist_as_png_and_pdf(workflow_run, name):
    assert (workflow_run / f"results/figures/{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (workflow_run / f"results/figures/{name}.pdf").read_bytes()[:5] == b"%PDF-"


TRACKED = [f"figures/{name}.{ext}" for name in ("fig3", "fig4", "fig5", "long_run", "stability_map", "escapement_error",
                                                 "existence_map")
           for ext in ("png", "pdf")] + ["README.md", "REPLICATION.md"]


def test_the_tracked_figures_and_documents_are_the_published_copies(workflow_run):
    for path in TRACKED:
        source = f"results/docs/{path}" if path.endswith(".md") else f"results/{path}"
        assert (workflow_run / path).read_bytes() == (workflow_run / source).read_bytes(), path
    assert not (workflow_run / "figures/work_precision.png").exists()  # drawn from wall times
    for path in ("README.md", "REPLICATION.md"):
        assert "<!--m-->" not in (workflow_run / path).read_text()


def test_redrawing_leaves_every_tracked_file_byte_identical(workflow_run):
    before = {path: (workflow_run / path).read_bytes() for path in TRACKED}
    rules = ["plot_fig3", "plot_stability_map", "render_docs"]
    snakemake(workflow_run, "--cores", "2", "--forcerun", *rules)
    assert {path: (workflow_run / path).read_bytes() for path in TRACKED} == before
    log = (workflow_run / "results/logs/publish.log").read_text()
    assert log.count(": unchanged") == len(TRACKED) and ": updated" not in log
    assert planned_jobs(workflow_run) == {}


def test_a_failed_run_leaves_the_tracked_documents_in_place(workflow_run, tmp_path):
    run = copy_run(workflow_run, tmp_path / "run")
    before = {path: (run / path).read_bytes() for path in TRACKED}
    claims = run / "results/claims.csv"
    stat = claims.stat()
    claims.write_text("not,the,claims,table\n")
    os.utime(claims, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    result = snakemake(run, "--cores", "1", "--forcerun", "render_docs", check=False)
    assert result.returncode != 0
    assert {path: (run / path).read_bytes() for path in TRACKED} == before


def test_logs_and_benchmarks_are_written(workflow_run):
    assert (workflow_run / "results/logs/simulate_fig3_a.log").read_text().count("done in") == 1
    assert (workflow_run / "results/benchmarks/simulate_fig4.tsv").exists()


def test_a_second_run_does_nothing(workflow_run):
    assert planned_jobs(workflow_run) == {}


VERDICT = {"check_claims": 1, "render_docs": 1, "publish": 1, "all": 1}
DOCS = {"render_docs": 1, "publish": 1, "all": 1}
#: a change of the readings' score table redraws the three paper figures, whose captions list its ties
READINGS = {"score_readings": 1, "plot_fig3": 1, "plot_fig4": 1, "plot_fig5": 1}


@pytest.mark.parametrize(
    "edit, expected",
    [
        (lambda c: c["fig4"].update(samples_per_second=500), {"simulate_fig4": 1, **READINGS, **VERDICT}),
        (lambda c: c["fig5"].update(n_cycles=61), {"simulate_fig5": 3, **READINGS, **VERDICT}),
        (lambda c: c["checks"].update(n_cycles=301), {"simulate_checks": 1, **VERDICT}),
        (
            lambda c: c["long_run"].update(ivp_cycles=900),
            {"simulate_long_run": 1, "plot_long_run": 1, "run_stress": 1, **DOCS},
        ),
        (
            lambda c: c["stability_map"].update(chunks=5),
            {"simulate_stability_chunk": 5, "merge_stability": 1, "plot_stability_map": 1, **DOCS},
        ),
        (
            lambda c: c["fig3"]["cases"]["b"].update(F=0.6),
            {"simulate_fig3": 1, "simulate_checks": 1, **READINGS, **VERDICT},
        ),
    ],
)
def test_editing_one_scene_reruns_that_scene_only(workflow_run, edit, expected):
    original = edit_config(workflow_run, edit)
    try:
        assert planned_jobs(workflow_run) == expected
    finally:
        (workflow_run / "config/config.yaml").write_text(original)


def test_the_report_shows_every_figure(workflow_run):
    snakemake(workflow_run, "--report", "results/report.html")
    html = (workflow_run / "results/report.html").read_text(errors="replace")
    for name in ("fig3.png", "fig4.png", "fig5.png", "work_precision.png", "long_run.png", "stability_map.png"):
        assert name in html


def test_compliance_checker_passes_cf_1_11(workflow_run):
    checker = shutil.which("compliance-checker", path=str(Path(sys.executable).parent))
    if checker is None:
        pytest.skip("compliance-checker is not installed")
    paths = sorted((workflow_run / "results").glob("*/*.nc"))
    assert len(paths) >= 11
    result = subprocess.run([checker, "--test=cf:1.11", "--criteria=strict", *map(str, paths)], capture_output=True,
                            text=True, timeout=300)
    assert result.returncode == 0, result.stdout[-3000:]
    assert result.stdout.count("All tests passed") == len(paths), result.stdout[-3000:]


EXPECTED_VERDICT = {
    "eq3a_state_matrix": "undetermined",
    "eq3c_impact_matrix": "consistent",
    "eq4_jump_set": "consistent",
    "eq5_impulse_sets": "consistent",
    "eq16_map": "reproduced",
    "eq14_as_printed": "partially_reproduced",
    "eq19_fixed_point_case_a": "reproduced",
    "eq19_fixed_point_case_b": "reproduced",
    "eq21_multiplier": "reproduced",
    "stability_iff_b": "partially_reproduced",
    "stability_symmetric_independent": "reproduced",
    "asymmetric_convergence_depends": "not_reproduced",
    "eq22_step_times": "reproduced",
    "eq22e_step_time": "not_reproduced",
    "eq23_period": "partially_reproduced",
    "eq24_impact_perturbation": "partially_reproduced",
    "eq25_force_perturbation": "not_reproduced",
    "fig3_both_converge": "reproduced",
    "fig3_velocity_a_greater": "reproduced",
    "fig3_amplitude_a_greater": "reproduced",
    "fig3_converging_speed_depends_on_force": "not_reproduced",
    "fig3_period_a": "not_reproduced",
    "fig3_period_b": "not_reproduced",
    "fig3_periods_identical": "not_reproduced",
    "period_independent_of_initial_condition": "reproduced",
    "fig3a_velocity_axis": "consistent",
    "fig3b_velocity_axis": "consistent",
    "fig3a_period_axis": "not_reproduced",
    "fig3b_period_axis": "not_reproduced",
    "fig3a_amplitude_axis": "partially_reproduced",
    "fig3b_amplitude_axis": "consistent",
    "fig4_impulse_and_energy": "consistent",
    "fig4_velocity_axis": "partially_reproduced",
    "fig4_acceleration_axis": "partially_reproduced",
    "fig5_limit_cycles": "reproduced",
    "fig5_amplitude_smaller_K_greater": "reproduced",
    "fig5_max_velocity_greater_K_smaller": "not_reproduced",
    "fig5_recovery_small_K_faster": "partially_reproduced",
    "fig5a_axes": "consistent",
    "fig5b_axes": "consistent",
    "fig5c_axes": "consistent",
    "asymmetric_existence_depends": "reproduced",
    "fig3_a_smaller_at_start": "reproduced",
    "initial_amplitude_no_effect": "partially_reproduced",
    "period_is_natural_period": "not_reproduced",
    "section_one_crossing_per_cycle": "reproduced",
    "eq10_impact_a1": "consistent",
    "eq11_velocity_a2": "reproduced",
    "eq12_velocity_a3": "reproduced",
    "eq13_impact_a3": "consistent",
    "eq15_velocity_a1": "reproduced",
    "eq17_symmetric_map": "reproduced",
    "eq20_map_derivative": "reproduced",
    "stable_velocity_determined_by_force": "reproduced",
    "fig4_window_holds_impact": "reproduced",
    "solution_exists_unique": "partially_reproduced",
    "fig5_dimensions_differ": "reproduced",
    "fig5_impact_shown": "reproduced",
    "sec2_frequency_changed_by_force_and_impact": "reproduced",
    "sec33_linear_non_homogeneous": "partially_reproduced",
    "eq8_trivial_multiplier": "reproduced",
    "sec4_greater_force_greater_amplitude": "reproduced",
    "sec4_transient_periods_depend_on_release": "reproduced",
    "model_describes_system": "untestable",
    "airy_symmetric_impulse": "reproduced",
    "period_as_daily_rate": "not_reproduced",
}


def _verdict_table(markdown: str) -> dict[str, str]:
    """Claim id to status, from the register table of REPLICATION.md (first column the id in backticks,
    last column the status in words, "not reproduced" in bold)."""
    rows = re.findall(r"^\| `(\w+)` \|.*\| ([^|]+?) \|$", markdown, re.M)
    return {claim: status.strip("*").replace(" ", "_") for claim, status in rows}


def test_the_committed_verdict_is_the_expected_one():
    """A change of verdict must be deliberate: update this table and REPLICATION.md's template.

    The full workflow writes REPLICATION.md from ``results/claims.csv``; CI's Quick start checks
    that the regenerated document is the committed one."""
    assert _verdict_table((REPO / "REPLICATION.md").read_text()) == EXPECTED_VERDICT


def test_the_reduced_run_judges_every_claim(workflow_run):
    from escapement.pipeline.verdict import read_claims_csv

    rows = read_claims_csv(workflow_run / "results/claims.csv")
    assert [r["claim_id"] for r in rows] == list(EXPECTED_VERDICT)
    assert {r["status"] for r in rows} <= set(STATUSES)


def test_the_work_precision_table_and_its_targets(workflow_run):
    import csv

    rows = list(csv.DictReader(open(workflow_run / "results/benchmark/work_precision.csv")))
    assert list(rows[0]) == ["method", "setting", "wall_s", "repeats", "error_velocity", "error_time"]
    methods = {r["method"] for r in rows}
    assert methods == {"exact", "closed-form cycles", "map16", "RK45", "DOP853", "LSODA", "Radau", "CVODE-Adams", "CVODE-BDF", "naive-RK4"}
    exact = next(r for r in rows if r["method"] == "exact")
    assert float(exact["error_velocity"]) <= 1e-14 and float(exact["error_time"]) <= 1e-14



@pytest.mark.parametrize(
    "damaged, target, rule",
    [("results/fig4/shock.nc", "results/figures/fig4.png", "plot_fig4"),
     ("results/claims/checks.nc", "results/claims.csv", "check_claims")],
)
def test_a_damaged_netcdf_fails_its_rule_naming_the_file(workflow_run, tmp_path, damaged, target, rule):
    run = copy_run(workflow_run, tmp_path / "run")
    path = run / damaged
    stat = path.stat()
    path.write_bytes(path.read_bytes()[: stat.st_size // 3])
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))  # damaged, not updated: only the rule reruns
    result = snakemake(run, "--cores", "1", "--forcerun", rule, target, check=False)
    assert result.returncode != 0
    assert f"{path.name}: not a readable netCDF file" in result.stdout + result.stderr
    assert not (run / target).exists()  # no partial output left behind


def test_the_stress_summary_passes(workflow_run):
    import csv

    rows = list(csv.DictReader(open(workflow_run / "results/stress/summary.csv")))
    assert len(rows) >= 15
    assert all(r["passed"] == "yes" for r in rows), [r for r in rows if r["passed"] != "yes"]


def test_a_motion_that_leaves_the_regime_is_recorded(workflow_run, tmp_path):
    where = copy_run(workflow_run, tmp_path / "run")
    edit_config(where, lambda c: c["fig3"]["cases"]["a"].update(x0=0.05))
    for made in ("results/figures/fig3.png", "results/claims.csv"):  # the copy's, made before the edit
        (where / made).unlink()
    snakemake(where, "--cores", "2", "results/fig3/case_a.nc", "results/figures/fig3.png", "results/claims.csv")
    ds = read_netcdf(where / "results/fig3/case_a.nc")
    assert ds.attrs["outcome"] == "stopped" and ds.sizes["cycle"] == 0
    assert "never passes the next impact position" in ds.attrs["outcome_message"]
    from escapement.pipeline.verdict import read_claims_csv

    rows = {r["claim_id"]: r for r in read_claims_csv(where / "results/claims.csv")}
    assert rows["eq19_fixed_point_case_a"]["status"] == "not_reproduced"
    assert "left the escapement regime" in rows["eq19_fixed_point_case_a"]["replicated_value"]
    assert (where / "results/figures/fig3.png").exists()
