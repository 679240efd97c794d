"""The CF datasets of a run: its variables, their units and long names, the global attributes (the provenance
added when the file is written), and one run as a dataset (:func:`escapement.scenes.run_dataset`)."""

import datetime as dt

import numpy as np
import pytest
import xarray as xr

import escapement
from escapement.scenes.cf import (
    DOI,
    MODEL_SUMMARY,
    cycle_variables,
    dataset,
    event_variables,
    impact_variables,
    parameter_variables,
    run_dataset,
    sample_variables,
)
from escapement.io.netcdf import read_netcdf, write_netcdf
from escapement.model.parameters import Parameters
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision


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


def test_the_global_attributes_follow_acdd_with_the_provenance_of_the_writer(case_a, tmp_path):
    run = solve_exact(case_a, 1.0, n_cycles=3)
    ds = dataset(run, cycle_variables(run), title="A title", scene="fig3", summary="This file holds a test.")
    a = read_netcdf(write_netcdf(ds, tmp_path / "a.nc", history="a test wrote it")).attrs
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
    assert a["history"].endswith(": a test wrote it") and a["source"].startswith(f"escapement {escapement.__version__}")


def test_every_variable_has_a_coverage_content_type(case_b):
    run = solve_exact(case_b, 3.0, n_cycles=3)
    variables = {**sample_variables(run, np.linspace(0, 5, 11)), **cycle_variables(run), **event_variables(run)}
    ds = dataset(run, variables, title="t", scene="fig5", summary="s")
    content = {name: ds[name].attrs["coverage_content_type"] for name in ds.variables}
    assert content["t"] == content["cycle"] == "coordinate"
    assert content["event_kind"] == "thematicClassification"
    assert content["velocity"] == content["period"] == "modelResult"
    assert content["F"] == content["x0"] == "auxiliaryInformation"


def test_impulse_and_dissipated_energy_follow_the_impact_law():
    p = Parameters(M=2.0, K=1.0, F=0.5, b=0.2, a1=-0.1, a2=0.05)
    run = solve_exact(p, 3.0, n_cycles=3)
    imp = impact_variables(run)
    vb = imp["velocity_before"].values
    assert np.allclose(imp["impulse"].values, -2.0 * 0.2 * vb, rtol=1e-14)
    assert np.allclose(imp["energy_dissipated"].values, 0.5 * 2.0 * vb**2 * (1 - 0.8**2), rtol=1e-14)
    assert np.all(np.isin(imp["impact_position"].values, [-0.1, 0.1]))


# --- run_dataset --------------------------------------------------------------------------------


def test_run_dataset_round_trips_through_the_netcdf_writer_with_units_everywhere(run50, tmp_path):
    ds = run_dataset(run50)
    path = write_netcdf(ds, tmp_path / "run.nc")
    back = read_netcdf(path)
    xr.testing.assert_identical(back.drop_attrs(deep=False).assign_attrs(ds.attrs), ds)
    without_units = {name for name, variable in back.variables.items() if "units" not in variable.attrs}
    assert without_units == {"event_kind"}  # a CF flag variable: flag_values and flag_meanings, no units
    assert "flag_values" in back["event_kind"].attrs
    assert all("long_name" in variable.attrs for variable in back.variables.values())


def test_run_dataset_holds_the_solution_s_arrays_and_outcome(run50):
    ds = run_dataset(run50)
    np.testing.assert_array_equal(ds["period"].values, run50.cycles.period)
    np.testing.assert_array_equal(ds["velocity_before_impact"].values, run50.cycles.velocity_before_impact)
    np.testing.assert_array_equal(ds["cycle"].values, np.arange(1, 51))
    np.testing.assert_array_equal(ds["event_time"].values, run50.events.t)
    np.testing.assert_array_equal(ds["event_kind"].values, run50.events.kind)
    assert float(ds["t_final"]) == run50.t_final
    assert {name: ds[name].attrs["units"] for name in ("period", "velocity_before_impact", "K", "x0", "t_final")} == {
        "period": "s", "velocity_before_impact": "m s-1", "K": "N m-1", "x0": "m", "t_final": "s"}
    assert float(ds["F"]) == 1.0 and float(ds["x0"]) == 1.0 and float(ds["a3"]) == 0.1
    assert ds.attrs["outcome"] == "completed" and ds.attrs["solver"] == "exact"
    assert ds.attrs["outcome_message"] == "completed 50 cycles"
    assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
    assert np.isnan(float(ds["exit_margin"]))


def test_run_dataset_of_a_stopped_run_keeps_the_exit_and_an_infinite_end(stopped, tmp_path):
    back = read_netcdf(write_netcdf(run_dataset(stopped), tmp_path / "stopped.nc"))
    assert back.sizes["cycle"] == 0 and back.sizes["event"] == 0
    assert float(back["t_final"]) == np.inf
    assert float(back["exit_turning_point"]) == 0.01
    assert float(back["exit_margin"]) == pytest.approx(0.1 - 0.01, abs=1e-15)
    assert back.attrs["outcome"] == "stopped"


def test_run_dataset_of_a_high_precision_run_stores_the_nearest_doubles(tmp_path):
    p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    hp = solve_high_precision(p, 1.0, n_cycles=2, dps=20)
    back = read_netcdf(write_netcdf(run_dataset(hp), tmp_path / "hp.nc"))
    assert back["period"].dtype == np.float64
    assert back["period"].values.tolist() == [float(x) for x in hp.cycles.period]
    assert back["event_velocity_after"].values.tolist() == [float(x) for x in hp.events.v_after]


def test_a_run_s_data_frames_have_the_names_units_and_long_names_of_its_dataset(run50):
    ds = run_dataset(run50)
    for table in ("cycles", "events"):
        frame = run50.to_dataframe(table)
        for name in frame.columns:
            np.testing.assert_array_equal(frame[name].to_numpy(), ds[name].values)
            assert frame.attrs["long_names"][name] == ds[name].attrs["long_name"]
            assert frame.attrs["units"].get(name) == ds[name].attrs.get("units")


def test_run_dataset_is_exported_by_scenes():
    import escapement.scenes

    assert escapement.scenes.run_dataset is run_dataset and "run_dataset" in dir(escapement.scenes)


def test_samples_are_in_the_units_of_their_quantities_and_follow_the_free_swing(run50):
    """Before the first impact (at a3 = 0.1 m, t = acos(0.1) = 1.47 s) the mass swings freely from rest at
    1 m with w = 1 rad/s: x = cos t (m), v = -sin t (m/s), a = -cos t (m/s2), written out here."""
    from cf_units import Unit

    t = np.array([0.0, 0.5, 1.0, 1.4])
    sampled = sample_variables(run50, t, acceleration=True)
    expected = {"displacement": (np.cos(t), "m"), "velocity": (-np.sin(t), "m/s"), "acceleration": (-np.cos(t), "m/s2")}
    assert set(sampled) == set(expected)
    for name, (values, dimension) in expected.items():
        assert sampled[name].values == pytest.approx(values, rel=1e-14, abs=1e-15), name
        units = Unit(sampled[name].attrs["units"])
        assert units.is_convertible(dimension) and units.convert(1.0, dimension) == pytest.approx(1.0), name
    assert sampled["displacement"]["t"].attrs["units"] == "s"
    assert "acceleration" not in sample_variables(run50, t)


def test_impact_variables_are_in_the_units_of_their_quantities():
    """The impulse M (v+ - v-) in N s, the energy dissipated in J, velocities in m/s, the impact position in m."""
    from cf_units import Unit

    run = solve_exact(Parameters(M=2.0, K=1.0, F=0.5, b=0.2, a1=-0.1, a2=0.05), 3.0, n_cycles=3)
    dimensions = {"impulse": "N s", "energy_dissipated": "J", "velocity_before": "m/s", "velocity_after": "m/s",
                  "impact_position": "m", "impact_time": "s"}
    imp = impact_variables(run)
    assert set(dimensions) <= set(imp)
    for name, dimension in dimensions.items():
        units = Unit(imp[name].attrs["units"])
        assert units.is_convertible(dimension) and units.convert(1.0, dimension) == pytest.approx(1.0), name
