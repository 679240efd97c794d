import math

import mpmath
import numpy as np
import pytest

from escapement.model.kinematics import (
    arc_maximum,
    arc_terms,
    compensated_add,
    crossing,
    rebound_accumulation_time,
    sample_arcs,
    time_to_rest,
    two_sum,
)


def crossing_from(centre, x0, v0, omega, target, direction, xp=math):
    """The crossing of the arc about ``centre`` from ``(x0, v0)`` to ``target``: its terms, then the crossing."""
    u0, q, k = arc_terms(centre, x0, omega, target)
    return crossing(u0, q, k, v0, omega, direction, xp)


def test_arc_terms_are_the_offsets_and_the_energy_change():
    # about c = 0.5 with w = 2 from x0 = 1.5 to 0.25: u0 = 1, q = -0.25, and by energy
    # v1**2 - v0**2 = w**2 ((x0 - c)**2 - (target - c)**2) = 4 (1 - 1/16) = 3.75
    u0, q, k = arc_terms(0.5, 1.5, 2.0, 0.25)
    assert (u0, q) == (1.0, -0.25) and k == pytest.approx(3.75, rel=1e-15)
    got = arc_terms(np.array([0.0, 0.5]), np.array([1.0, 1.5]), np.array([1.0, 2.0]), np.array([0.5, 0.25]))
    assert [g.tolist() for g in got] == [[1.0, 1.0], [0.5, -0.25], [0.75, 3.75]]


def test_crossing_of_a_free_swing_from_rest():
    # x = cos t from (1, 0): x = 0.5 moving left at t = pi/3, with v = -sin(pi/3).
    reached, tau, v, angle = crossing_from(0.0, 1.0, 0.0, 1.0, 0.5, -1)
    assert reached
    assert tau == pytest.approx(math.pi / 3, rel=1e-15)
    assert v == pytest.approx(-math.sin(math.pi / 3), rel=1e-15)
    assert angle == pytest.approx(math.pi / 3, rel=1e-15)


def test_crossing_moving_right_needs_the_far_side_of_the_circle():
    # From (1, 0) the first passage of x = 0.5 moving right is at t = 2 pi - pi/3.
    reached, tau, v, _ = crossing_from(0.0, 1.0, 0.0, 1.0, 0.5, 1)
    assert reached
    assert tau == pytest.approx(5 * math.pi / 3, rel=1e-15)
    assert v == pytest.approx(math.sin(math.pi / 3), rel=1e-15)


def test_crossing_about_a_shifted_centre_with_frequency():
    # x = c + u0 cos(w t) with c = 2, u0 = -1, w = 3: reaches x = 2 (the centre) moving right at w t = pi/2.
    reached, tau, v, angle = crossing_from(2.0, 1.0, 0.0, 3.0, 2.0, 1)
    assert reached
    assert angle == pytest.approx(math.pi / 2, rel=1e-15)
    assert tau == pytest.approx(math.pi / 6, rel=1e-15)
    assert v == pytest.approx(3.0, rel=1e-15)


@pytest.mark.parametrize("target", [1.0, 1.5, -1.0])
def test_no_crossing_at_or_beyond_the_turning_point(target):
    # x = cos t turns at +-1: a target at a turning point is grazed, not passed; beyond it is never reached.
    reached, *_ = crossing_from(0.0, 1.0, 0.0, 1.0, target, -1 if target < 0 else 1)
    assert reached is False or reached == np.False_


def test_crossing_just_inside_the_turning_point_has_the_energy_speed():
    target = 1.0 - 1e-12
    eps = 1.0 - target  # exact in floating point
    reached, tau, v, _ = crossing_from(0.0, 1.0, 0.0, 1.0, target, -1)
    assert reached
    assert v == pytest.approx(-math.sqrt(2 * eps - eps * eps), rel=1e-12)
    assert tau == pytest.approx(math.acos(1 - eps), rel=1e-6)


def test_crossing_on_arrays_is_the_scalar_crossing_elementwise():
    # rows: a free swing from rest, a shifted centre, a target beyond the turning point, a start moving left
    centre = np.array([0.0, 2.0, 0.0, 0.3])
    x0 = np.array([1.0, 1.0, 1.0, -0.2])
    v0 = np.array([0.0, 0.0, 0.0, -1.5])
    omega = np.array([1.0, 3.0, 1.0, 2.0])
    target = np.array([0.5, 2.0, 1.5, 0.1])
    direction = np.array([-1.0, 1.0, 1.0, 1.0])
    reached, tau, v, angle = crossing_from(centre, x0, v0, omega, target, direction, np)
    assert reached.tolist() == [True, True, False, True]
    for i in (0, 1, 3):
        one = crossing_from(*(float(a[i]) for a in (centre, x0, v0, omega, target, direction)))
        assert (tau[i], v[i], angle[i]) == pytest.approx(one[1:], rel=1e-15)
    # row 3 by hand: u0 = -0.5, w0 = -0.75 about c = 0.3, radius sqrt(0.8125); it reaches x = 0.1 (u = -0.2)
    # moving right after passing the bottom: clockwise from phase atan2(-0.75, -0.5) to atan2(+w1, -0.2)
    radius = math.hypot(-0.5, -0.75)
    w1 = math.sqrt(radius**2 - 0.04)
    sweep = (math.atan2(-0.75, -0.5) - math.atan2(w1, -0.2)) % (2 * math.pi)
    assert tau[3] == pytest.approx(sweep / 2.0, rel=1e-14)
    assert v[3] == pytest.approx(2.0 * w1, rel=1e-15)


def test_a_full_turn_is_2pi_not_0():
    # From x = 0.5 moving right, the next arrival at x = 0.5 moving right is a full period later.
    reached, tau, v, angle = crossing_from(0.0, 0.5, 1.0, 2.0, 0.5, 1)
    assert reached and angle == pytest.approx(2 * math.pi, rel=1e-15) and tau == pytest.approx(math.pi, rel=1e-15)
    assert v == pytest.approx(1.0, rel=1e-15)


def _arc_end(centre, x0, v0, omega, angle):
    """Where the arc about ``centre`` from ``(x0, v0)`` is after sweeping ``angle``: the harmonic motion."""
    u0, w0 = x0 - centre, v0 / omega
    return (centre + u0 * np.cos(angle) + w0 * np.sin(angle),
            omega * (w0 * np.cos(angle) - u0 * np.sin(angle)))


def test_arc_maximum_over_the_top_and_short_of_it():
    # From (0, 1) about 0 with w = 1 the top x = 1 is reached after a quarter turn.
    assert arc_maximum(0.0, 0.0, 1.0, 1.0, math.pi, 0.0, -1.0) == pytest.approx(1.0, rel=1e-15)
    assert arc_maximum(0.0, 0.0, 1.0, 1.0, 0.5, math.sin(0.5), math.cos(0.5)) == math.sin(0.5)


def test_arc_maximum_on_arrays():
    got = arc_maximum(np.zeros(2), np.zeros(2), np.ones(2), 1.0, np.array([math.pi, 0.5]),
                      np.array([0.0, math.sin(0.5)]), np.array([-1.0, math.cos(0.5)]))
    assert got == pytest.approx([1.0, math.sin(0.5)], rel=1e-15)


def test_arc_maximum_about_a_shifted_centre_from_below_the_top():
    # about c = 0.2 from (x, v) = (0.2 - 0.3, -0.4 w), w = 2: radius 0.5; moving left, the top (0.7) comes
    # after the bottom, i.e. after a phase of 2 pi + atan2(-0.4, -0.3) (clockwise) from the start.
    to_top = math.atan2(-0.4, -0.3) + 2 * math.pi
    short = _arc_end(0.2, -0.1, -0.8, 2.0, to_top - 1e-6)
    past = _arc_end(0.2, -0.1, -0.8, 2.0, to_top + 1e-6)
    assert short[1] > 0 > past[1]  # moving right just before the top, left just after
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, to_top - 1e-6, *short) == short[0] < 0.7  # the larger end
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, to_top + 1e-6, *past) == pytest.approx(0.7, rel=1e-15)
    # half a turn from the start moving left ends at the bottom's far side, short of the top
    half = _arc_end(0.2, -0.1, -0.8, 2.0, math.pi - 1e-3)
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, math.pi - 1e-3, *half) == max(-0.1, half[0])


def test_arc_maximum_is_the_largest_sample_of_random_arcs():
    """Against brute force: the largest of 4_001 samples of each arc, for arcs of every length below a turn,
    starting anywhere on their circle (moving left, right, at rest at the bottom or top)."""
    rng = np.random.default_rng(3)
    n = 200
    centre, omega = rng.uniform(-1, 1, n), rng.uniform(0.5, 3.0, n)
    x0, v0 = centre + rng.uniform(-1, 1, n), rng.uniform(-2, 2, n)
    v0[:10] = 0.0  # at rest: at the bottom (x0 < c) the arc starts moving right, at the top left
    angle = rng.uniform(1e-3, 2 * math.pi - 1e-3, n)
    x1, v1 = _arc_end(centre, x0, v0, omega, angle)
    got = arc_maximum(centre, x0, v0, omega, angle, x1, v1)
    s = np.linspace(0.0, 1.0, 4_001)[:, None] * angle
    sampled = np.max(_arc_end(centre, x0, v0, omega, s)[0], axis=0)
    radius = np.hypot(x0 - centre, v0 / omega)
    step = angle / 4_000
    assert np.all(got >= sampled - 1e-15) and np.all(got - sampled <= radius * step**2 / 8 + 1e-15)


def test_compensated_sum_of_a_hundred_thousand_tenths_is_the_exactly_rounded_sum():
    total = error = 0.0
    for _ in range(100_000):
        total, error = compensated_add(total, error, 0.1)
    exact = math.fsum([0.1] * 100_000)  # correctly rounded sum of the floats
    assert total + error == exact != sum([0.1] * 100_000)  # the naive sum drifts: the compensation is needed


def test_compensated_add_carries_the_exact_rounding_error_of_each_addition():
    """TwoSum: from ``(a, 0)``, adding ``b`` gives ``total = fl(a + b)`` and ``total + error = a + b`` exactly
    (checked in fractions), whatever the order and the magnitudes, on floats and on arrays alike; two_sum is it."""
    from fractions import Fraction

    rng = np.random.default_rng(11)
    a = rng.standard_normal(2000) * 10.0 ** rng.integers(-30, 30, 2000)
    b = rng.standard_normal(2000) * 10.0 ** rng.integers(-30, 30, 2000)
    total, error = compensated_add(a, np.zeros_like(a), b)
    assert np.array_equal(total, a + b)
    for i in range(2000):
        assert Fraction(float(total[i])) + Fraction(float(error[i])) == Fraction(float(a[i])) + Fraction(float(b[i]))
        assert compensated_add(float(a[i]), 0.0, float(b[i])) == (total[i], error[i]) == two_sum(a[i], b[i])


def test_compensated_add_on_arrays():
    total, error = np.array([1e16, 0.0]), np.zeros(2)
    for term in (1.0, 1.0, -1e16):
        total, error = compensated_add(total, error, np.array([term, term]))
    assert (total + error).tolist() == [2.0, -1e16 + 2.0]


def test_time_to_rest_on_floats_arrays_and_mpmath():
    """The next rest by hand: about c = 0 with w = 1 from x = 0 moving left at 1, a quarter turn to x = -1; about
    c = 1 with w = 2 from x = 1 moving right at 2 (radius 1), a quarter turn (pi/4 s) to x = 2; at rest, now."""
    expected = ([math.pi / 2, math.pi / 4, 0.0], [-1.0, 2.0, 0.3])
    args = ([0.0, 1.0, 0.0], [0.0, 1.0, 0.3], [-1.0, 2.0, 0.0], [1.0, 2.0, 1.0])
    for i in range(3):
        tau, x = time_to_rest(*(a[i] for a in args))
        assert (tau, x) == (pytest.approx(expected[0][i], rel=1e-15), pytest.approx(expected[1][i], rel=1e-15))
    tau, x = time_to_rest(*(np.array(a) for a in args), np)
    np.testing.assert_allclose(tau, expected[0], rtol=1e-15)
    np.testing.assert_allclose(x, expected[1], rtol=1e-15)
    with mpmath.workdps(40):
        tau, x = time_to_rest(*(mpmath.mpf(a[1]) for a in args), mpmath)
        assert abs(tau - mpmath.pi / 4) < mpmath.mpf("1e-39") and x == 2


@pytest.mark.parametrize(
    "args, name",
    [
        ((1.0, 0.1, 1.0, 1.0), "ratio"),
        ((1.0, 0.1, 1.0, -0.5), "ratio"),
        ((1.0, 0.1, 1.0, math.nan), "ratio"),
        ((0.0, 0.1, 1.0, 0.5), "omega"),
        ((1.0, 0.0, 1.0, 0.5), "distance"),
        ((1.0, 0.1, -1.0, 0.5), "speed"),
        ((1.0, 0.1, math.inf, 0.5), "speed"),
        ((1e-300, 1e-300, 1.0, 0.5), "speed / \\(omega \\* distance\\)"),
    ],
)
def test_rebound_accumulation_time_rejects_invalid_input(args, name):
    with pytest.raises(ValueError, match=name + " = .* is invalid"):
        rebound_accumulation_time(*args)


def test_sample_arcs_is_nan_outside_the_trajectory():
    x, v, a = sample_arcs(
        np.array([-1.0, 0.0, 1.0, 3.0]), np.array([0.0]), np.array([0.0]), np.array([1.0]), np.array([0.0]), 1.0, 2.0
    )
    assert np.isnan(x[0]) and np.isnan(x[3])
    assert x[1:3] == pytest.approx([1.0, math.cos(1.0)], rel=1e-15)
    assert v[2] == pytest.approx(-math.sin(1.0), rel=1e-15)
    assert a[2] == pytest.approx(-math.cos(1.0), rel=1e-15)
