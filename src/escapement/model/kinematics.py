"""Closed-form kinematics of one harmonic arc ``x'' = -omega**2 (x - c)`` (centre 0 free, ``+-F/K`` in an impulse
zone) for floats, NumPy arrays and (where said) mpmath, and the sum of a chattering impact's rebounds
(:func:`rebound_accumulation_time`, hand-written: no library sums ``atan(x r**n)`` in bounded time).
"""

from __future__ import annotations

import math
from fractions import Fraction
from types import ModuleType

import mpmath
import numpy as np

from .arguments import Numeric

__all__ = ["arc_terms", "crossing", "arc_maximum", "compensated_add", "time_to_rest", "two_sum",
           "rebound_accumulation_time", "sample_arcs"]

TWO_PI = 2.0 * math.pi


def arc_terms(centre: Numeric, x0: Numeric, omega: Numeric, target: Numeric) -> tuple[Numeric, Numeric, Numeric]:
    """The terms of :func:`crossing` that depend on positions only: ``x0 - c``, ``target - c`` and
    ``k = omega**2 (x0 - target)(x0 + target - 2 c)``, by energy the arrival's ``v**2 - v0**2``."""
    return x0 - centre, target - centre, (omega * omega) * ((x0 - target) * (x0 + target - 2.0 * centre))


def crossing(u0: Numeric, q: Numeric, k: Numeric, v0: Numeric, omega: Numeric, direction: Numeric,
             xp: ModuleType = math) -> tuple[Numeric, Numeric, Numeric, Numeric]:
    """First arrival at ``target = c + q`` moving in ``direction`` (+1 right, -1 left) of an arc from ``x0 = c + u0``
    at ``v0`` (``k`` from :func:`arc_terms`): ``(reached, tau, v, angle)``, whether it passes the target strictly
    (else it grazes or turns short, and the rest is meaningless), the time, the arrival velocity and the phase angle
    swept, from ``atan2`` (``arccos`` loses accuracy near a turn). ``xp`` is :mod:`math` or :mod:`numpy`."""
    v_sq = v0 * v0 + k
    v1 = direction * xp.sqrt(abs(v_sq))
    w0, w1 = v0 / omega, v1 / omega
    # Clockwise angle from (u0, w0) to (q, w1), in (0, 2 pi].
    angle = xp.atan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
    angle = angle + TWO_PI * (angle <= 0.0)  # arithmetic, not a branch: floats and arrays alike
    return v_sq > 0.0, angle / omega, v1, angle


def arc_maximum(centre: Numeric, x0: Numeric, v0: Numeric, omega: Numeric, angle: Numeric, x1: Numeric,
                v1: Numeric) -> Numeric:
    """Largest ``x`` on the arc from ``(x0, v0)`` sweeping ``angle`` (rad) to ``(x1, v1)``: the top of its circle
    if it passes it (starting right or at rest at the bottom: it ends moving left or turns more than half a circle;
    starting left: both), else the larger end."""
    u0 = x0 - centre
    right = (v0 > 0.0) | ((v0 == 0.0) & (u0 < 0.0))
    left_at_end = v1 < 0.0
    more_than_half = angle > math.pi
    passes = np.where(right, left_at_end | more_than_half, left_at_end & more_than_half)
    return np.where(passes, centre + np.hypot(u0, v0 / omega), np.maximum(x0, x1))


def two_sum(a: Numeric, b: Numeric) -> tuple[Numeric, Numeric]:
    """Knuth's TwoSum, without a branch (floats or arrays): ``s = fl(a + b)`` and ``e`` with ``s + e == a + b``."""
    s = a + b
    part = s - a
    return s, (a - (s - part)) + (b - part)


def compensated_add(total: Numeric, error: Numeric, term: Numeric) -> tuple[Numeric, Numeric]:
    """``total + error + term`` as a new compensated pair (:func:`two_sum`): an event's time, the sum of every
    duration before it, stays within an ulp or so of the exact sum however many events there are."""
    total, rounding = two_sum(total, term)
    return total, error + rounding


def time_to_rest(centre: Numeric, x0: Numeric, v0: Numeric, omega: Numeric,
                 xp: ModuleType = math) -> tuple[Numeric, Numeric]:
    """Time until the velocity next vanishes, and the position there: the top of the circle moving right, its
    bottom moving left, ``(0, x0)`` at rest. ``xp`` is :mod:`math`, :mod:`numpy` or :mod:`mpmath`."""
    u0, w0 = x0 - centre, v0 / omega
    radius = xp.hypot(u0, w0)
    right, left, rest = w0 > 0.0, w0 < 0.0, w0 == 0.0
    angle = (xp.atan2(w0, u0) + xp.pi * left) * (right | left)  # arithmetic, not a branch: any of the three
    return angle / omega, (centre + radius) * right + (centre - radius) * left + x0 * rest


def _sech_even_derivatives(max_order: int) -> list[list[int]]:
    """Integer coefficients ``a[i][j]``, ``sech^(2i)(u) = sum_j a[i][j] sech(u)**(2j+1)``, for ``2i <= max_order``:
    with ``s = sech u``, ``t = tanh u``, ``(s**n)' = -n s**n t`` and ``(t s**n)' = (n+1) s**(n+2) - n s**n``."""
    even = [[1]]
    for _ in range(max_order // 2):
        odd = [-(2 * j + 1) * a for j, a in enumerate(even[-1])]  # coefficients of t s**(2j+1)
        nxt = [0] * (len(odd) + 1)
        for j, a in enumerate(odd):
            nxt[j + 1] += (2 * j + 2) * a
            nxt[j] -= (2 * j + 1) * a
        even.append(nxt)
    return even


_EM_TERMS, _EM_LAMBDA_MAX = 8, 0.1  #: Euler-Maclaurin terms kept, and the largest lambda = -log(ratio) they serve
_SERIES_ARGUMENT_MAX = 0.25  #: arguments at or below this are summed by the power series in the argument
_SERIES_TERMS = 16  # x**(2k) <= 16**-k < 1e-18 for k = 15
_TI2_DENOMINATORS = tuple((2 * k + 1) * (2 * k + 1) for k in range(25))  # 4**-k / (2k+1)**2 < 2e-18 for k = 24
_CLAUSEN_TERMS = 20
_BERNOULLI = [Fraction(*mpmath.bernfrac(n)) for n in range(2 * _CLAUSEN_TERMS + 1)]  # exact
#: ``|B_2n| / (2n (2n+1)!)``, n = 1 .. _CLAUSEN_TERMS: the series of the Clausen function
_CLAUSEN_COEFFICIENTS = tuple(float(abs(_BERNOULLI[2 * n]) / (2 * n * math.factorial(2 * n + 1)))
                              for n in range(1, _CLAUSEN_TERMS + 1))
#: ``(B_2k / (2k)!, coefficients of sech^(2k-2))``, k = 1 .. _EM_TERMS
_EM_CORRECTIONS = tuple((float(_BERNOULLI[2 * k] / math.factorial(2 * k)), tuple(float(a) for a in coefficients))
                        for k, coefficients in enumerate(_sech_even_derivatives(2 * _EM_TERMS - 2), start=1))
_DIRECT_TERMS_MAX = 16  #: direct terms of a sum of arguments <= 1/ratio at lambda > 0.1: 1 + ln(4) / 0.1 < 15


def _clausen2(theta: float) -> float:
    """Clausen's function ``Cl2(theta) = -int_0^theta ln(2 sin(t/2)) dt`` for ``0 < theta <= 2.22``, by the series
    ``theta - theta ln(theta) + sum_n |B_2n| theta**(2n+1) / (2n (2n+1)!)``, whose terms beyond 20 are below 1e-20.
    """
    theta_sq, tail = theta * theta, 0.0
    for c in reversed(_CLAUSEN_COEFFICIENTS):
        tail = (tail + c) * theta_sq
    return theta - theta * math.log(theta) + theta * tail


def _inverse_tangent_integral(y: float) -> float:
    """``Ti2(y) = int_0^y atan(u) / u du`` for ``y >= 0``, to a few units of 2**-53 relative: its power series for
    ``y <= 1/2``, ``Ti2(1/y) + (pi/2) ln(y)`` for ``y > 1``, and between, with ``theta = atan(y)``,
    ``theta ln(tan theta) + (Cl2(2 theta) + Cl2(pi - 2 theta)) / 2`` (Lewin, *Polylogarithms and associated
    functions*, 1981, ch. 2)."""
    if y > 1.0:
        return _inverse_tangent_integral(1.0 / y) + 0.5 * math.pi * math.log(y)
    if y > 0.5:
        theta = math.atan(y)
        return theta * math.log(y) + 0.5 * (_clausen2(2.0 * theta) + _clausen2(math.pi - 2.0 * theta))
    return _alternating_series(y, _TI2_DENOMINATORS)


def _series_denominators(log_r: float) -> tuple[float, ...]:
    """``(2k+1)(1 - r**(2k+1))`` for ``k < 16``, from ``log_r = ln(r) < 0`` (``expm1``: exact as ``r -> 1``)."""
    return tuple((2 * k + 1) * -math.expm1((2 * k + 1) * log_r) for k in range(_SERIES_TERMS))


def _alternating_series(x: float, denominators: tuple[float, ...]) -> float:
    """``sum_k (-1)**k x**(2k+1) / denominators[k]``. With :func:`_series_denominators` of ``r`` and ``x <= 1/4``,
    ``sum_{n>=0} atan(x r**n)`` (the power series of ``atan`` summed over ``n``) within ``16**-16`` relative."""
    x_sq, total = x * x, 0.0
    for denominator in reversed(denominators):
        total = total * -x_sq + 1.0 / denominator
    return x * total


def _atan_direct_sum(w: float, ratio: float, denominators: tuple[float, ...]) -> float:
    """``sum_{n>=0} atan(w r**n)`` for ``0 <= w <= ~1/r`` and ``-ln(r) > 0.1``: the terms with arguments above 1/4
    directly, the rest by the power series."""
    total = 0.0
    for _ in range(_DIRECT_TERMS_MAX):
        if w <= _SERIES_ARGUMENT_MAX:
            return total + _alternating_series(w, denominators)
        total += math.atan(w)
        w *= ratio
    raise ArithmeticError(f"the direct sum of atan(w r**n) for r = {ratio!r} kept arguments above "
                          f"{_SERIES_ARGUMENT_MAX} after {_DIRECT_TERMS_MAX} terms; its argument was out of range")


def _atan_euler_maclaurin_sum(x: float, lam: float) -> float:
    """``sum_{n>=0} atan(x exp(-lam n))`` for ``x > 1/4`` and ``0 < lam <= 0.1`` by Euler-Maclaurin.

    With ``f(t) = g(lam t)``, ``g(s) = atan(x exp(-s))`` and ``L = ln x``: ``g'(s) = -sech(s - L) / 2``,
    ``int_0^inf f = Ti2(x) / lam`` and ``f^(2k-1)(0) = -lam**(2k-1) sech^(2k-2)(L) / 2``, so
    ``S = Ti2(x)/lam + atan(x)/2 + (1/2) sum_{k=1}^{8} B_2k/(2k)! lam**(2k-1) sech^(2k-2)(L) + R``, with
    (DLMF 2.10.1) ``|R| <= |B_16|/16! lam**15 C``, ``C = (1/2) int_R |sech^(15)| = 6.26410e8`` (the total variation
    of ``sech^(14)`` on ``[0, inf)``); as ``S > 0.2465/lam``, ``|R| / S <= 8.7e-20`` at ``lam <= 0.1``.
    """
    s = 2.0 / (x + 1.0 / x)  # sech(ln x)
    s_sq, correction, lam_power = s * s, 0.0, lam
    for weight, coefficients in _EM_CORRECTIONS:
        poly = 0.0
        for a in reversed(coefficients):
            poly = poly * s_sq + a
        correction += weight * lam_power * s * poly
        lam_power *= lam * lam
    return _inverse_tangent_integral(x) / lam + (0.5 * math.atan(x) + 0.5 * correction)


def _atan_geometric_sum(x: float, ratio: float) -> float:
    """``S(x, r) = sum_{n>=0} atan(x r**n)`` for ``x >= 0`` and ``0 <= r < 1``, in a bounded number of operations.

    For ``x > 1`` at ``lam = -ln r > 0.1`` the ``N = ceil(ln(x)/lam)`` terms above 1 become, by
    ``atan(y) = pi/2 - atan(1/y)``, ``N pi/2 - S(z, r) + S(z r**N, r)`` with ``z = 1/(x r**(N-1))`` in ``[r, 1]``,
    and the rest is ``S(x r**N, r)``. At most 64 evaluations of ``atan``, ``expm1`` and ``log``, whatever ``x`` and
    ``r``; truncation below 1e-18 relative, rounding a few units of 2**-53 (below 4e-16 against 30-digit sums).
    """
    if x == 0.0:
        return 0.0
    if ratio == 0.0:
        return math.atan(x)
    log_r = math.log1p(ratio - 1.0) if ratio >= 0.5 else math.log(ratio)
    lam = -log_r
    if x <= _SERIES_ARGUMENT_MAX:
        return _alternating_series(x, _series_denominators(log_r))
    if lam <= _EM_LAMBDA_MAX:
        return _atan_euler_maclaurin_sum(x, lam)
    denominators = _series_denominators(log_r)
    if x <= 1.0:
        return _atan_direct_sum(x, ratio, denominators)
    n = max(1, math.ceil(math.log(x) / lam))  # at most ln(1.8e308) / 0.1 < 7100
    half = (n - 1) // 2
    # x r**(N-1) in two factors, each >= r**(N-1) > 1/x: neither underflows
    w = (x * ratio**half) * ratio ** (n - 1 - half)
    return (n * (0.5 * math.pi) - _atan_direct_sum(1.0 / w, ratio, denominators)
            + _atan_direct_sum(ratio / x, ratio, denominators) + _atan_direct_sum(w * ratio, ratio, denominators))


def rebound_accumulation_time(omega: float, distance: float, speed: float, ratio: float) -> float:
    """Total time of the rebounds, shrinking geometrically, after an impact that reverses the velocity (a Zeno point):
    at the impact position ``distance > 0`` from the centre, rebounding with ``ratio = |1 - b| < 1`` times its speed,
    the ``n``-th flight lasts ``(2/omega) atan(ratio**n x)``, ``x = speed / (omega * distance)``."""
    for name, value, holds, requirement in (
        ("omega", omega, math.isfinite(omega) and omega > 0.0, "finite and > 0 (rad/s)"),
        ("distance", distance, math.isfinite(distance) and distance > 0.0, "finite and > 0 (m)"),
        ("speed", speed, math.isfinite(speed) and speed >= 0.0, "finite and >= 0 (m/s)"),
        ("ratio", ratio, 0.0 <= ratio < 1.0, "in [0, 1) (|1 - b| of an impact that reverses the velocity)"),
    ):
        if not holds:
            raise ValueError(f"rebound_accumulation_time: {name} = {value!r} is invalid: {name} must be {requirement}")
    x = speed / omega / distance  # in two steps: omega * distance may underflow
    if not math.isfinite(x):
        raise ValueError(f"rebound_accumulation_time: speed / (omega * distance) = {x!r} is invalid: it must be "
                         f"finite (speed = {speed!r}, omega = {omega!r}, distance = {distance!r})")
    return 2.0 * _atan_geometric_sum(x, ratio) / omega


def sample_arcs(t: np.ndarray, t_start: np.ndarray, centre: np.ndarray, x_start: np.ndarray, v_start: np.ndarray,
                omega: float, t_final: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Displacement, velocity and smooth acceleration (the impacts' impulses are the event log's) at times ``t``:
    arc ``i`` holds from ``t_start[i]``, the last one up to ``t_final``; NaN before 0 or after ``t_final``."""
    t = np.asarray(t, dtype=float)
    idx = np.searchsorted(t_start, t, side="right") - 1
    valid = (idx >= 0) & (t <= t_final) & (t >= 0.0)
    idx = np.clip(idx, 0, len(t_start) - 1)
    tau = t - t_start[idx]
    s, c = np.sin(omega * tau), np.cos(omega * tau)
    u0, v0 = x_start[idx] - centre[idx], v_start[idx]
    x = centre[idx] + u0 * c + (v0 / omega) * s
    v = v0 * c - omega * u0 * s
    a = -(omega * omega) * (x - centre[idx])
    return np.where(valid, x, np.nan), np.where(valid, v, np.nan), np.where(valid, a, np.nan)
