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


#: the long name each variable must have, written from the physics and the model (the wording read once from
#: the outputs, then fixed here as the expectation): a name with one meaning everywhere ...
LONG_NAMES = {
    "M": "mass", "K": "spring constant", "F": "force of the escapement over an impulse zone",
    "b": "impact coefficient (v+ = (1 - b) v-)",
    "a1": "impact position of the first half cycle (moving right)", "a2": "end of the first impulse zone",
    "a3": "impact position of the second half cycle (moving left)", "a4": "end of the second impulse zone",
    "x0": "initial displacement", "v0": "initial velocity", "t": "time since release", "cycle": "cycle number",
    "displacement": "displacement x", "velocity": "velocity dx/dt",
    "acceleration": "acceleration d2x/dt2 between impacts",
    "velocity_before": "velocity just before the impact", "velocity_after": "velocity just after the impact",
    "impact_time": "time of the impact", "impulse": "impulse of the impact force, M (v+ - v-)",
    "energy_dissipated": "kinetic energy dissipated by the impact",
    "impact_position": "position of the impact (a1 or a3)",
    "event_kind": "kind of event", "event_time": "time of the event", "event_position": "position of the event",
    "event_velocity_before": "velocity just before the event", "event_velocity_after": "velocity just after the event",
    "velocity_before_impact": "velocity just before impact k at a1",
    "period": "time from impact k to impact k+1 at a1",
    "samples_per_second": "sampling rate of the uniform time grid",
    "velocity_window": "time window [start, end] of the velocity panel",
    "acceleration_window": "time window [start, end] of the acceleration panel",
    "case": "case number", "label": "name of the case", "group": "claim the case serves",
    "outcome_message": "how the run ended, in words", "n_cycles": "complete cycles each run was given",
    "first_period": "period of the first cycle", "amplitude_cycle": "cycle number of the amplitude",
    "largest_speed": "largest |v| on the last cycle, exact from the harmonic arcs",
    "fixed_point": "fixed point of the simulated return map", "fixed_point_eq16": "fixed point of the map (16)",
    "fixed_point_19": "fixed point of the map (17) by Eq. (19) as printed (velocity before impact)",
    "fixed_point_period": "period of the limit cycle, 50-digit reference",
    "fixed_point_velocity": "velocity before impact at a1 on the limit cycle, 50-digit reference",
    "multiplier": "multiplier mu_2 measured from the simulated return map",
    "multiplier_eq21": "multiplier (1 - b)**4 of Eq. (21)",
    "floquet_major": "larger Floquet multiplier of the flow over the last period, measured",
    "floquet_minor": "smaller Floquet multiplier of the flow over the last period, measured",
    "cycles_to_converge": "first cycle within 1e-9 (relative) of the last velocity; -1 if none",
    "closed_form_difference": "largest relative difference between the per-cycle closed forms and the exact solver, "
                              "over the impact time, velocity before impact, period and amplitude of every cycle "
                              "both ran",
    "converged": "whether the run reached a limit cycle (completed, last two velocities before the impact at a1 "
                 "within the relative tolerance)",
    "tolerance": "relative tolerance on the last two velocities before the impact at a1 for a converged run",
    "threshold": "force F* at which the constant C of the map (16) read at a1 is zero",
    "threshold_mirror": "force F*' at which the constant of the map (16) read at a3 is zero (F* of the mirror-image "
                        "escapement)",
    "zone": "impulse zone number", "zone_name": "name of the impulse zone",
    "zone_a1": "impact position a1 of the first half cycle", "zone_a2": "end a2 of the first impulse zone",
    "period_formula": "2 pi / omega + dT1 + dT2 by the corrected Eqs. (24)-(25)",
    "rate": "rate of a clock counting 2 pi / omega per swing: seconds gained per day",
    "rate_impacts": "part of the rate due to the impacts' phase jumps dT1, Eq. (24)",
    "rate_zones": "part of the rate due to the impulse zones dT2, Eq. (25)", "seconds_per_day": "seconds in a day",
    **{f"drift_{solver}": f"impact time minus the 50-digit reference, {words}" for solver, words in
       (("exact", "exact solver"), ("ivp", "solve_ivp DOP853 rtol=1e-12"), ("closed_form", "per-cycle closed forms"))},
    **{f"error_time_{solver}": f"relative error of the impact time at a1, {words}" for solver, words in
       (("exact", "exact solver"), ("ivp", "solve_ivp DOP853 rtol=1e-12"), ("closed_form", "per-cycle closed forms"))},
    **{f"error_velocity_{solver}": f"relative error of the velocity before impact, {words}" for solver, words in
       (("exact", "exact solver"), ("ivp", "solve_ivp DOP853 rtol=1e-12"), ("closed_form", "per-cycle closed forms"))},
    "max_velocity_deviation": "largest relative deviation of the velocity before impact from the fixed point once "
                              "converged, exact solver",
    "max_period_deviation": "largest relative deviation of the period from the limit cycle's once converged, exact "
                            "solver",
    "max_period_difference": "largest relative difference between the corrected Eqs. (24)-(25) and the exact "
                             "solver's period",
}
#: ... and the names whose meaning depends on the output (its folder and file; the stability map's chunks are
#: parts of the map): a cycle table's impact time starts a cycle, a summary's velocity is one number per run
LONG_NAMES_IN = {
    "fig3/case": {
        "impact_time": "time of impact k at a1 (start of cycle k)",
        "amplitude": "Step-1 amplitude h0(k) = sqrt(a1^2 + (v_k / omega)^2) of the free arc that ends in impact k "
                     "at a1 (k = 1 .. N+1; Eqs. (9b), (22a))",
    },
    "fig5/K": {"amplitude": "largest displacement between impact k and impact k+1 (right turning point)"},
    "claims/checks": {
        "x0": "initial displacement (released from rest)", "outcome": "how the run ended",
        "velocity": "velocity before impact at the last cycle", "period": "period of the last cycle",
        "amplitude": "amplitude of the last cycle", "multiplier": "multiplier mu_2 measured from the return map",
    },
    "escapement_error/rate": {
        "velocity": "velocity before the impact at a1 on the limit cycle (fixed point of the map (16))",
        "period": "period of the limit cycle, exact solver",
        "amplitude": "amplitude of the limit cycle (largest displacement)",
    },
    "stability/map": {"period": "period of the cycle at the fixed point",
                      "outcome": "how the cycle from the fixed point ended"},
    "stability/existence": {"outcome": "how the run from the release ended"},
}

#: the flag variables: their codes and meanings, the model's names spelled out here. A run ends completed (0),
#: stopped (1), turned back in a zone (2), chattering (3) or at its event limit (4); an event is an impact at
#: a1 (1), the end of the impulse at a2 (2), an impact at a3 (3), the end of the impulse at a4 (4)
FLAGS = {
    "outcome": ([0, 1, 2, 3, 4], "completed stopped turned_back_in_zone chattering event_limit"),
    "event_kind": ([1, 2, 3, 4], "impact_at_a1 end_of_impulse_at_a2 impact_at_a3 end_of_impulse_at_a4"),
    "converged": ([0, 1], "no_limit_cycle limit_cycle"),
}


def _output_kind(path: Path) -> str:
    """``fig3/case``, ``fig5/K``, ``stability/map`` (its chunks too), ... from an output's path."""
    stem = re.sub(r"_[^_]*$", "", path.stem) if path.parent.name in ("fig3", "fig5") else path.stem
    return f"{path.parent.name}/{'map' if stem.startswith('chunk_') else stem}"


def test_every_variable_written_has_the_long_name_and_flags_of_its_quantity(workflow_run):
    """By value: every variable of every netCDF output has the long name the tables above give it (a long
    name swapped between two variables fails); every flag variable the codes and meanings of the model's
    outcomes, event kinds or convergence, and only those codes in its data (an outcome written as text, only
    those names); a variable not in the tables must be added to them."""
    checked, flagged = 0, set()
    for path in sorted((workflow_run / "results").rglob("*.nc")):
        ds = read_netcdf(path)
        specific = LONG_NAMES_IN.get(_output_kind(path), {})
        for name, variable in ds.variables.items():
            assert name in specific or name in LONG_NAMES, f"{path.name}: {name} has no expected long name"
            expected = specific.get(name, LONG_NAMES.get(name))
            assert variable.attrs.get("long_name") == expected, f"{path.name}: {name}"
            checked += 1
            if name in FLAGS or "flag_values" in variable.attrs:
                assert name in FLAGS, f"{path.name}: {name} is a flag not in the table"
                values, meanings = FLAGS[name]
                written = set(variable.values.ravel().tolist())
                if variable.dtype.kind in "OSU":  # the outcome written as its name (the claims' checks)
                    assert written <= set(meanings.split()), f"{path.name}: {name}"
                    continue
                assert [int(v) for v in variable.attrs["flag_values"]] == values, f"{path.name}: {name}"
                assert variable.attrs["flag_meanings"] == meanings, f"{path.name}: {name}"
                assert written <= set(values), f"{path.name}: {name}"
                flagged.add(name)
    assert checked > 200 and flagged == set(FLAGS)



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
    assert checker is not None, ("compliance-checker is not installed beside this Python: it is in "
                                 "environment/test.lock, which the Quick start installs")
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
    assert methods == {"exact", "closed-form cycles", "map16", "RK45", "DOP853", "LSODA", "Radau", "CVODE-Adams",
                       "CVODE-BDF", "naive-RK4"}
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
