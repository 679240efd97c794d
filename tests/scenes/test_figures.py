"""The scenes of the paper's kinds of figure: what each dataset keeps, how it is sampled, how it is titled for
the replication and for a study of the user's own, and the settings each refuses before any run."""

import numpy as np
import pytest

from escapement.model.parameters import ParameterError
from escapement.scenes.figures import phase_diagram, poincare_map, sample_times, shock_detail

#: Sec. 4's model (M = 1 kg, K = 1 N/m, b = 0.1, a1 = -0.1 m, a2 = 0.05 m), as the configuration gives it
MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
FIG3 = {**MODEL, "F": 1.0, "x0": -1.0, "n_cycles": 5, "amplitude": "amplitude_h0", "study": "replication",
        "label": "a"}
FIG4 = {**MODEL, "F": 0.5, "x0": 3.0, "velocity_window": [80.0, 87.0], "acceleration_window": [81.0, 85.0],
        "samples_per_second": 100}
FIG5 = {**MODEL, "F": 0.5, "x0": 3.0, "n_cycles": 5, "samples_per_period": 100, "label": "1"}


def test_the_poincare_map_keeps_no_trajectory_and_names_its_amplitude():
    """From rest at -1 m the free arc before the first impact has the Step-1 amplitude |x0| = 1 m (energy is
    conserved on it: derived on paper); Step 1 has one value more than there are cycles, Step 8 is it shifted."""
    ds = poincare_map(FIG3)
    assert "t" not in ds.dims and ds.sizes["cycle"] == 5 and ds.attrs["amplitude_variable"] == "amplitude_h0"
    h0 = ds["amplitude_h0"]
    assert h0["amplitude_cycle"].values.tolist() == list(range(1, 7)) and h0.attrs["units"] == "m"
    assert float(h0[0]) == pytest.approx(1.0, rel=1e-14)
    h4 = poincare_map({**FIG3, "amplitude": "amplitude_h4"})["amplitude_h4"]
    np.testing.assert_array_equal(h4.values, h0.values[1:])
    largest = poincare_map({**FIG3, "amplitude": "largest_displacement"})
    assert largest.attrs["amplitude_variable"] == "largest_displacement" and "amplitude_cycle" not in largest.dims


def test_the_replication_is_titled_by_the_paper_s_figure_and_a_study_of_your_own_by_its_name():
    assert poincare_map(FIG3).attrs["title"].endswith("(Fig. 3 of Mao, Fu & Li 2013)")
    own = poincare_map({**FIG3, "study": "own", "F": 2.0}).attrs
    assert "Fig." not in own["title"] and own["title"].endswith("case a, study own") and own["study"] == "own"
    assert "Fig." not in phase_diagram({**FIG5, "study": "heavy"}).attrs["title"]


@pytest.mark.parametrize("scene, settings", [(poincare_map, FIG3), (shock_detail, FIG4), (phase_diagram, FIG5)])
def test_a_study_s_dataset_names_what_it_changed_from_the_paper_and_the_replication_s_nothing(scene, settings):
    """The scene's settings carry the line (the configuration writes it); the dataset keeps it as a global
    attribute of text, as CF and ACDD want their attributes."""
    own = scene({**settings, "b": 0.3, "study": "own", "changes": "b = 0.3 (paper: 0.1)"})
    assert own.attrs["study_changes"] == "b = 0.3 (paper: 0.1)" and own.attrs["study"] == "own"
    assert float(own["b"]) == 0.3
    assert "study_changes" not in scene(settings).attrs


def test_the_shock_detail_is_sampled_only_inside_its_windows_on_each_side_of_each_event():
    ds = shock_detail(FIG4)
    t = ds["t"].values
    assert t[0] == 80.0 and t[-1] == 87.0 and np.all(np.diff(t) > 0)
    inside = ds.sizes["event"]
    assert inside >= 4 and len(t) == 701 + 2 * inside  # the grid, and both sides of each event
    assert ds["velocity_window"].values.tolist() == [80.0, 87.0] and ds["velocity_window"].attrs["units"] == "s"


def test_the_phase_diagram_s_resolution_follows_the_natural_period():
    ds = phase_diagram(FIG5)
    assert ds["t"].values[1] - ds["t"].values[0] <= 2 * np.pi / 100 and ds.sizes["cycle"] == 5


def test_a_motion_that_stops_is_an_outcome_recorded_in_the_dataset_not_an_error():
    ds = phase_diagram({**FIG5, "x0": 0.05})  # |x0| < |a1|: the free swing never reaches an impact position
    assert ds.attrs["outcome"] == "stopped" and ds.sizes["cycle"] == 0 and np.all(np.diff(ds["t"].values) > 0)


@pytest.mark.parametrize("scene, settings, name", [
    (poincare_map, {**FIG3, "n_cycles": 0}, "n_cycles"),
    (poincare_map, {**FIG3, "n_cycles": 2.5}, "n_cycles"),
    (poincare_map, {**FIG3, "n_cycles": True}, "n_cycles"),
    (poincare_map, {**FIG3, "amplitude": "peak"}, "amplitude"),
    (poincare_map, {**FIG3, "M": 0.0}, "M"),
    (poincare_map, {k: v for k, v in FIG3.items() if k != "x0"}, "x0"),
    (shock_detail, {**FIG4, "velocity_window": [87.0, 80.0]}, "velocity_window"),
    (shock_detail, {**FIG4, "acceleration_window": [-1.0, 2.0]}, "acceleration_window"),
    (shock_detail, {**FIG4, "velocity_window": "80-87"}, "velocity_window"),
    (shock_detail, {**FIG4, "samples_per_second": 0}, "samples_per_second"),
    (phase_diagram, {**FIG5, "x0": float("nan")}, "x0"),
])
def test_each_scene_refuses_its_bad_settings_naming_the_key_before_any_run(scene, settings, name):
    with pytest.raises(ParameterError, match=f"^{name} = "):
        scene(settings)


def test_sample_times_add_a_sample_on_each_side_of_each_jump():
    below = np.nextafter
    t = sample_times(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.5, 2.0, 0.0, 5.0]))
    # 1.5: both sides added; 2.0 on the grid: the sample below it added; 0.0 at the start: nothing below it;
    # 5.0 outside the grid: nothing
    assert t.tolist() == [0.0, 1.0, below(1.5, 0.0), 1.5, below(2.0, 0.0), 2.0, 3.0]


def test_the_amplitudes_a_scene_takes_are_those_the_readings_define_and_the_schema_allows():
    import yaml

    from escapement.scenes.settings import AMPLITUDES
    from escapement.studies.readings import AMPLITUDES as DEFINED
    from workflow_copies import REPO

    schema = yaml.safe_load((REPO / "workflow/schemas/config.schema.yaml").read_text())
    assert list(AMPLITUDES) == list(DEFINED) == schema["$defs"]["fig3"]["properties"]["amplitude"]["enum"]
