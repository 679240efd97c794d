"""The accumulation time of the rebounds for 1 < b < 2: S(x, r) = sum_{n>=0} atan(x r**n), r = b - 1, against
references at 30 digits computed by mpmath without the code under test: a direct sum while the argument is at least
1e-6, then the tail ``sum_k (-1)**k y**(2k+1) / ((2k+1)(1 - r**(2k+1)))`` cut after three terms (an error below
y**7 / (7 (1 - r**7))); for r >= 0.99, mpmath's own Euler-Maclaurin summation (``mpmath.sumem``) with the integral
``int_0^inf atan(x e^(-lam t)) dt = Ti2(x) / lam``, ``lam = -ln r``, ``Ti2(x) = Im Li2(i x)`` (mpmath's polylog).
"""

import math
import types

import mpmath
import pytest

from escapement.model import kinematics
from escapement.model.kinematics import rebound_accumulation_time

#: the arguments x = speed / (omega * distance): small (power series), near 1/4 and 1 (branch ends), large
ARGUMENTS = (1e-3, 0.2, 0.25, 0.26, 0.9, 1.0, 1.1, 3.0, 1e3)


def direct_reference(x: float, r: float) -> mpmath.mpf:
    with mpmath.workdps(30):
        x, r = mpmath.mpf(x), mpmath.mpf(r)
        total, y = mpmath.mpf(0), x
        stop = mpmath.mpf("1e-6")
        while y >= stop:  # at most ln(x / 1e-6) / -ln(r) terms: 2.1e4 for x = 1e3, r = 0.999
            total += mpmath.atan(y)
            y *= r
        return total + y / (1 - r) - y**3 / (3 * (1 - r**3)) + y**5 / (5 * (1 - r**5))


def ti2(x) -> mpmath.mpf:
    """The inverse tangent integral, Ti2(x) = Im Li2(i x)."""
    return mpmath.im(mpmath.polylog(2, 1j * mpmath.mpf(x)))


def euler_maclaurin_reference(x: float, r: float) -> mpmath.mpf:
    with mpmath.workdps(30):
        x, r = mpmath.mpf(x), mpmath.mpf(r)
        lam = -mpmath.log(r)
        return mpmath.sumem(lambda n: mpmath.atan(x * mpmath.exp(-lam * n)), [0, mpmath.inf], integral=ti2(x) / lam)


def computed(x: float, r: float) -> float:
    """S(x, r) through the public function: omega = distance = 1 make x = speed exactly."""
    return rebound_accumulation_time(1.0, 1.0, x, r) / 2.0


def relative_error(value: float, reference) -> float:
    return float(abs(mpmath.mpf(value) - reference) / reference)


# 0.9048 and 0.9049 bracket exp(-0.1), where the Euler-Maclaurin branch takes over; at 0.75 that branch would lose
# digits (its truncation grows like lam**16): a branch point moved down to it fails here. Deeper in that branch
# (r = 0.99) only x = 1/4 is a branch end. The huge arguments take up to ln(1e300 / 1e-6) / -ln(0.9) = 6700 terms
# in the reference, 60 operations in the code.
@pytest.mark.parametrize("r, x", [(r, x) for r in (1e-10, 0.5, 0.75, 0.9048, 0.9049) for x in ARGUMENTS]
                         + [(0.99, x) for x in (1e-3, 0.25, 0.26, 1.0, 1e3)]
                         + [(r, x) for r in (1e-10, 0.5) for x in (1e100, 1e300)] + [(0.9, 1e300)])
def test_against_a_direct_30_digit_sum(r, x):
    assert relative_error(computed(x, r), direct_reference(x, r)) < 1e-15


@pytest.mark.parametrize("x", (1e-3, 0.26, 1.0, 3.0, 1e300))
@pytest.mark.parametrize("r", [0.999, 1 - 1e-6, 1 - 1e-12])
def test_against_mpmath_euler_maclaurin(r, x):
    assert relative_error(computed(x, r), euler_maclaurin_reference(x, r)) < 1e-15


def test_ratio_zero_and_speed_zero():
    assert computed(2.0, 0.0) == math.atan(2.0) and computed(0.0, 0.5) == 0.0 == computed(0.0, 1 - 1e-12)


@pytest.mark.parametrize("x", [1e-3, 0.5, 1.0, 1e3])
def test_b_two_minus_1e_12_follows_the_leading_asymptotics(x):
    # r = b - 1 with b = 2 - 1e-12. Euler-Maclaurin: S = Ti2(x)/lam + atan(x)/2 + lam x / (12 (1 + x**2)) + ...,
    # the third term below 1e-24 of S here, so the first two give S to double precision.
    b = 2.0 - 1e-12
    r = abs(1.0 - b)
    with mpmath.workdps(30):
        lam = -mpmath.log(mpmath.mpf(r))
        leading = ti2(x) / lam + mpmath.atan(x) / 2
        assert lam * x / (12 * (1 + x * x)) / leading < mpmath.mpf("1e-24")
    value = computed(x, r)
    assert math.isfinite(value) and relative_error(value, leading) < 1e-15
    t = rebound_accumulation_time(1.3, 0.1, 0.13 * x, r)
    assert math.isfinite(t) and t == pytest.approx(2 * float(leading) / 1.3, rel=1e-14)


@pytest.mark.parametrize("x", [0.25, 1.0])  # power series | direct sum or Euler-Maclaurin; direct sum | reflection
@pytest.mark.parametrize("r", [0.5, 0.9, 0.99])
def test_continuous_across_the_argument_branches(x, r):
    # S is smooth; its relative change over one ulp of x is below 1e-16
    assert computed(math.nextafter(x, 2.0), r) == pytest.approx(computed(x, r), rel=1e-15)


@pytest.mark.parametrize("x", [0.3, 1.0, 1e3])
def test_continuous_across_the_ratio_branches(x):
    # lam = -log1p(r - 1) = 0.1 at r = exp(-0.1): Euler-Maclaurin at and above, the direct sum below
    edge = math.exp(-0.1)
    for r in (math.nextafter(edge, 0.0), edge, math.nextafter(edge, 1.0)):
        assert computed(x, r) == pytest.approx(float(direct_reference(x, r)), rel=1e-15)


def test_inverse_tangent_integral_against_mpmath():
    for y in (1e-300, 1e-8, 0.1, 0.25, 0.5, math.nextafter(0.5, 1.0), 0.7, 0.99, 1.0, 1.01, 2.0, 1e3, 1e300):
        assert kinematics._inverse_tangent_integral(y) == pytest.approx(float(ti2(y)), rel=4e-16)


def test_euler_maclaurin_remainder_constant():
    # The docstring's C = (1/2) int_R |sech^(15)| = int_0^inf |sech^(15)|: the total variation of sech^(14) on
    # [0, inf), summed between the zeros of sech^(15). The derivatives come from the reciprocal of the Taylor
    # series of cosh(u + h) = cosh(u) cosh(h) + sinh(u) sinh(h) in h.
    def sech_derivative(m, u):
        c = [(mpmath.cosh(u) if j % 2 == 0 else mpmath.sinh(u)) / mpmath.factorial(j) for j in range(m + 1)]
        d = [1 / c[0]]
        for n in range(1, m + 1):
            d.append(-sum(c[j] * d[n - j] for j in range(1, n + 1)) / c[0])
        return mpmath.factorial(m) * d[m]

    with mpmath.workdps(15):  # the heights to 5 digits
        grid = [mpmath.mpf(k) / 4 for k in range(1, 36)]  # a zero per interval at most: 7 found are all 7
        values = [sech_derivative(15, u) for u in grid]
        zeros = [mpmath.findroot(lambda u: sech_derivative(15, u), (a, b), solver="anderson")
                 for a, b, fa, fb in zip(grid, grid[1:], values, values[1:]) if fa * fb < 0]
        assert len(zeros) == 7  # sech^(15) is odd with 15 real zeros
        heights = [sech_derivative(14, z) for z in [mpmath.mpf(0)] + zeros] + [mpmath.mpf(0)]
        total_variation = sum(abs(b - a) for a, b in zip(heights, heights[1:]))
        assert 6.2640e8 < total_variation < 6.2642e8
        bound = abs(mpmath.bernoulli(16)) / mpmath.factorial(16) * total_variation * mpmath.mpf("0.1") ** 16
        assert bound / ti2(0.25) < mpmath.mpf("8.7e-20")


@pytest.mark.parametrize("r", [0.0, 1e-10, 0.5, 0.9048, 0.999999, math.nextafter(1.0, 0.0)])
@pytest.mark.parametrize("x", [1e-3, 0.3, 1e3, 1e300])
def test_a_bounded_number_of_elementary_functions(monkeypatch, r, x):
    """At most 64 calls of the functions that cost most, however large x and however close r is to 1."""
    calls = []
    counted = types.SimpleNamespace(**vars(math))
    for name in ("atan", "expm1", "log", "log1p", "pow", "exp"):
        setattr(counted, name, lambda *args, f=getattr(math, name): calls.append(f) or f(*args))
    monkeypatch.setattr(kinematics, "math", counted)
    rebound_accumulation_time(1.0, 1.0, x, r)
    assert len(calls) <= 64
