"""The scenes over grids: the existence map against the closed-form thresholds written out here from their
formula with the paper's numbers, the stability map's multiplier against (1 - b)^4, and the escapement error's
shape and agreement of the corrected Eqs. (24)-(25) with the solver."""

from __future__ import annotations

import numpy as np
import pytest

from escapement.model.status import Status
from escapement.scenes.maps import escapement_error, existence_map, stability_map

#: the paper's Sec. 4 model with the symmetric a4 = -a2; a3 is the existence map's axis
MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}


def f_star(a3: float) -> float:
    """F* = (2b - b^2) K (a1^2 - a3^2) / (2 [(1 - b)^2 (a2 - a1) + (a3 - a4)]), b = 0.1, K = 1 N/m,
    a1 = -0.1 m, a2 = 0.05 m, a4 = -0.05 m."""
    return 0.19 * (0.01 - a3 * a3) / (2 * (0.81 * 0.15 + (a3 + 0.05)))


def f_star_mirror(a3: float) -> float:
    """F* of the mirror image (a1, a2, a3, a4) -> (-a3, -a4, -a1, -a2) = (-a3, 0.05, 0.1, -0.05)."""
    return 0.19 * (a3 * a3 - 0.01) / (2 * (0.81 * (a3 + 0.05) + 0.15))


def existence(a3: dict, F: dict, n_cycles: int = 150) -> dict:
    return {**MODEL, "a3": a3, "F": F, "x0": -1.0, "n_cycles": n_cycles, "tolerance": 1e-9}


def test_the_existence_map_settles_where_the_closed_forms_allow_and_stops_elsewhere():
    """Cell centres of a3 in (0, 0.24) and F in (0, 0.012): converged exactly where F > max(F*, F*')."""
    ds = existence_map(existence({"start": 0.0, "stop": 0.24, "n": 6}, {"start": 0.0, "stop": 0.012, "n": 6}))
    a3, F = ds["a3"].values, ds["F"].values
    np.testing.assert_allclose(a3, [0.02, 0.06, 0.10, 0.14, 0.18, 0.22])
    expected = np.array([[f > max(f_star(a), f_star_mirror(a)) for f in F] for a in a3])
    assert expected.any() and not expected.all()
    assert (ds["converged"].values.astype(bool) == expected).all()
    assert ((ds["outcome"].values == Status.STOPPED.code) == ~expected).all()
    np.testing.assert_allclose(ds["threshold"].values, [f_star(a) for a in a3], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(ds["threshold_mirror"].values, [f_star_mirror(a) for a in a3], rtol=1e-12,
                               atol=1e-15)
    assert float(ds["a4"]) == -0.05 and float(ds["x0"]) == -1.0 and int(ds["n_cycles"]) == 150


@pytest.mark.parametrize("a3", [0.03, 0.13])
def test_the_existence_map_flips_just_across_the_binding_threshold(a3):
    bound = max(f_star(a3), f_star_mirror(a3))
    ds = existence_map(existence({"start": a3 - 1e-6, "stop": a3 + 1e-6, "n": 1},
                                 {"start": 0.94 * bound, "stop": 1.06 * bound, "n": 2}))
    assert ds["outcome"].values[0].tolist() == [Status.STOPPED.code, Status.COMPLETED.code]


def test_the_stability_map_measures_the_multiplier_of_eq_21():
    """mu2 = (1 - b)^4 (Eq. (21), written out here) where the cycle completes, on a small (b, F) grid: b at the
    cell centres 0.25, 0.75, 1.25, 1.75 of (0, 2), F = 0.5 and 1 N."""
    ds, timings = stability_map({**MODEL, "b": {"start": 0.0, "stop": 2.0, "n": 4}, "F": {"start": 0.5, "stop": 1.0,
                                                                                        "n": 2}})
    assert ds["b"].values.tolist() == [0.25, 0.75, 1.25, 1.75] and ds["F"].values.tolist() == [0.5, 1.0]
    completed = ds["outcome"].values == Status.COMPLETED.code
    assert completed[:2].all() and not completed[2:].any()  # b > 1: the impact reverses the velocity
    expected = (1 - np.array([0.25, 0.75, 1.25, 1.75]))[:, None] ** 4 * np.ones((1, 2))
    np.testing.assert_allclose(ds["multiplier"].values[completed], expected[completed], atol=1e-8)
    np.testing.assert_array_equal(ds["multiplier_eq21"].values, expected)
    assert set(timings) == {"ensemble_seconds_per_trajectory", "scalar_seconds_per_trajectory",
                            "ensemble_speedup_per_trajectory"}


@pytest.mark.parametrize("scene, settings", [
    (lambda s: stability_map(s, speed_sample=1)[0], {"b": {"start": 0.0, "stop": 1.0, "n": 2},
                                                     "F": {"start": 0.5, "stop": 1.0, "n": 2}}),
    (existence_map, existence({"start": 0.05, "stop": 0.15, "n": 2}, {"start": 0.0, "stop": 0.01, "n": 2}, 5)),
    (escapement_error, {"F": {"start": 0.5, "stop": 1.0, "n": 2}, "zones": {"paper": [-0.1, 0.05]}}),
])
def test_a_map_of_a_study_names_what_it_changed_in_a_text_attribute(scene, settings):
    own = scene({**MODEL, **settings, "study": "own", "changes": "K = 2 N/m (paper: 1 N/m)"})
    assert own.attrs["study_changes"] == "K = 2 N/m (paper: 1 N/m)" and own.attrs["study"] == "own"
    assert "study_changes" not in scene({**MODEL, **settings}).attrs


def test_the_escapement_error_holds_each_zone_at_each_force_and_its_formula_agrees_with_the_solver():
    ds = escapement_error({**MODEL, "F": {"start": 0.1, "stop": 1.0, "n": 3},
                           "zones": {"symmetric": [-0.1, 0.1], "before": [-0.2, -0.05]}})
    assert ds["rate"].dims == ("zone", "F") and ds.sizes == {"zone": 2, "F": 3}
    np.testing.assert_allclose(ds["F"].values, [0.1, 0.1 * 10 ** 0.5, 1.0])  # geometric
    assert ds["zone_name"].values.tolist() == ["symmetric", "before"]
    assert float(ds["max_period_difference"]) < 1e-12
    # Airy: an impulse before the equilibrium shortens the period, a clock counting 2 pi / omega gains
    assert (ds["rate_zones"].sel(zone=1).values > 0).all()


def test_a_zone_without_a_limit_cycle_is_nan_with_its_outcome_and_the_others_are_kept():
    """b = 1 stops the mass at a1: for the zone (0.05, 0.2) m it then swings about F/K inside the zone and turns
    short of its end at F = 0.1 N (amplitude 0.05 m about 0.1 m), while the paper's zone has a limit cycle."""
    ds = escapement_error({**MODEL, "b": 1.0, "F": {"start": 0.1, "stop": 1.0, "n": 2},
                           "zones": {"paper": [-0.1, 0.05], "after": [0.05, 0.2]}})
    outcome = ds["outcome"].values
    assert (outcome[0] == Status.COMPLETED.code).all() and outcome[1, 0] == Status.TURNED_BACK_IN_ZONE.code
    assert np.isnan(ds["rate"].values[1, 0]) and np.isfinite(ds["rate"].values[0]).all()
    assert float(ds["max_period_difference"]) < 1e-12
