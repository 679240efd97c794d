import numpy as np
import pytest

from escapement.io.scenes import phase_scene, poincare_scene, shock_scene
from escapement.model.parameters import ParameterError


def test_poincare_scene_keeps_no_trajectory(case_a):
    ds = poincare_scene(case_a, 1.0, 50)
    assert set(ds.dims) == {"cycle", "event"}
    assert ds.sizes["cycle"] == 50
    assert ds["cycle"].values[0] == 1


def test_shock_scene_samples_only_inside_its_windows(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 100)
    assert ds["t"].values[0] == 80.0 and ds["t"].values[-1] == 87.0
    assert ds.sizes["t"] == 701
    assert np.all((ds["impact_time"] >= 80) & (ds["impact_time"] <= 87))
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


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(velocity_window=(87.0, 80.0)), "velocity_window"),
        (dict(acceleration_window=(-1.0, 2.0)), "acceleration_window"),
        (dict(velocity_window="80-87"), "velocity_window"),
        (dict(samples_per_second=0), "samples_per_second"),
    ],
)
def test_shock_scene_rejects_bad_settings(case_b, kwargs, name):
    args = dict(velocity_window=(80.0, 87.0), acceleration_window=(81.0, 85.0), samples_per_second=10)
    args.update(kwargs)
    with pytest.raises(ParameterError, match=f"^{name} = "):
        shock_scene(case_b, 3.0, **args)
