"""The escapement error: Airy's theorem in the model, and the rate of the limit cycle."""

from __future__ import annotations

import math

import pytest
from scipy.integrate import quad

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper.corrected import zone_period_change
from escapement.studies.escapement_error import (daily_rate, first_order_zone_change, limit_cycle_rate,
                                                 rate_against_amplitude)

#: zones (a1, a2): symmetric about the equilibrium, before it, after it (moving right)
CENTRED, BEFORE, AFTER = (-0.1, 0.1), (-0.2, -0.05), (-0.02, 0.2)


def zone_cost_by_quadrature(a: float, c: float, amplitude: float, omega: float) -> float:
    """d(dT2)/df at f = 0, by numerical quadrature of the phase-rate defect x / (w**2 A**2) over the
    zone's time, dt = dx / v, v = w sqrt(A**2 - x**2) (independent of the closed form)."""
    integrand = lambda x: x / (omega**2 * amplitude**2) / (omega * math.sqrt(amplitude**2 - x * x))  # noqa: E731
    return quad(integrand, a, c, epsabs=1e-14, epsrel=1e-12)[0]


@pytest.mark.parametrize("zone", [CENTRED, BEFORE, AFTER], ids=["centred", "before", "after"])
def test_the_first_order_zone_cost_against_quadrature(zone):
    a, c = zone
    for amplitude, omega in ((1.0, 1.0), (0.5, 3.0)):
        expected = zone_cost_by_quadrature(a, c, amplitude, omega)
        assert first_order_zone_change(a, c, amplitude, omega, 1.0) == pytest.approx(expected, rel=1e-10, abs=1e-15)


def _zone_cost_over_f(zone, f):  # dT2 / f of the exact zone time (corrected Eq. (25)), entering the zone at 1 m/s
    p = Parameters(M=1.0, K=1.0, F=f, b=0.1, a1=zone[0], a2=zone[1])
    return zone_period_change(1.0 / (1 - p.b), p) / f


def test_airy_a_centred_impulse_changes_the_period_only_at_second_order_an_off_centre_one_at_first():
    ratios = [_zone_cost_over_f(CENTRED, f) for f in (1e-2, 1e-3, 1e-4)]
    # dT2 / f -> 0 linearly in f: each tenfold smaller force gives a tenfold smaller ratio
    assert abs(ratios[2]) < 1e-6
    assert [ratios[1] / ratios[0], ratios[2] / ratios[1]] == pytest.approx([0.1, 0.1], rel=0.02)
    for zone, sign in ((BEFORE, -1), (AFTER, 1)):  # before the equilibrium shorter, after it longer
        first_order = zone_cost_by_quadrature(*zone, math.hypot(zone[0], 1.0), 1.0)  # entering at a1 with 1 m/s
        assert math.copysign(1, first_order) == sign
        for f in (1e-3, 1e-4):
            assert _zone_cost_over_f(zone, f) == pytest.approx(first_order, rel=20 * f)


def test_the_limit_cycle_period_is_the_natural_one_plus_the_impacts_and_zones():
    # a clock that swings slow loses time
    assert (daily_rate(2.0, 2.0), daily_rate(1.0, 2.0)) == (0.0, pytest.approx(86_400.0))
    assert daily_rate(2.0 * (1 + 1e-6), 2.0) == pytest.approx(-0.0864, rel=1e-5)
    r = limit_cycle_rate(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05))
    assert r.period_formula == pytest.approx(r.period, rel=1e-13)
    assert r.rate == pytest.approx(daily_rate(r.period, 2 * math.pi), rel=1e-15)
    # the paper's 6.2832 s is the natural period; the replicated cycle is about 171 s/day slow
    assert -172.0 < r.rate < -171.0
    assert r.rate_impacts + r.rate_zones == pytest.approx(r.rate, rel=2e-3)  # first order in dT / T0
    rates = rate_against_amplitude(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), [0.25, 0.5, 1.0, 2.0])
    assert [r.largest_displacement for r in rates] == sorted(r.largest_displacement for r in rates)  # more force


def test_without_a_limit_cycle_the_rate_is_nan_and_the_status_says_how_the_motion_ends():
    # the constant term of the map (16) is negative: F = 0.05 N with an asymmetric geometry, no fixed point
    r = limit_cycle_rate(Parameters(M=1.0, K=1.0, F=0.05, b=0.1, a1=-0.3, a2=-0.25, a3=0.1, a4=0.05))
    assert r.status is Status.STOPPED and "F = 0.05" in r.message and math.isnan(r.rate)
    # b = 1: the impact stops the mass at a1 = 0.05 m, inside the zone (0.05, 0.2) m; there it swings about
    # F/K = 0.1 m with amplitude 0.05 m and turns at 0.15 m, short of the zone's end
    r = limit_cycle_rate(Parameters(M=1.0, K=1.0, F=0.1, b=1.0, a1=0.05, a2=0.2))
    assert r.status is Status.TURNED_BACK_IN_ZONE and math.isnan(r.largest_displacement)
