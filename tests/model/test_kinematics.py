"""Closed-form kinematics of a harmonic arc against the motion by hand: crossings, the largest x, the next rest,
compensated sums of times, the sampled arcs."""

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from escapement.model.kinematics import (arc_maximum, arc_terms, compensated_add, crossing, rebound_accumulation_time,
                                         sample_arcs, time_to_rest, two_sum)


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


#: about c = 0.3 with w = 2 from (-0.2, -1.5), u0 = -0.5 and w0 = -0.75, the arc reaches x = 0.1 (u = -0.2) moving
#: right after the bottom: clockwise from phase atan2(-0.75, -0.5) to atan2(+w1, -0.2)
_W1 = math.sqrt(0.5**2 + 0.75**2 - 0.2**2)
_SWEEP = (math.atan2(-0.75, -0.5) - math.atan2(_W1, -0.2)) % (2 * math.pi)
#: arcs (centre, x0, v0, omega, target, direction) and their crossing by hand: (time, velocity, angle)
CROSSINGS = [
    ((0.0, 1.0, 0.0, 1.0, 0.5, -1), (math.pi / 3, -math.sin(math.pi / 3), math.pi / 3)),  # x = cos t
    ((0.0, 1.0, 0.0, 1.0, 0.5, 1), (5 * math.pi / 3, math.sin(math.pi / 3), 5 * math.pi / 3)),  # the far side
    ((2.0, 1.0, 0.0, 3.0, 2.0, 1), (math.pi / 6, 3.0, math.pi / 2)),  # x = 2 - cos(3 t) reaches its centre
    ((0.0, 0.5, 1.0, 2.0, 0.5, 1), (math.pi, 1.0, 2 * math.pi)),  # the next arrival moving the same way: a full turn
    ((0.3, -0.2, -1.5, 2.0, 0.1, 1), (_SWEEP / 2.0, 2.0 * _W1, _SWEEP)),  # moving left: past the bottom first
]


@pytest.mark.parametrize("arc, expected", CROSSINGS, ids=["from rest", "far side", "shifted centre", "full turn",
                                                           "moving left"])
def test_crossing_by_hand(arc, expected):
    reached, *got = crossing_from(*arc)
    assert reached and got == pytest.approx(expected, rel=1e-15)


def test_crossing_on_arrays_is_the_crossing_row_by_row():
    arcs = np.array([arc for arc, _ in CROSSINGS] + [(0.0, 1.0, 0.0, 1.0, 1.5, 1)]).T  # the last beyond its turn
    reached, *got = crossing_from(*arcs, np)
    assert reached.tolist() == [True] * len(CROSSINGS) + [False]
    np.testing.assert_allclose(np.array(got)[:, :-1], np.array([e for _, e in CROSSINGS]).T, rtol=1e-15)


@pytest.mark.parametrize("target", [1.0, 1.5, -1.0])
def test_no_crossing_at_or_beyond_the_turning_point(target):
    # x = cos t turns at +-1: a target at a turning point is grazed, not passed; beyond it is never reached.
    reached, *_ = crossing_from(0.0, 1.0, 0.0, 1.0, target, -1 if target < 0 else 1)
    assert reached is False


def test_crossing_just_inside_the_turning_point_has_the_energy_speed():
    target = 1.0 - 1e-12
    eps = 1.0 - target  # exact in floating point
    reached, tau, v, _ = crossing_from(0.0, 1.0, 0.0, 1.0, target, -1)
    assert reached and v == pytest.approx(-math.sqrt(2 * eps - eps * eps), rel=1e-12)
    assert tau == pytest.approx(math.acos(1 - eps), rel=1e-6)


def _arc_end(centre, x0, v0, omega, angle):
    """Where the arc about ``centre`` from ``(x0, v0)`` is after sweeping ``angle``: the harmonic motion."""
    u0, w0 = x0 - centre, v0 / omega
    return centre + u0 * np.cos(angle) + w0 * np.sin(angle), omega * (w0 * np.cos(angle) - u0 * np.sin(angle))


def test_arc_maximum_about_a_shifted_centre_from_below_the_top():
    # about c = 0.2 from (x, v) = (0.2 - 0.3, -0.4 w), w = 2: radius 0.5; moving left, the top (0.7) comes
    # after the bottom, i.e. after a phase of 2 pi + atan2(-0.4, -0.3) (clockwise) from the start.
    to_top = math.atan2(-0.4, -0.3) + 2 * math.pi
    short, past = (_arc_end(0.2, -0.1, -0.8, 2.0, to_top + d) for d in (-1e-6, 1e-6))
    assert short[1] > 0 > past[1]  # moving right just before the top, left just after
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, to_top - 1e-6, *short) == short[0] < 0.7  # the larger end
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, to_top + 1e-6, *past) == pytest.approx(0.7, rel=1e-15)
    # half a turn from the start moving left ends at the bottom's far side, short of the top
    half = _arc_end(0.2, -0.1, -0.8, 2.0, math.pi - 1e-3)
    assert arc_maximum(0.2, -0.1, -0.8, 2.0, math.pi - 1e-3, *half) == max(-0.1, half[0])


def test_arc_maximum_is_the_largest_sample_of_random_arcs():
    """Against brute force: the largest of 2_001 samples of each arc, for arcs of every length below a turn,
    starting anywhere on their circle (moving left, right, at rest at the bottom or top)."""
    rng = np.random.default_rng(3)
    n = 100
    centre, omega = rng.uniform(-1, 1, n), rng.uniform(0.5, 3.0, n)
    x0, v0 = centre + rng.uniform(-1, 1, n), rng.uniform(-2, 2, n)
    v0[:10] = 0.0  # at rest: at the bottom (x0 < c) the arc starts moving right, at the top left
    angle = rng.uniform(1e-3, 2 * math.pi - 1e-3, n)
    got = arc_maximum(centre, x0, v0, omega, angle, *_arc_end(centre, x0, v0, omega, angle))
    sampled = np.max(_arc_end(centre, x0, v0, omega, np.linspace(0.0, 1.0, 2_001)[:, None] * angle)[0], axis=0)
    step = angle / 2_000
    assert np.all(got >= sampled - 1e-15)
    assert np.all(got - sampled <= np.hypot(x0 - centre, v0 / omega) * step**2 / 8 + 1e-15)


def test_compensated_sum_of_ten_thousand_tenths_is_the_exactly_rounded_sum():
    total = error = 0.0
    for _ in range(10_000):
        total, error = compensated_add(total, error, 0.1)
    exact = math.fsum([0.1] * 10_000)  # correctly rounded sum of the floats
    assert total + error == exact != sum([0.1] * 10_000)  # the naive sum drifts: the compensation is needed


def test_compensated_add_carries_the_exact_rounding_error_of_each_addition():
    """TwoSum: from ``(a, 0)``, adding ``b`` gives ``total = fl(a + b)`` and ``total + error = a + b`` exactly
    (checked in fractions), whatever the order and the magnitudes, on floats and on arrays alike; two_sum is it."""
    rng = np.random.default_rng(11)
    a, b = (rng.standard_normal(300) * 10.0 ** rng.integers(-30, 30, 300) for _ in range(2))
    total, error = compensated_add(a, np.zeros_like(a), b)
    assert np.array_equal(total, a + b)
    for i in range(300):
        assert Fraction(float(total[i])) + Fraction(float(error[i])) == Fraction(float(a[i])) + Fraction(float(b[i]))
        assert compensated_add(float(a[i]), 0.0, float(b[i])) == (total[i], error[i]) == two_sum(a[i], b[i])


def test_time_to_rest_on_floats_arrays_and_mpmath():
    """The next rest by hand: about c = 0 with w = 1 from x = 0 moving left at 1, a quarter turn to x = -1; about
    c = 1 with w = 2 from x = 1 moving right at 2 (radius 1), a quarter turn (pi/4 s) to x = 2; at rest, now."""
    expected = ([math.pi / 2, math.pi / 4, 0.0], [-1.0, 2.0, 0.3])
    args = ([0.0, 1.0, 0.0], [0.0, 1.0, 0.3], [-1.0, 2.0, 0.0], [1.0, 2.0, 1.0])
    for i in range(3):
        assert time_to_rest(*(a[i] for a in args)) == pytest.approx((expected[0][i], expected[1][i]), rel=1e-15)
    tau, x = time_to_rest(*(np.array(a) for a in args), np)
    np.testing.assert_allclose(tau, expected[0], rtol=1e-15)
    np.testing.assert_allclose(x, expected[1], rtol=1e-15)
    with mpmath.workdps(40):
        tau, x = time_to_rest(*(mpmath.mpf(a[1]) for a in args), mpmath)
        assert abs(tau - mpmath.pi / 4) < mpmath.mpf("1e-39") and x == 2


@pytest.mark.parametrize("args, name", [
    ((1.0, 0.1, 1.0, 1.0), "ratio"), ((1.0, 0.1, 1.0, -0.5), "ratio"), ((1.0, 0.1, 1.0, math.nan), "ratio"),
    ((0.0, 0.1, 1.0, 0.5), "omega"), ((1.0, 0.0, 1.0, 0.5), "distance"), ((1.0, 0.1, -1.0, 0.5), "speed"),
    ((1.0, 0.1, math.inf, 0.5), "speed"), ((1e-300, 1e-300, 1.0, 0.5), "speed / \\(omega \\* distance\\)"),
])
def test_rebound_accumulation_time_rejects_invalid_input(args, name):
    with pytest.raises(ValueError, match=f"^rebound_accumulation_time: {name} = .* is invalid"):
        rebound_accumulation_time(*args)


def test_sample_arcs_is_nan_outside_the_trajectory():
    x, v, a = sample_arcs(np.array([-1.0, 0.0, 1.0, 3.0]), np.array([0.0]), np.array([0.0]), np.array([1.0]),
                          np.array([0.0]), 1.0, 2.0)
    assert np.isnan(x[0]) and np.isnan(x[3])
    assert x[1:3] == pytest.approx([1.0, math.cos(1.0)], rel=1e-15)
    assert (v[2], a[2]) == pytest.approx((-math.sin(1.0), -math.cos(1.0)), rel=1e-15)
