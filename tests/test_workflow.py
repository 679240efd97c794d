"""End to end: the workflow run once on a copy of the repository with a reduced replication (few cycles, small
maps, a short benchmark: every rule and file format in seconds), then the user's two jobs on that run: parameter
studies of their own, which must run to the end under their own name and leave the replication and every tracked
file as they were, and the explicit publish step. The plans of edits are dry runs on a copy of the finished run.
The full replication runs in CI's Quick start, which checks by the publish rule that the tracked files are
current, every netCDF output against CF-1.11 and ACDD-1.3, and the report in a browser."""

from __future__ import annotations

import html
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml
from snakemake.api import SnakemakeApi
from snakemake.settings.types import OutputSettings, ResourceSettings
from workflow_copies import copy_repository, planned_jobs, reduced_copy, snakemake, tracked_state

from escapement.io.netcdf import read_netcdf, write_csv
from escapement.pipeline.article import write_article
from escapement.pipeline.outputs import ARTICLE_FIGURES
from escapement.pipeline.publish import check
from escapement.pipeline.tables import read_claims


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The reduced copy after the default run (each job's loaded modules listed in the folder :func:`traces`
    names), and the state of its tracked files before it."""
    where = reduced_copy(tmp_path_factory.mktemp("workflow"))
    before = tracked_state(where)
    snakemake(where, "--cores", "2", trace=traces(where))
    return where, before


@pytest.fixture(scope="module")
def own_studies(run):
    """The run, then a study of the user's own on it, under its own name: other spring constants and forces."""
    where, _ = run
    claims = (where / "results/replication/claims.csv").read_bytes()
    for stale in ("phase_diagrams/K_7.nc", "stability_map.nc"):  # what an earlier configuration of the study made
        (where / "results/forces" / stale).parent.mkdir(parents=True, exist_ok=True)
        (where / "results/forces" / stale).write_bytes(b"")
    study = snakemake(where, "--cores", "2", "--config", "fig5={K: [0.1, 1.0, 5.0], F: [1.0, 0.5, 1.0]}",
                      "name=forces")
    return where, claims, study


def test_the_default_run_writes_only_under_results(run):
    where, before = run
    assert tracked_state(where) == before
    assert (where / "results/replication/docs/README.md").is_file()


def test_a_second_run_has_nothing_to_do(run):
    assert planned_jobs(run[0]) == {}


def test_a_parameter_study_runs_to_the_end_under_its_own_name_and_leaves_the_replication_as_it_was(run, own_studies):
    where, claims, study = own_studies
    figure = where / "results/forces/figures/phase_diagrams.png"
    assert figure.is_file() and figure.with_suffix(".pdf").is_file()
    panels = [read_netcdf(where / f"results/forces/phase_diagrams/K_{k:g}.nc") for k in (0.1, 1.0, 5.0)]
    assert [float(ds["K"]) for ds in panels] == [0.1, 1.0, 5.0] and [float(ds["F"]) for ds in panels] == [1.0, 0.5, 1.0]
    assert all("Fig." not in ds.attrs["title"] and ds.attrs["study"] == "forces" for ds in panels)
    assert panels[0].attrs["study_changes"] == \
        "fig5.K = [0.1, 1, 5] N/m (paper: [0.1, 1, 10] N/m); fig5.F = [1, 0.5, 1] N (paper: [1, 0.5, 0.5] N)"
    assert (where / "results/replication/claims.csv").read_bytes() == claims  # the claims: neither rerun nor changed
    assert tracked_state(where) == run[1]
    assert "check_claims" not in study.stdout + study.stderr and "publish" not in study.stdout + study.stderr


def test_a_study_run_again_keeps_only_what_its_configuration_makes(own_studies):
    where, _, study = own_studies
    assert sorted(p.name for p in (where / "results/forces/phase_diagrams").iterdir()) == \
        ["K_0.1.nc", "K_1.nc", "K_5.nc"]
    assert not (where / "results/forces/stability_map.nc").exists()
    for stale in ("phase_diagrams/K_7.nc", "stability_map.nc"):
        assert f"removed results/forces/{stale}: the study 'forces' no longer makes it" in study.stderr


def test_publish_is_refused_before_any_job_with_a_configuration_of_your_own(run):
    result = snakemake(run[0], "--cores", "2", "publish", "--config", "model={M: 2.0}", check=False)
    assert result.returncode != 0
    said = result.stdout + result.stderr
    assert "publish updates the tracked figures and documents from the replication alone" in said


def test_publish_updates_the_tracked_files_and_then_they_show_what_the_run_drew(run, tmp_path, monkeypatch):
    where = Path(shutil.copytree(run[0], tmp_path / "copy", symlinks=True))
    snakemake(where, "--cores", "2", "publish")
    monkeypatch.chdir(where)
    assert all(same for _, same, _ in check())
    assert (where / "README.md").read_text() == (where / "results/replication/docs/README.md").read_text()


#: the dimension each variable of the outputs must have, written from the physics (not read from the package):
#: lengths in m, times in s, velocities in m/s, accelerations in m/s2, forces in N, the impulse in N s, energies
#: in J, the daily rate in s/day; counts, ratios and relative errors dimensionless
DIMENSIONS = {
    "M": "kg", "K": "N/m", **dict.fromkeys(["F", "threshold", "threshold_mirror"], "N"),
    **dict.fromkeys(["a1", "a2", "a3", "a4", "x0", "amplitude_h0", "largest_displacement", "displacement",
                     "event_position", "impact_position", "zone_a1", "zone_a2"], "m"),
    **dict.fromkeys(["t", "t_final", "period", "first_period", "period_formula", "fixed_point_period", "impact_time",
                     "event_time", "drift_exact", "drift_ivp", "drift_closed_form", "velocity_window",
                     "acceleration_window", "continued_at"], "s"),
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
#: the variables of each run of the checks dataset beside its table, <run>_<variable> (the run by its name in
#: config/paper.yaml's checks block), by <variable>: the run's model, its settings and what it measures
RUN_VARIABLES = {"M": "kg", "K": "N/m", "F": "N", **dict.fromkeys(["b", "n_cycles", "side", "cycles", "slope",
                                                                   "perturbation", "section_cycles", "offset",
                                                                   "event_kind", "samples_per_period", "crossings"],
                                                                  "1"),
                 **dict.fromkeys(["a1", "a2", "a3", "a4", "x0", "event_position"], "m"),
                 **dict.fromkeys(["impact_time", "zone_shift", "event_time", "t_end"], "s"),
                 **dict.fromkeys(["velocity", "next_velocity", "converged_speed", "speed", "event_velocity_before",
                                  "event_velocity_after"], "m/s")}
#: the flag variables: a run ends completed (0), stopped (1), turned back in a zone (2), chattering (3) or at its
#: event limit (4); an event is an impact at a1 (1), the end of the impulse at a2 (2), an impact at a3 (3), the end
#: of the impulse at a4 (4)
FLAGS = {"outcome": [0, 1, 2, 3, 4], "event_kind": [1, 2, 3, 4], "converged": [0, 1]}


def test_every_variable_written_has_the_dimension_of_its_quantity_and_a_long_name(run):
    """By value: the units of every variable of every netCDF output convert to the dimension its quantity must
    have (cf_units), so a velocity written in m s-2 fails; a variable without units is a flag or a label."""
    from cf_units import Unit

    paths = sorted((run[0] / "results").rglob("*.nc"))
    assert len(paths) >= 13
    runs = sorted(yaml.safe_load((run[0] / "config/paper.yaml").read_text())["checks"], key=len, reverse=True)

    def variable_of(name: str) -> str:  # a named run's variable by what it is, whatever the run's name
        prefix = next((f"{r}_" for r in runs if name.startswith(f"{r}_") and name[len(r) + 1:] in RUN_VARIABLES), "")
        return name.removeprefix(prefix)

    for path in paths:
        ds = read_netcdf(path)
        assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3" and "commit " in ds.attrs["source"]
        assert "rule " in ds.attrs["history"] or "merged" in ds.attrs["history"]
        # a coordinate variable (named as its dimension) holds numbers, as CF's checker requires
        assert all(ds[dim].dtype.kind in "iuf" for dim in ds.dims if dim in ds.variables), path.name
        for name, variable in ds.variables.items():
            assert variable.attrs.get("long_name"), f"{path.name}: {name}"
            units, table = variable.attrs.get("units"), DIMENSIONS if name in DIMENSIONS else RUN_VARIABLES
            if units is None:
                if "flag_values" in variable.attrs:
                    assert variable.attrs["flag_values"].tolist() == FLAGS[variable_of(name)], f"{path.name}: {name}"
                else:
                    assert variable.dtype.kind in "OSU", f"{path.name}: {name}"  # a label
                continue
            quantity = name if name in DIMENSIONS else variable_of(name)
            assert quantity in table, f"{path.name}: {name} ({units}) has no expected dimension in the table"
            got, expected = Unit(units), Unit(table[quantity])
            assert got.is_convertible(expected) and got.convert(1.0, expected) == pytest.approx(1.0), (
                f"{path.name}: {name} is in {units}, not in {table[quantity]}")


def test_the_replication_s_poincare_map_follows_the_map_17_by_hand(run):
    """Fig. 3 (a), from rest at -1 m: v1^2 = x0^2 - a1^2 = 0.99, then v(k+1)^2 = 0.6561 v(k)^2 + 0.543 f with
    f = 1 (the map (17) with the paper's numbers, iterated here)."""
    ds = read_netcdf(run[0] / "results/replication/poincare_map/case_a.nc")
    v2 = [0.99]
    for _ in range(ds.sizes["cycle"] - 1):
        v2.append(0.6561 * v2[-1] + 0.543)
    np.testing.assert_allclose(ds["velocity_before_impact"].values, np.sqrt(v2), rtol=1e-12)
    assert ds.attrs["title"].endswith("(Fig. 3 of Mao, Fu & Li 2013)")


def article_inputs(where: Path) -> dict[str, str | list[str]]:
    """The article's files in the run ``where``, as the rule render_article hands them to its job."""
    results = where / "results/replication"
    return {"claims": str(results / "claims.csv"), "limits": str(results / "panel_limits.csv"),
            "checks": str(results / "checks.nc"), "readings": str(results / "readings.csv"),
            "benchmark": str(results / "work_precision.csv"), "citation": str(where / "CITATION.cff"),
            "template": str(where / "workflow/templates/article.typ"),
            "bibliography": str(where / "workflow/templates/article.bib"),
            "fig3": [str(results / "poincare_map/case_a.nc"), str(results / "poincare_map/case_b.nc")],
            "figures": [str(results / f"figures/{name}.svg") for name in ARTICLE_FIGURES]}


def test_the_article_is_a_pdf_a_of_its_metadata_with_the_runs_numbers(run):
    """The run writes the article: PDF/A-2b (its XMP says so), titled as metadata.yaml is, of four pages or more
    and five figures or more, with the limit cycles' periods, velocities and multiplier of the checks dataset (read
    here) and the headline counts of the documents."""
    where = run[0] / "results/replication/article"
    pdf, meta = (where / "article.pdf").read_bytes(), yaml.safe_load((where / "metadata.yaml").read_text())
    assert b"<pdfaid:part>2</pdfaid:part><pdfaid:conformance>B</pdfaid:conformance>" in pdf
    title = re.search(rb'<dc:title><rdf:Alt><rdf:li xml:lang="x-default">(.*?)</rdf:li>', pdf).group(1)
    assert html.unescape(title.decode()) == meta["title"] and meta["title"].split()[0] in ("[Re]", "[¬Re]")
    assert int(re.search(rb"/Type/Pages/Count (\d+)", pdf).group(1)) >= 4
    source = (where / "article.typ").read_text(encoding="utf-8")
    assert source.count("#figure(image(") >= 5 and meta["type"] == "Replication"
    checks = read_netcdf(run[0] / "results/replication/checks.nc")
    paper = checks["group"].values == "paper"
    for value in (*checks["period"].values[paper], *checks["velocity"].values[paper]):
        assert f"{value:.12g}" in source
    assert f"{checks['multiplier'].values[paper][0]:.10g}" in source
    counts = re.search(r"replication: (\d+) of (\d+) findings reproduced",
                       (run[0] / "results/replication/docs/README.md").read_text()).groups()
    assert f"Of the {counts[1]} sentences the register quotes, {counts[0]} are reproduced" in meta["abstract"]


def test_a_value_changed_in_the_claims_table_changes_the_article(run, tmp_path):
    """One status flipped in the claims table: the article says the new one where it cites that row."""
    rows = read_claims(run[0] / "results/replication/claims.csv")
    row = next(r for r in rows if r["claim_id"] == "fig4_impulse_and_energy")
    was = row["status"]
    row["status"] = "not_reproduced" if was != "not_reproduced" else "reproduced"
    write_csv(rows, list(rows[0]), tmp_path / "claims.csv")
    written = {}
    for name, claims in (("before", run[0] / "results/replication/claims.csv"), ("after", tmp_path / "claims.csv")):
        outputs = {key: str(tmp_path / name / file) for key, file in (("pdf", "article.pdf"), ("metadata", "m.yaml"),
                   ("source", "article.typ"), ("bibliography", "article.bib"))}
        (tmp_path / name).mkdir()
        write_article({**article_inputs(run[0]), "claims": str(claims)}, outputs, str(tmp_path / name / "log"),
                      yaml.safe_load((run[0] / "config/paper.yaml").read_text()))
        written[name] = Path(outputs["source"]).read_text(encoding="utf-8")
    said = "can be evaluated from the graph is"
    assert f"{said}\n{was.replace('_', ' ')}." in written["before"].replace(" \n", "\n")
    assert f"{said}\n{row['status'].replace('_', ' ')}." in written["after"].replace(" \n", "\n")


SIMULATIONS = {"poincare_map", "shock_detail", "phase_diagrams", "escapement_error", "stability_map", "existence_map",
               "stability_map_chunk", "existence_map_chunk", "checks", "long_run", "readings", "work_precision",
               "run_stress"}
PLOTS = {"plot_poincare_map", "plot_shock_detail", "plot_phase_diagrams", "plot_escapement_error", "plot_stability_map",
         "plot_existence_map", "plot_long_run", "plot_work_precision"}
EVERY_JOB = SIMULATIONS | PLOTS | {"check_claims", "render_docs", "render_article"}


def traces(where: Path) -> Path:
    return where.with_name(f"{where.name}-trace")


def loaded(where: Path) -> dict[str, set[Path]]:
    """The files of the repository's copy each rule's jobs loaded, by rule (from the run's trace)."""
    found: dict[str, set[Path]] = {}
    for trace in traces(where).glob("*.txt"):
        modules = dict(line.split("\t", 1) for line in trace.read_text().split("\n") if line)
        files = {Path(f).resolve() for f in modules.values()}
        # the package known by its modules' names, wherever it is installed (not by a folder's name: a clone lives
        # in a folder named escapement, and so does its venv's site-packages)
        package = {name: Path(f).resolve() for name, f in modules.items() if name.split(".")[0] == "escapement"}
        assert package and all(where.resolve() / "src/escapement" in f.parents for f in package.values()), \
            f"{trace.name}: the job loaded the package from outside the copy"
        rule = trace.name.rsplit("-", 1)[0]
        found.setdefault(rule, set()).update(f for f in files if where.resolve() in f.parents)
    return found


def test_every_job_loads_only_code_that_the_rules_digest_covers(run):
    """Each job's process, traced: every file of the repository it loads is in the package, the workflow's scripts
    or the benchmarks' floors (escapement.pipeline.outputs.code_digest, a param of every rule), or is Snakemake's
    copy of the rule's script; the verdict's job loads no solver or integrator."""
    where = run[0].resolve()
    jobs = loaded(where)
    assert set(jobs) == EVERY_JOB
    covered = [where / "src/escapement", where / "workflow/scripts", where / "benchmarks", where / ".snakemake/scripts"]
    for rule, files in jobs.items():
        simulates = any(where / f"src/escapement/{layer}" in f.parents for f in files for layer in ("solvers",
                                                                                                    "integrators"))
        # the verdict reads the datasets and never simulates; every simulation job loads the solvers
        assert simulates is (rule != "check_claims") or rule.startswith(("plot_", "render")), rule
        outside = sorted(str(f.relative_to(where)) for f in files if not any(c in f.parents for c in covered))
        assert not outside, f"{rule} loads {outside}, which no rule's digest covers"


def test_an_edit_of_any_file_a_job_loads_changes_the_digest_of_every_rule(run, tmp_path):
    """Every file any job loaded, edited in turn (one byte appended) in a copy of the package: the digest changes."""
    from escapement.pipeline.outputs import code_digest

    where = run[0].resolve()
    files = sorted({f for found in loaded(where).values() for f in found if where / "src/escapement" in f.parents})
    assert len(files) >= 60
    package = shutil.copytree(where / "src/escapement", tmp_path / "escapement")
    before = code_digest(where, package)
    for file in files:
        copy = package / file.relative_to(where / "src/escapement")
        text = copy.read_bytes()
        copy.write_bytes(text + b"\n")
        assert code_digest(where, package) != before, file
        copy.write_bytes(text)
    assert code_digest(where, package) == before


@pytest.mark.parametrize("edit", ["src/escapement/__init__.py", "workflow/scripts/plot.py"])
def test_an_edit_replans_every_job(run, tmp_path, edit):
    """An edit of the package (its __init__, which the rules' hand-kept lists of layers once missed) or of a script
    replans every job: the digest every rule's params hold (each file a job loads changes it: the test above)."""
    where = Path(shutil.copytree(run[0], tmp_path / "copy", symlinks=True))
    assert (where / edit).is_file(), edit  # an edit, not a new file
    with open(where / edit, "a") as handle:
        handle.write("\n# an edit\n")
    assert set(planned_jobs(where)) - {"all"} == EVERY_JOB


def test_a_deleted_output_is_made_again_by_a_plain_run(run, tmp_path):
    where = Path(shutil.copytree(run[0], tmp_path / "copy", symlinks=True))
    (where / "results/replication/long_run.nc").unlink()
    (where / "results/replication/poincare_map/case_b.nc").unlink()
    (where / "results/replication/readings.csv").unlink()
    (where / "results/replication/docs/verdict.html").unlink()  # an output beside the job's target, README.md
    (where / "results/replication/figures/long_run.pdf").unlink()
    planned = planned_jobs(where)
    assert planned["long_run"] == 1 and planned["poincare_map"] == 1 and planned["readings"] == 1
    assert planned["render_docs"] == 1 and planned["plot_long_run"] == 1


@pytest.mark.parametrize("config, planned, said", [
    # the escapement error sets a3 = -a1, a4 = -a2 from its zones; the existence map's axis is a3
    ("model={a3: 0.12, a4: -0.03}", {"poincare_map": 2, "shock_detail": 1, "phase_diagrams": 3, "stability_map": 1,
                                     "stability_map_chunk": 1, "existence_map": 1, "existence_map_chunk": 1},
     "your study 'own': escapement_error does not run: its zones set a1 and a2"),
    ("model={F: 2.0}", {}, "does not run: nothing you changed (model.F = 2 N (paper: absent)) reaches a scene"),
])
def test_a_study_runs_only_the_kinds_its_changes_reach_and_says_why_of_the_others(run, config, planned, said):
    result = snakemake(run[0], "--dry-run", "--cores", "2", "--config", config)
    jobs = {m[0]: int(m[1]) for m in re.findall(r"^(\w+)\s+(\d+)\s*$", result.stdout, re.M)
            if m[0] not in ("job", "all", "total") and not m[0].startswith("plot_")}
    assert jobs == planned
    assert said is None or said in result.stderr


def test_a_target_no_rule_makes_is_refused_in_one_line_naming_what_the_study_draws(run):
    result = snakemake(run[0], "--dry-run", "--cores", "2", "results/replication/figures/fig3.png", check=False)
    said = [line for line in result.stderr.splitlines() if "fig3.png" in line]
    assert result.returncode == 1 and len(said) == 1 and "Traceback" not in result.stderr
    assert said[0].startswith("results/replication/figures/fig3.png is not made by this configuration (the paper's "
                              "Fig. 3 is drawn as poincare_map.png")
    result = snakemake(run[0], "--dry-run", "--cores", "2", "results/own/figures/phase_diagrams.png", "--config",
                       "fig3={n_cycles: 20}", check=False)
    assert result.returncode == 1 and "Traceback" not in result.stderr + result.stdout
    assert "the study 'own' draws poincare_map (each as .png, .pdf and .svg)" in result.stderr


@pytest.mark.parametrize("config, message", [
    ("model={M: 0}", "the configuration: model.M = 0.0 is invalid: M must be > 0 (kg)"),
    ("escapement_error={F:0.7}", "the configuration: escapement_error: unknown key 'F:0.7' (a flow mapping needs a "
                                 "space after each colon: {F: 0.7})"),
])
def test_an_invalid_configuration_stops_before_any_job_in_one_line(run, config, message):
    """Each refusal's words are tested on the configuration's functions (tests/pipeline/test_config.py); here,
    that Snakemake stops on one before planning any job, a --config entry read as a file's."""
    result = snakemake(run[0], "--dry-run", "--cores", "2", "--config", config, check=False)
    assert result.returncode != 0 and "Job stats" not in result.stdout
    assert [line for line in (result.stdout + result.stderr).splitlines() if "the configuration" in line] == [message]


def test_the_jobs_of_seconds_run_beside_snakemake_and_every_simulation_goes_to_the_executor(tmp_path):
    """On a cluster (profiles/slurm) the plots and the documents' jobs are local rules, as the README says; a
    rule made by ``use rule ... with`` does not inherit the flag, so each states it. Read in process, from a copy
    (Snakemake starts a log file in its working directory)."""
    where = copy_repository(tmp_path)
    with SnakemakeApi(OutputSettings(quiet={"all"})) as api:
        workflow = api.workflow(resource_settings=ResourceSettings(cores=1), snakefile=where / "Snakefile",
                                workdir=where)._workflow
        rules = {rule.name for rule in workflow.rules if not rule.norun}
        local = set(workflow._localrules)
        digests = {rule.name: rule.params.get("code") for rule in workflow.rules if not rule.norun}
    from escapement.pipeline.outputs import code_digest

    # and every rule that runs code holds the digest of it all in its params (the package as the jobs load it)
    assert digests == dict.fromkeys(rules - {"publish"}, code_digest(where, where / "src/escapement")) | {
        "publish": None}
    assert local == {rule for rule in rules if rule.startswith("plot_")} | {"check_claims", "render_docs",
                                                                          "render_article", "publish"}
