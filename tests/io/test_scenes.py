"""The datasets of the scenes: each describes itself (units, long names, ACDD attributes, no wall
time), holds the model as 0-d variables, and keeps a sample on each side of every jump it shows.
The datasets are made as the workflow makes them: the experiment's run, then io's dataset
(:mod:`escapement.pipeline.simulate`)."""

import re

import numpy as np
import pytest

from escapement.io.netcdf import read_netcdf, write_netcdf
from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.quantities import INITIAL_STATE, PARAMETERS
from escapement.pipeline.simulate import (
    checks_scene,
    long_run_scene,
    phase_scene,
    poincare_scene,
    shock_scene,
    stability_chunk_scene,
)
from escapement.pipeline.tables import merge_stability, write_timings
from escapement.plotting.paper_figures import fig4

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "F": 0.0, "a1": -0.1, "a2": 0.05}


def test_poincare_scene_holds_no_trajectory(case_a):
    ds = poincare_scene(case_a, 1.0, 50)
    assert set(ds.dims) == {"cycle", "event", "amplitude_cycle"}
    assert ds.sizes["cycle"] == 50
    assert ds["cycle"].values[0] == 1


def test_poincare_scene_names_its_amplitude(case_a):
    ds = poincare_scene(case_a, -1.0, 5, "amplitude_h0")
    step1 = ds["amplitude_h0"]
    assert step1.sizes["amplitude_cycle"] == 6 and ds.attrs["amplitude_variable"] == "amplitude_h0"
    assert step1["amplitude_cycle"].values.tolist() == list(range(1, 7)) and step1.attrs["units"] == "m"


def test_shock_scene_holds_its_windows_and_the_impacts_inside_them(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 100)
    assert ds["t"].values[0] == 80.0 and ds["t"].values[-1] == 87.0
    assert ds["velocity_window"].values.tolist() == [80.0, 87.0]
    assert ds["acceleration_window"].values.tolist() == [81.0, 85.0] and float(ds["samples_per_second"]) == 100
    assert np.all((ds["impact_time"] >= 80) & (ds["impact_time"] <= 87))
    assert np.all((ds["event_time"] >= 80) & (ds["event_time"] <= 87))
    assert np.all(np.isfinite(ds["velocity"]))


def test_phase_scene_resolution_follows_the_natural_period(case_b):
    ds = phase_scene(case_b, 3.0, 5, 100)
    dt = float(ds["t"][1] - ds["t"][0])
    assert dt <= case_b.natural_period / 100
    assert ds.sizes["cycle"] == 5


def test_a_stopped_motion_is_recorded_not_raised(case_a):
    ds = phase_scene(case_a, 0.05, 5, 50)
    assert ds.attrs["outcome"] == "stopped"
    assert "escapement stopped" in ds.attrs["outcome_message"]
    assert ds.sizes["cycle"] == 0


def _scenes(case_b):
    """One dataset of each kind the workflow writes (small)."""
    fast = Parameters(M=1.0, K=1.0, F=1.0, b=0.9, a1=-0.1, a2=0.05)  # converges in a few cycles
    case = {"group": "paper", "label": "a", **MODEL, "F": 1.0, "x0": 1.0}
    return {
        "fig3": poincare_scene(case_b, 3.0, 5),
        "fig4": shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 20),
        "fig5": phase_scene(case_b, 3.0, 3, 20),
        "checks": checks_scene([case], 20),
        "long_run": long_run_scene(fast, 1.0, 50, "DOP853", 1e-8, 5)[0],
        "stability_map": stability_chunk_scene(MODEL, [0.3, 0.6], [0.5, 1.0], speed_sample=2)[0],
    }


def test_every_scene_describes_itself(case_b):
    for scene, ds in _scenes(case_b).items():
        for name, variable in ds.variables.items():
            text = variable.dtype == object
            assert "long_name" in variable.attrs, (scene, name)
            assert text or "units" in variable.attrs or "flag_values" in variable.attrs, (scene, name)
            assert "coverage_content_type" in variable.attrs, (scene, name)
        assert not set(ds.attrs) & (set(PARAMETERS) | set(INITIAL_STATE)), scene
        assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
        for key in ("title", "summary", "keywords", "license", "creator_name", "date_created", "product_version"):
            assert ds.attrs[key], (scene, key)
        assert "v+ = (1 - b) v-" in ds.attrs["summary"] and "This file holds" in ds.attrs["summary"]
        assert "https://doi.org/10.3233/SAV-130800" in ds.attrs["references"]
        names = [*ds.variables, *ds.attrs]
        assert not [n for n in names if re.search("wall|seconds|timing", n)], scene  # no wall times


def test_every_scalar_parameter_has_units_and_a_long_name(case_b):
    for scene, ds in _scenes(case_b).items():
        for name in set(ds.variables) & (set(PARAMETERS) | set(INITIAL_STATE)):
            if ds[name].ndim == 0:
                assert ds[name].attrs["units"] and ds[name].attrs["long_name"], (scene, name)
    ds = poincare_scene(case_b, 3.0, 5)
    assert [float(ds[k]) for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4", "x0", "v0")] == [
        1.0, 1.0, 0.5, 0.1, -0.1, 0.05, 0.1, -0.05, 3.0, 0.0
    ]
    assert ds["K"].attrs["units"] == "N m-1" and ds["F"].attrs["units"] == "N"


def test_fig5_holds_its_spring_constant_as_a_scalar():
    ds = phase_scene(Parameters(M=1.0, K=10.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 1.0, 3, 20)
    assert ds["K"].ndim == 0 and float(ds["K"]) == 10.0 and "K" not in ds.attrs


def test_the_stability_map_holds_no_scalar_contradicting_its_axes(tmp_path):
    paths, timings = [], []
    for i, b in enumerate(([0.3, 0.6], [0.9, 1.2])):
        ds, timing = stability_chunk_scene(MODEL, b, [0.5, 1.0, 2.0], speed_sample=2)
        assert ds["b"].dims == ("b",) and ds["F"].dims == ("F",)
        paths.append(write_netcdf(ds, tmp_path / f"chunk_{i}.nc"))
        timings.append(tmp_path / f"chunk_{i}.csv")
        write_timings(timing, timings[-1])
    merge_stability(paths, timings, str(tmp_path / "map.nc"), str(tmp_path / "timing.csv"), str(tmp_path / "log"))
    merged = read_netcdf(tmp_path / "map.nc")
    assert merged["b"].values.tolist() == [0.3, 0.6, 0.9, 1.2] and merged["F"].values.tolist() == [0.5, 1.0, 2.0]
    assert not {"b", "F"} & set(merged.attrs)
    assert merged["multiplier"].dims == ("b", "F")
    # the other parameters are constants of the map; a3 and a4 take the symmetric default
    assert {k: float(merged[k]) for k in ("M", "K", "a1", "a2", "a3", "a4")} == {
        "M": 1.0, "K": 1.0, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05
    }
    assert all(merged[k].ndim == 0 for k in ("M", "K", "a1", "a2", "a3", "a4"))
    assert merged.attrs["chunks"] == 2 and "merged from 2 chunks" in merged.attrs["history"]


def _jumps_sampled_on_both_sides(ds, times, before, after):
    """At each jump time inside the samples: a sample at it and one at the largest float below it,
    with the values ``after`` and ``before`` the jump (a jump at the last sample ends the run: no arc
    follows it)."""
    t, v = ds["t"].values, ds["velocity"].values
    assert np.all(np.diff(t) > 0)
    checked = 0
    for tk, vb, va in zip(times, before, after):
        if not t[0] < tk < t[-1]:
            continue
        i = np.searchsorted(t, tk)
        assert t[i] == tk and t[i - 1] == np.nextafter(tk, -np.inf)
        assert v[i] == va  # the arc from the impact starts with the velocity after it
        assert v[i - 1] == pytest.approx(vb, rel=1e-9, abs=1e-12)  # the arc before it, one float earlier
        checked += 1
    return checked


def test_fig4_samples_both_sides_of_each_jump(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 20)
    impacts = _jumps_sampled_on_both_sides(
        ds, ds["impact_time"].values, ds["velocity_before"].values, ds["velocity_after"].values
    )
    assert impacts == ds.sizes["impact"] >= 2
    # the acceleration jumps at every event (impacts and ends of the impulse zones): both sides sampled
    events = _jumps_sampled_on_both_sides(
        ds, ds["event_time"].values, ds["event_velocity_before"].values, ds["event_velocity_after"].values
    )
    assert events == ds.sizes["event"] > impacts
    a, t = ds["acceleration"].values, ds["t"].values
    ends = ds["event_time"].values[ds["event_kind"].values == int(EventKind.ZONE_END_A2)]
    assert len(ends) >= 1
    for tk in ends:  # the force F switches off at a2: the acceleration drops by F / M = 0.5 m/s2
        i = np.searchsorted(t, tk)
        assert a[i - 1] - a[i] == pytest.approx(0.5, rel=1e-9)


def test_fig5_samples_both_sides_of_each_impact(case_b):
    ds = phase_scene(case_b, 3.0, 5, 20)
    n = _jumps_sampled_on_both_sides(
        ds, ds["impact_time"].values, ds["velocity_before"].values, ds["velocity_after"].values
    )
    # every impact but the last, which ends cycle 5 and the run (the last sample)
    assert ds["impact_time"].values[-1] == ds["t"].values[-1]
    assert n == ds.sizes["impact"] - 1 >= 10


def test_fig4_still_draws_each_jump_as_a_jump(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 20)
    line = fig4(ds).axes[0].lines[0]
    x, y = line.get_xdata(), line.get_ydata()
    for tk in ds["impact_time"].values:
        i = int(np.flatnonzero(x == tk)[0])
        assert np.isnan(y[i - 1]) and x[i - 2] == np.nextafter(tk, -np.inf)  # the line stops below t_k...
        assert np.isfinite(y[i]) and np.isfinite(y[i - 2])  # ...and starts again at t_k
