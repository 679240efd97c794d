import datetime as dt

import numpy as np

import escapement
from escapement.io.dataset import (
    MODEL_SUMMARY,
    cycle_variables,
    dataset,
    event_variables,
    impact_variables,
    parameter_variables,
    sample_times,
    sample_variables,
)
from escapement.io.provenance import DOI
from escapement.model.parameters import Parameters
from escapement.solvers.exact import solve_exact


def test_every_variable_has_units_and_a_long_name(case_b):
    run = solve_exact(case_b, 3.0, n_cycles=5)
    variables = {**cycle_variables(run), **impact_variables(run), **sample_variables(run, np.linspace(0, 5, 11), True)}
    variables.update(event_variables(run))
    for name, da in variables.items():
        assert "long_name" in da.attrs, name
        assert "units" in da.attrs or "flag_values" in da.attrs, name


def test_attributes_carry_outcome_and_provenance_and_variables_the_parameters(case_a):
    run = solve_exact(case_a, 1.0, n_cycles=3)
    ds = dataset(run, cycle_variables(run), title="t", scene="fig3", summary="This file holds a test.")
    assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
    assert DOI in ds.attrs["references"]
    assert ds.attrs["source"].startswith("escapement ")
    assert "git commit" in ds.attrs["source"]
    for key, value in case_a.as_dict().items():
        assert ds[key].ndim == 0 and float(ds[key]) == value
        assert key not in ds.attrs
    assert ds.attrs["outcome"] == "completed" and float(ds["x0"]) == 1.0 and float(ds["v0"]) == 0.0


def test_the_parameters_are_0d_variables_with_their_units_and_long_names():
    variables = parameter_variables({"M": 2.0, "K": 3.0, "F": 0.5, "b": 0.2, "a1": -0.1, "x0": 1.5, "v0": -0.25})
    units = {name: da.attrs["units"] for name, da in variables.items()}
    assert units == {"M": "kg", "K": "N m-1", "F": "N", "b": "1", "a1": "m", "x0": "m", "v0": "m s-1"}
    assert variables["K"].attrs["long_name"] == "spring constant"
    assert variables["b"].attrs["long_name"] == "impact coefficient (v+ = (1 - b) v-)"
    assert all(da.ndim == 0 for da in variables.values())
    assert float(variables["v0"]) == -0.25
    assert {da.attrs["coverage_content_type"] for da in variables.values()} == {"auxiliaryInformation"}
    assert all("standard_name" not in da.attrs for da in variables.values())  # CF has none for these


def test_the_global_attributes_follow_acdd(case_a):
    run = solve_exact(case_a, 1.0, n_cycles=3)
    ds = dataset(run, cycle_variables(run), title="A title", scene="fig3", summary="This file holds a test.")
    a = ds.attrs
    assert a["title"] == "A title"
    assert a["summary"] == MODEL_SUMMARY + " This file holds a test."
    assert "v+ = (1 - b) v-" in a["summary"] and "[a1, a2]" in a["summary"] and "[a4, a3]" in a["summary"]
    assert "escapement mechanism" in a["keywords"].split(", ")
    assert a["license"] == "CC-BY-4.0"
    assert a["creator_name"] == "escapement replication contributors" and a["creator_type"] == "group"
    assert "https://doi.org/10.3233/SAV-130800" in a["references"]
    assert a["product_version"] == escapement.__version__
    created = dt.datetime.fromisoformat(a["date_created"])
    assert created.tzinfo is not None
    assert abs(dt.datetime.now(dt.timezone.utc) - created) < dt.timedelta(minutes=5)
    assert a["history"].endswith("created by escapement for scene fig3")


def test_every_variable_has_a_coverage_content_type(case_b):
    run = solve_exact(case_b, 3.0, n_cycles=3)
    variables = {**sample_variables(run, np.linspace(0, 5, 11)), **cycle_variables(run), **event_variables(run)}
    ds = dataset(run, variables, title="t", scene="fig5", summary="s")
    content = {name: ds[name].attrs["coverage_content_type"] for name in ds.variables}
    assert content["t"] == content["cycle"] == "coordinate"
    assert content["event_kind"] == "thematicClassification"
    assert content["velocity"] == content["period"] == "modelResult"
    assert content["F"] == content["x0"] == "auxiliaryInformation"


def test_sample_times_add_a_sample_on_each_side_of_each_jump():
    below = np.nextafter
    t = sample_times(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.5, 2.0, 0.0, 5.0]))
    # 1.5: both sides added; 2.0 on the grid: the sample below it added; 0.0 at the start: nothing below it;
    # 5.0 outside the grid: nothing
    assert t.tolist() == [0.0, 1.0, below(1.5, 0.0), 1.5, below(2.0, 0.0), 2.0, 3.0]
    assert np.all(np.diff(t) > 0)


def test_sample_times_keep_the_grid_without_jumps():
    grid = np.linspace(80.0, 87.0, 8)
    assert sample_times(grid, np.array([])).tolist() == grid.tolist()


def test_impulse_and_dissipated_energy_follow_the_impact_law():
    p = Parameters(M=2.0, K=1.0, F=0.5, b=0.2, a1=-0.1, a2=0.05)
    run = solve_exact(p, 3.0, n_cycles=3)
    imp = impact_variables(run)
    vb = imp["velocity_before"].values
    assert np.allclose(imp["impulse"].values, -2.0 * 0.2 * vb, rtol=1e-14)
    assert np.allclose(imp["energy_dissipated"].values, 0.5 * 2.0 * vb**2 * (1 - 0.8**2), rtol=1e-14)
    assert np.all(np.isin(imp["impact_position"].values, [-0.1, 0.1]))

