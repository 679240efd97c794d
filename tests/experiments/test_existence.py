"""The existence map of an asymmetric escapement (Sec. 5): the simulated outcome on either side of the
closed-form thresholds, which the tests write out from their formula with the paper's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from escapement.experiments.existence import axis_centres, existence_map, thresholds
from escapement.model.status import Status
from escapement.pipeline.simulate import existence_scene

#: the paper's Sec. 4 model with the symmetric a4 = -a2; a3 is the map's axis
MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}


def f_star(a3: float) -> float:
    """F* = (2b - b^2) K (a1^2 - a3^2) / (2 [(1 - b)^2 (a2 - a1) + (a3 - a4)]), b = 0.1, K = 1 N/m,
    a1 = -0.1 m, a2 = 0.05 m, a4 = -0.05 m."""
    return 0.19 * (0.01 - a3 * a3) / (2 * (0.81 * 0.15 + (a3 + 0.05)))


def f_star_mirror(a3: float) -> float:
    """F* of the mirror image (a1, a2, a3, a4) -> (-a3, -a4, -a1, -a2) = (-a3, 0.05, 0.1, -0.05)."""
    return 0.19 * (a3 * a3 - 0.01) / (2 * (0.81 * (a3 + 0.05) + 0.15))


@pytest.mark.parametrize("a3", [0.02, 0.05, 0.08, 0.12, 0.2])
def test_thresholds_are_the_closed_forms(a3):
    threshold, mirror = thresholds(MODEL, [a3])
    assert threshold[0] == pytest.approx(f_star(a3), rel=1e-12)
    assert mirror[0] == pytest.approx(f_star_mirror(a3), rel=1e-12)


def test_the_thresholds_vanish_in_the_symmetric_case():
    threshold, mirror = thresholds(MODEL, [0.1])
    assert abs(threshold[0]) < 1e-18 and abs(mirror[0]) < 1e-18


@pytest.mark.parametrize("a3", [0.03, 0.07, 0.13, 0.22])
def test_simulation_settles_just_above_and_stops_just_below_the_binding_threshold(a3):
    bound = max(f_star(a3), f_star_mirror(a3))
    forces = [0.97 * bound, 1.03 * bound]
    run = existence_map(MODEL, [a3], forces, x0=-1.0, n_cycles=150, tolerance=1e-9)
    assert run.status[0].tolist() == [Status.STOPPED.code, Status.COMPLETED.code]
    assert run.converged[0].tolist() == [False, True]


def test_the_region_of_the_whole_grid_is_the_closed_form_region():
    a3 = np.array([0.01, 0.04, 0.09, 0.11, 0.16, 0.24])
    F = np.array([0.0005, 0.002, 0.004, 0.006, 0.009, 0.013])
    run = existence_map(MODEL, a3, F, x0=-1.0, n_cycles=150, tolerance=1e-9)
    expected = np.array([[f > max(f_star(a), f_star_mirror(a)) for f in F] for a in a3])
    assert expected.any() and not expected.all()
    assert (run.converged == expected).all()
    assert ((run.status == Status.STOPPED.code) == ~expected).all()


def test_one_cycle_cannot_count_as_converged():
    run = existence_map(MODEL, [0.05], [0.01], x0=-1.0, n_cycles=1, tolerance=1e-9)
    assert run.status[0, 0] == Status.COMPLETED.code and not run.converged[0, 0]


def test_the_axes_are_cell_centres():
    a3, F = (axis_centres({"start": 0.0, "stop": 0.25, "n": 5}), axis_centres({"start": 0.0, "stop": 0.01, "n": 2}))
    np.testing.assert_allclose(a3, [0.025, 0.075, 0.125, 0.175, 0.225])
    np.testing.assert_allclose(F, [0.0025, 0.0075])


def test_the_dataset_is_self_describing():
    block = {"a3": {"start": 0.0, "stop": 0.2, "n": 4}, "F": {"start": 0.0, "stop": 0.01, "n": 3}, "x0": -1.0,
             "n_cycles": 80, "tolerance": 1e-9}
    ds = existence_scene(MODEL, block)
    assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
    assert ds["outcome"].dims == ("a3", "F") and ds["threshold"].dims == ("a3",)
    for name in ("a3", "F", "threshold", "threshold_mirror"):
        assert ds[name].attrs["units"] in ("m", "N") and ds[name].attrs["long_name"]
    assert ds["converged"].attrs["flag_meanings"] == "no_limit_cycle limit_cycle"
    assert float(ds["x0"]) == -1.0 and float(ds["a4"]) == -0.05 and int(ds["n_cycles"]) == 80
    np.testing.assert_allclose(ds["threshold"].values, [f_star(a) for a in (0.025, 0.075, 0.125, 0.175)], rtol=1e-12)
