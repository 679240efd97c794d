"""Closed-form kinematics of one harmonic arc.

Between events the motion obeys ``x'' = -omega**2 (x - c)`` with a constant centre
``c`` (0 in free flight, ``+F/K`` or ``-F/K`` in an impulse zone).  In the phase
plane ``(u, w) = (x - c, v / omega)`` the state turns clockwise on a circle at
angular rate ``omega``.  Every event is the arrival at a position ``p`` with a
given direction of motion, so

* the speed there follows from energy, ``v**2 = v0**2 + omega**2 (x0 - p)(x0 + p - 2c)``;
* the time is the clockwise angle between the start and end points divided by
  ``omega``, taken with ``atan2`` of their cross and dot products (no ``arccos``,
  which loses accuracy near a turning point).

No step size and no root finding: each event costs a square root and an ``atan2``.
Each formula is written once for floats and NumPy arrays alike (the argument ``lib``).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

__all__ = [
    "SCALAR",
    "VECTOR",
    "crossing",
    "arc_maximum",
    "compensated_add",
    "time_to_rest",
    "rebound_accumulation_time",
    "sample_arcs",
]

TWO_PI = 2.0 * math.pi


def _pick(condition, yes, no):
    return yes if condition else no


#: the functions the closed forms need, for one float at a time and for NumPy arrays
SCALAR = SimpleNamespace(sqrt=math.sqrt, atan2=math.atan2, hypot=math.hypot, where=_pick, maximum=max)
VECTOR = SimpleNamespace(sqrt=np.sqrt, atan2=np.arctan2, hypot=np.hypot, where=np.where, maximum=np.maximum)


def crossing(centre, x0, v0, omega, target, direction, lib=SCALAR):
    """First arrival at ``x = target`` moving in ``direction`` (+1 right, -1 left).

    Returns ``(reached, tau, v, angle)``: whether the arc passes the target strictly, the time
    after the start, the velocity on arrival and the phase angle swept (``angle = omega * tau``).
    Where ``reached`` is false (the turning point lies short of the target or exactly on it:
    grazing) the other values are meaningless. ``lib`` is :data:`SCALAR` or :data:`VECTOR`.
    """
    v_sq = v0 * v0 + (omega * omega) * ((x0 - target) * (x0 + target - 2.0 * centre))
    reached = v_sq > 0.0
    v1 = direction * lib.sqrt(lib.maximum(v_sq, 0.0))
    u0 = x0 - centre
    q = target - centre
    w0 = v0 / omega
    w1 = v1 / omega
    # Clockwise angle from (u0, w0) to (q, w1), in (0, 2 pi].
    angle = lib.atan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
    angle = angle + TWO_PI * (angle <= 0.0)  # arithmetic, not a branch: floats and arrays alike
    return reached, angle / omega, v1, angle


def arc_maximum(centre, x0, v0, omega, angle, x1, lib=SCALAR):
    """Largest ``x`` on the arc that starts at ``(x0, v0)``, sweeps ``angle`` and ends at ``x1``."""
    u0 = x0 - centre
    w0 = v0 / omega
    start = lib.atan2(w0, u0)  # the top of the circle (x = centre + R) is at phase 0
    to_top = start + TWO_PI * (start < 0.0)
    return lib.where(to_top <= angle, centre + lib.hypot(u0, w0), lib.maximum(x0, x1))


def compensated_add(total, error, term, lib=SCALAR):
    """Neumaier's compensated sum: add ``term`` to ``total + error``; returns the new pair.

    The time of an event is the sum of every duration before it; summed this way it stays
    within an ulp or so of the exact sum however many events there are.
    """
    new = total + term
    error = error + lib.where(abs(total) >= abs(term), (total - new) + term, (term - new) + total)
    return new, error


def time_to_rest(centre: float, x0: float, v0: float, omega: float) -> tuple[float, float]:
    """Time until the velocity next vanishes, and the position there (a turning point)."""
    u0 = x0 - centre
    w0 = v0 / omega
    radius = math.hypot(u0, w0)
    if w0 == 0.0:
        return 0.0, x0
    start = math.atan2(w0, u0)
    if w0 > 0.0:  # moving right: the next rest is the top of the circle, phase 0
        return start / omega, centre + radius
    return (start + math.pi) / omega, centre - radius  # moving left: phase -pi


def rebound_accumulation_time(
    omega: float, distance: float, speed: float, ratio: float, max_terms: int = 1_000_000
) -> float | None:
    """Total time of an infinite sequence of rebounds that shrink geometrically.

    After an impact reverses the velocity, the spring brings the mass back to the
    impact position, which lies ``distance > 0`` from the centre of oscillation
    on the side the spring pushes towards; it arrives with the speed it left with
    and rebounds again with ``ratio = |1 - b| < 1`` times it.  The ``n``-th flight
    lasts ``(2/omega) atan(ratio**n * speed / (omega * distance))``, so the flights
    sum to a finite time (a Zeno point).  Terms are summed directly while their
    argument is above 1/4 and then by the convergent series
    ``sum_m atan(x r**m) = sum_k (-1)**k x**(2k+1) / ((2k+1)(1 - r**(2k+1)))``.

    Returns ``None`` if more than ``max_terms`` direct terms would be needed
    (``ratio`` extremely close to 1).
    """
    if not (distance > 0.0 and speed >= 0.0 and 0.0 <= ratio < 1.0):
        raise ValueError("rebound_accumulation_time needs distance > 0, speed >= 0 and 0 <= ratio < 1")
    x = speed / (omega * distance)
    total = 0.0
    terms = 0
    while x > 0.25:
        if terms >= max_terms:
            return None
        total += math.atan(x)
        x *= ratio
        terms += 1
    if ratio == 0.0:
        return 2.0 * (total + math.atan(x)) / omega
    log_r = math.log(ratio)
    tail = 0.0
    power = x
    for k in range(60):
        n = 2 * k + 1
        term = power / (n * -math.expm1(n * log_r))
        tail += term if k % 2 == 0 else -term
        power *= x * x
        if power < 1e-300:
            break
    return 2.0 * (total + tail) / omega


def sample_arcs(
    t: np.ndarray,
    t_start: np.ndarray,
    centre: np.ndarray,
    x_start: np.ndarray,
    v_start: np.ndarray,
    omega: float,
    t_final: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Displacement, velocity and (smooth) acceleration at times ``t``.

    Arc ``i`` holds on ``[t_start[i], t_start[i+1])``; the last one up to
    ``t_final``.  Times before 0 or after ``t_final`` give NaN.  The acceleration
    excludes the impulsive part at impacts, which the event log carries.
    """
    t = np.asarray(t, dtype=float)
    idx = np.searchsorted(t_start, t, side="right") - 1
    valid = (idx >= 0) & (t <= t_final) & (t >= 0.0)
    idx = np.clip(idx, 0, len(t_start) - 1)
    tau = t - t_start[idx]
    s, c = np.sin(omega * tau), np.cos(omega * tau)
    u0 = x_start[idx] - centre[idx]
    v0 = v_start[idx]
    x = centre[idx] + u0 * c + (v0 / omega) * s
    v = v0 * c - omega * u0 * s
    a = -(omega * omega) * (x - centre[idx])
    nan = np.nan
    return np.where(valid, x, nan), np.where(valid, v, nan), np.where(valid, a, nan)
