"""The replication's own runs: the claims register's (one row per case of the table, its columns by value against
hand derivations; the runs of another measure under their names) and the long run's settings."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from escapement.model.parameters import ParameterError
from escapement.model.quantities import MODEL_KEYS
from escapement.pipeline.config import ConfigError
from escapement.pipeline.plan import check_runs
from escapement.scenes.probes import MEASURES
from escapement.scenes.runs import checks, long_run

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}


def test_one_row_per_case_with_the_limit_cycle_measured_by_value():
    cases = [{"group": "force", "label": "a", **MODEL, "F": 1.0, "x0": -1.0},
             {"group": "b", "label": "b=0.5", **MODEL, "b": 0.5, "F": 0.5, "x0": 3.0}]
    ds = checks(cases, 200)
    assert ds.sizes["case"] == 2 and ds["label"].values.tolist() == ["a", "b=0.5"]
    assert set(MODEL_KEYS) <= set(ds.variables) and ds["a3"].values.tolist() == [0.1, 0.1]  # symmetric default
    # the limit cycle of the paper's case: the largest speed is at a2, v2^2 = 0.81 * 0.3/0.19 + 0.3075 (hand
    # derivation in tests/paper/test_floquet_and_speed.py); the multipliers 1 and (1 - b)^4 = 0.6561
    assert float(ds["largest_speed"][0]) == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)
    assert float(ds["floquet_major"][0]) == pytest.approx(1.0, abs=1e-8)
    assert float(ds["floquet_minor"][0]) == pytest.approx(0.6561, abs=1e-8)
    assert float(ds["multiplier"][1]) == pytest.approx(0.5**4, abs=1e-8)
    assert ds["cycles_to_converge"].dtype == np.int32 and ds["first_period"].attrs["units"] == "s"


def test_a_run_continued_past_an_accumulation_of_impacts_says_when_it_first_did():
    """b = 1.5 from rest at -1 m: the first impact at a1 at acos(0.1) s reverses the velocity to 0.5 sqrt(0.99) m/s;
    the flights from a1 and back last 2 atan(u / 0.1) s, u halved at each rebound. Stopped there, the run chatters."""
    cases = [{"group": "b", "label": label, **MODEL, "b": 1.5, "F": 1.0, "x0": -1.0, "past_accumulation": label}
             for label in ("stop", "continue")]
    ds = checks(cases, 2)
    t_acc = math.acos(0.1) + sum(2 * math.atan(0.5**n * 0.5 * math.sqrt(0.99) / 0.1) for n in range(200))
    assert ds["outcome"].values.tolist() == ["chattering", "completed"]
    assert ds["past_accumulation"].values.tolist() == ["stop", "continue"] and ds["continued_at"].attrs["units"] == "s"
    assert np.isnan(ds["continued_at"][0]) and float(ds["continued_at"][1]) == pytest.approx(t_acc, rel=1e-12)


def test_a_bad_case_or_count_is_refused_before_any_run():
    with pytest.raises(ParameterError, match="^n_cycles = "):
        checks([], 0)
    with pytest.raises(ParameterError, match="^F = "):
        checks([{"group": "g", "label": "l", **MODEL, "x0": 1.0}], 5)


@pytest.mark.parametrize("name, value", [("n_cycles", 0), ("ivp_cycles", 1.5)])
def test_the_long_run_refuses_a_count_that_is_not_a_positive_integer(name, value):
    settings = {**MODEL, "F": 1.0, "x0": -1.0, "n_cycles": 2000, "ivp_method": "DOP853", "ivp_rtol": 1e-12,
                "ivp_cycles": 10, name: value}
    with pytest.raises(ParameterError, match=f"^{name} = "):
        long_run(settings)


def test_the_runs_of_another_measure_under_their_names_by_value():
    """The paper's case (a) (w = 1): from rest at -1 m the first impact at a1 comes at sqrt(1 - a1^2); the return
    map's slope is Eq. (20), 0.6561 x / sqrt(0.6561 x^2 + 0.543 F); the runs from the section at the converged
    speed and 1 % above it agree in speed after 100 cycles and keep their impact times -0.000848 s apart (the
    referee's simulator, in 40-digit arithmetic, finds -0.000848 s). Each under its name, with its settings."""
    case = {**MODEL, "a3": 0.1, "a4": -0.05, "F": 1.0, "x0": -1.0, "case": "a"}

    def named(measure: str, *runs: dict) -> dict:
        return {"measure": measure, "runs": [{**case, "label": str(i), **r} for i, r in enumerate(runs)]}

    ds = checks([], 1, {"swings": named("release", {"n_cycles": 1}, {"x0": -3.0, "n_cycles": 1}),
                        "slopes": named("return_map", {"velocity": 0.5}, {"velocity": 2.0}),
                        "shift": named("from_section", *({"n_cycles": 50, "perturbation": p, "section_cycles": 100}
                                                         for p in (0.0, 0.01)))})
    assert ds["swings_velocity"].values == pytest.approx([math.sqrt(0.99), math.sqrt(8.99)], rel=1e-12)
    assert ds["swings_outcome"].values.tolist() == ["completed"] * 2 and ds["swings_x0"].values.tolist() == [-1, -3]
    assert ds["swings_velocity"].dims == ("swings_run",) and ds["swings_case"].values.tolist() == ["a", "a"]
    slope = [0.6561 * v / math.sqrt(0.6561 * v * v + 0.543) for v in (0.5, 2.0)]
    assert ds["slopes_slope"].values == pytest.approx(slope, rel=1e-9)
    times = ds["shift_impact_time"].values
    assert ds["shift_impact_time"].dims == ("shift_run", "shift_impact") and np.isfinite(times).all()
    assert ds["shift_perturbation"].values.tolist() == [0.0, 0.01]
    assert times[1, -1] - times[0, -1] == pytest.approx(-0.000848, abs=5e-7)
    speeds = ds["shift_speed"].values
    assert abs(speeds[1] - speeds[0]) <= 1e-8 * speeds[0]
    assert ds["shift_converged_speed"].values == pytest.approx([math.sqrt(0.3 / 0.19)] * 2, rel=1e-8)


@pytest.mark.parametrize("spec, message", [
    ({"measure": "slope", "runs": [{}]}, "checks.r: measure = 'slope' with 1 runs is invalid: "),
    ({"measure": "release", "runs": [{**MODEL, "F": 1.0, "x0": 1.0, "label": "l"}]}, "checks.r: a run has no n_cycles"),
])
def test_a_named_run_of_no_measure_or_without_its_settings_is_refused_before_any_run(spec, message):
    with pytest.raises(ValueError, match=f"^{message}"):
        checks([{"group": "g", "label": "l", **MODEL, "F": 1.0, "x0": 1.0}], 100_000, {"r": spec})


def test_the_measures_are_those_the_configuration_s_schema_names():
    schema = yaml.safe_load((Path(__file__).parents[2] / "workflow/schemas/config.schema.yaml").read_text())
    assert schema["$defs"]["checks"]["$defs"]["run"]["properties"]["measure"]["enum"] == list(MEASURES)


def test_the_checks_block_states_every_run_and_each_derivation_once_by_value():
    """The runs the checks block of config/paper.yaml plans: the table's groups by their names, a run derived from
    another block (the Fig. 3 cases, Fig. 5's springs at its forces, Fig. 4's grid, Fig. 3's cycle count), a release
    either side and at the grazing one; a case the fig3 block lacks refused, naming the run."""
    paper = yaml.safe_load((Path(__file__).parents[2] / "config/paper.yaml").read_text())
    planned = check_runs(paper)
    assert dict.fromkeys(c["group"] for c in planned["cases"]) == dict.fromkeys(
        ["paper", "initial_conditions", "b", "b_continued", "symmetric", "asymmetric", "common_force", "releases",
         "forces"])
    assert [(c["label"], c["F"], c["x0"]) for c in planned["cases"] if c["group"] == "paper"] == [
        ("fig3a", 1.0, -1.0), ("fig3b", 0.5, -3.0)]
    assert [(c["F"], c["K"], c["x0"]) for c in planned["cases"] if c["group"] == "common_force"] == [
        (F, K, -1.0) for F in (0.5, 1.0) for K in (0.1, 1.0, 10.0)]
    symmetric = next(c for c in planned["cases"] if c["label"] == "F=1,a1=-0.3,a2=0.2")
    assert (symmetric["a3"], symmetric["a4"], symmetric["x0"]) == (0.3, -0.2, 1.0)  # a pair mirrored; the table's x0
    runs = {name: spec["runs"] for name, spec in planned["probes"].items()}
    assert [(r["case"], r["x0"]) for r in runs["first_swings"]] == [("a", -1.0), ("a", 1.0), ("b", -3.0), ("b", 3.0)]
    assert [r["n_cycles"] for r in runs["phase_shift"]] == [paper["fig3"]["n_cycles"]] * 2
    assert [(r["F"], r["K"], r["x0"], r["t_end"]) for r in runs["windows"]][:3] == [
        (0.5, 0.1, -1.0, 87.0), (0.5, 0.1, 1.0, 87.0), (0.5, 0.1, -3.0, 87.0)] and len(runs["windows"]) == 24
    # A^2 = 0.01 + (0.09 - 0.01 - 0.03) / 0.81, released at -A (1 + offset)
    edge = math.sqrt(0.01 + 0.05 / 0.81)
    assert [r["x0"] for r in runs["grazing"][:2]] == pytest.approx([-edge * 1.0001, -edge * 0.9999], rel=1e-14)
    paper["checks"]["first_swings"]["case"] = ["a", "c"]
    with pytest.raises(ConfigError, match=r"^config/paper.yaml: checks.first_swings: case 'c' is invalid: a case "
                                          "must be one of fig3.cases, one of a, b$"):
        check_runs(paper)
