import math

import mpmath
import numpy as np
import pytest

from escapement.arcs import (
    arc_maximum,
    crossing,
    rebound_accumulation_time,
    sample_arcs,
    state_after,
    time_to_rest,
)


def test_crossing_of_a_free_swing_from_rest():
    # x = cos t from (1, 0): x = 0.5 moving left at t = pi/3, with v = -sin(pi/3).
    tau, v, angle = crossing(0.0, 1.0, 0.0, 1.0, 0.5, -1)
    assert tau == pytest.approx(math.pi / 3, rel=1e-15)
    assert v == pytest.approx(-math.sin(math.pi / 3), rel=1e-15)
    assert angle == pytest.approx(math.pi / 3, rel=1e-15)


def test_crossing_moving_right_needs_the_far_side_of_the_circle():
    # From (1, 0) the first passage of x = 0.5 moving right is at t = 2 pi - pi/3.
    tau, v, _ = crossing(0.0, 1.0, 0.0, 1.0, 0.5, 1)
    assert tau == pytest.approx(5 * math.pi / 3, rel=1e-15)
    assert v == pytest.approx(math.sin(math.pi / 3), rel=1e-15)


def test_crossing_about_a_shifted_centre_with_frequency():
    # x = c + u0 cos(w t) with c = 2, u0 = -1, w = 3: reaches x = 2 (the centre) moving right at w t = pi/2.
    tau, v, _ = crossing(2.0, 1.0, 0.0, 3.0, 2.0, 1)
    assert tau == pytest.approx(math.pi / 6, rel=1e-15)
    assert v == pytest.approx(3.0, rel=1e-15)


@pytest.mark.parametrize("target", [1.0, 1.5, -1.0])
def test_no_crossing_at_or_beyond_the_turning_point(target):
    assert crossing(0.0, 1.0, 0.0, 1.0, target, -1 if target < 0 else 1) is None


def test_crossing_just_inside_the_turning_point_has_the_energy_speed():
    target = 1.0 - 1e-12
    eps = 1.0 - target  # exact in floating point
    tau, v, _ = crossing(0.0, 1.0, 0.0, 1.0, target, -1)
    assert v == pytest.approx(-math.sqrt(2 * eps - eps * eps), rel=1e-12)
    assert tau == pytest.approx(math.acos(1 - eps), rel=1e-6)


def test_state_after_matches_the_sinusoid():
    x, v = state_after(0.5, 1.0, 2.0, 2.0, 0.3)
    u0, w = 0.5, 2.0
    assert x == pytest.approx(0.5 + u0 * math.cos(0.6) + (2.0 / w) * math.sin(0.6), rel=1e-15)
    assert v == pytest.approx(2.0 * math.cos(0.6) - w * u0 * math.sin(0.6), rel=1e-15)


def test_arc_maximum_over_the_top_and_short_of_it():
    # From (0, 1) about 0 with w = 1 the top x = 1 is reached after a quarter turn.
    assert arc_maximum(0.0, 0.0, 1.0, 1.0, math.pi, 0.0) == pytest.approx(1.0, rel=1e-15)
    assert arc_maximum(0.0, 0.0, 1.0, 1.0, 0.5, math.sin(0.5)) == math.sin(0.5)


def test_time_to_rest_moving_left_and_right():
    tau, x = time_to_rest(0.0, 0.0, -1.0, 1.0)
    assert (tau, x) == (pytest.approx(math.pi / 2, rel=1e-15), pytest.approx(-1.0, rel=1e-15))
    tau, x = time_to_rest(1.0, 1.0, 2.0, 2.0)
    assert (tau, x) == (pytest.approx(math.pi / 4, rel=1e-15), pytest.approx(2.0, rel=1e-15))
    assert time_to_rest(0.0, 0.3, 0.0, 1.0) == (0.0, 0.3)


@pytest.mark.parametrize("ratio, speed", [(0.5, 1.0), (0.9, 3.0), (0.2, 0.01), (0.0, 1.0), (0.99, 50.0)])
def test_rebound_accumulation_time_against_a_30_digit_sum(ratio, speed):
    # Direct sum of the flight times (2/w) atan(x r^n) until x r^n < 1e-20; the rest is
    # sum of x r^n / (1 - r) up to a relative error of order 1e-40.
    omega, distance = 1.3, 0.1
    with mpmath.workdps(30):
        x = mpmath.mpf(speed) / (mpmath.mpf(omega) * mpmath.mpf(distance))
        r = mpmath.mpf(ratio)
        total = mpmath.mpf(0)
        term = x
        while term > mpmath.mpf("1e-20"):
            total += mpmath.atan(term)
            term *= r
        total += term / (1 - r)
        expected = float(2 * total / mpmath.mpf(omega))
    assert rebound_accumulation_time(omega, distance, speed, ratio) == pytest.approx(expected, rel=1e-13)


def test_rebound_accumulation_time_gives_up_beyond_its_bound():
    assert rebound_accumulation_time(1.0, 0.1, 10.0, 1 - 1e-9, max_terms=1000) is None


def test_rebound_accumulation_time_rejects_invalid_input():
    with pytest.raises(ValueError):
        rebound_accumulation_time(1.0, 0.1, 1.0, 1.0)


def test_sample_arcs_is_nan_outside_the_trajectory():
    x, v, a = sample_arcs(
        np.array([-1.0, 0.0, 1.0, 3.0]), np.array([0.0]), np.array([0.0]), np.array([1.0]), np.array([0.0]), 1.0, 2.0
    )
    assert np.isnan(x[0]) and np.isnan(x[3])
    assert x[1:3] == pytest.approx([1.0, math.cos(1.0)], rel=1e-15)
    assert v[2] == pytest.approx(-math.sin(1.0), rel=1e-15)
    assert a[2] == pytest.approx(-math.cos(1.0), rel=1e-15)
