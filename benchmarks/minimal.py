"""The floors of the speed table: the least code that computes the solvers' numbers, written out by hand.

* :func:`minimal_cycles`, a minimal closed-form loop for one trajectory, each regular cycle unrolled: the
  same closed forms as :func:`escapement.model.kinematics.crossing` (the same operations in the same order),
  the same compensated time sum and the paper's impact law ``v+ = (1 - b) v-``; no exits, no event log, no
  checks. It gives the cycle table of :func:`escapement.solvers.solve_exact` bit for bit.
* :func:`minimal_events`, the same closed forms as a plain loop over the cycle's four arcs, storing each
  event's time and velocity: the event log, bit for bit.
* :func:`minimal_blocked`, the same numbers the way the solver's kernel computes them: a loop follows the
  velocity alone, then every arc's angle and duration and every event's time are computed on arrays; the
  event log (times, positions, velocities before and after) and the cycle table, bit for bit.
* :func:`numpy_cycles`, the unrolled loop vectorised with NumPy over many trajectories at once, the floor of
  :func:`escapement.solvers.solve_ensemble` (the same numbers in practice: the tests ask for 1e-14).

All assume the regime holds (the paper's cases: ``a1 < 0``, ``a4 <= a2``, ``a4 <= a3``, ``b < 1``, a
release that reaches an impact): outside it their numbers mean nothing.
"""

from __future__ import annotations

import math
from array import array
from typing import NamedTuple

import numpy as np

from escapement.model import Parameters

__all__ = ["PAPER_A", "TWO_PI", "Cycles", "minimal_blocked", "minimal_cycles", "minimal_events", "numpy_cycles"]

TWO_PI = 2.0 * math.pi
#: the model of the paper's Sec. 4 with F = 1 N: the default workload of the scalar floors (the workflow passes
#: the scene of its benchmark instead)
PAPER_A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


class Cycles(NamedTuple):
    """The cycle table of :func:`numpy_cycles` (s, m/s, s, m): a row per trajectory, a column per cycle."""

    impact_time: np.ndarray
    velocity_before_impact: np.ndarray
    period: np.ndarray
    largest_displacement: np.ndarray


def _first_impact(p: Parameters, x0: float, v0: float):
    """From the release to the first impact at a1: the compensated time there (``t_sum``, ``t_err``), the
    velocity before it, and the regular cycle's stage terms ``(k, u, q)`` of its four arcs."""
    w = p.omega
    w2 = w * w
    c = p.zone_offset
    r = 1.0 - p.b
    a1, a2, a3, a4 = p.a1, p.a2, p.a3, p.a4
    sqrt, atan2 = math.sqrt, math.atan2
    t_sum = t_err = x0 * 0
    best = None
    for target, d in ((a1, 1), (a3, -1)):  # the first arc, free: a1 moving right or a3 moving left
        v_sq = v0 * v0 + w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0))
        if v_sq > 0.0:
            v1 = d * sqrt(v_sq)
            u0, q, w0, w1 = x0 - 0.0, target - 0.0, v0 / w, v1 / w
            angle = atan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
            angle = angle + TWO_PI * (angle <= 0.0)
            if best is None or angle / w < best[0]:
                best = (angle / w, v1, target)
    dt, v, x = best
    new = t_sum + dt
    t_err += (t_sum - new) + dt if abs(t_sum) >= abs(dt) else (dt - new) + t_sum
    t_sum = new

    def stage(x_from, target, centre):
        return w2 * ((x_from - target) * (x_from + target - 2.0 * centre)), x_from - centre, target - centre

    k1, u1, q1 = stage(a1, a2, c)
    k2, u2, q2 = stage(a2, a3, 0.0)
    k3, u3, q3 = stage(a3, a4, -c)
    k4, u4, q4 = stage(a4, a1, 0.0)
    if x == a3:  # the impact at a3, the zone to a4, the free swing to a1
        v = r * v
        v1 = -sqrt(v * v + k3)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q3 - u3 * w1, u3 * q3 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        v = v1
        v1 = sqrt(v * v + k4)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q4 - u4 * w1, u4 * q4 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        v = v1
    return t_sum, t_err, v, ((k1, u1, q1), (k2, u2, q2), (k3, u3, q3), (k4, u4, q4))


def minimal_cycles(p: Parameters, x0: float, v0: float, n_cycles: int) -> tuple[array, array, array, array]:
    """Impact times at a1 (s), velocities before them (m/s), periods (s) and amplitudes (m) of ``n_cycles``
    cycles from ``(x0, v0)``, by the minimal closed-form loop.

    The first arc from the release, free (to a1 moving right or a3 moving left, whichever comes first), the
    arcs to the first impact at a1, then per cycle the zone (a1, a2), the free swing over the top to a3, the
    zone (a4, a3) and the free swing to a1. The amplitude is the top of the free swing, the only arc of a
    regular cycle that passes the top of its circle, ``hypot(a2, v / omega)``, or the largest surface
    position if that is larger.
    """
    w = p.omega
    r = 1.0 - p.b
    a2, a3 = p.a2, p.a3
    sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
    t_sum, t_err, v, ((k1, u1, q1), (k2, u2, q2), (k3, u3, q3), (k4, u4, q4)) = _first_impact(p, x0, v0)
    times, speeds, periods, amplitudes = array("d"), array("d"), array("d"), array("d")
    floor = max(a2, a3)
    for _ in range(n_cycles):
        times.append(t_sum + t_err)
        speeds.append(v)
        v = r * v
        # (a1, a2) in the zone
        v1 = sqrt(v * v + k1)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q1 - u1 * w1, u1 * q1 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed = 0.0 + dt
        v = v1
        # a2 to a3, free, over the top
        v1 = -sqrt(v * v + k2)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q2 - u2 * w1, u2 * q2 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        top = 0.0 + hypot(u2, w0)
        v = r * v1
        # (a4, a3) in the zone
        v1 = -sqrt(v * v + k3)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q3 - u3 * w1, u3 * q3 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        v = v1
        # a4 to a1, free
        v1 = sqrt(v * v + k4)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q4 - u4 * w1, u4 * q4 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        v = v1
        periods.append(elapsed)
        amplitudes.append(top if top > floor else floor)
    return times, speeds, periods, amplitudes


def minimal_events(p: Parameters, x0: float, v0: float, n_cycles: int) -> tuple[array, array]:
    """Each event's time (s) and the velocity before it (m/s), from the first impact at a1 over ``n_cycles``
    regular cycles: the event log an event solver returns, by the least code. A plain loop over the cycle's
    four arcs as rows ``(k, u, q, direction, jump)``, the closed form of each arc and the compensated time sum
    written out, the impact law as the factor ``1 - b`` at the arcs that start with an impact, two numbers
    stored per event; no exits, no checks. The floor of :func:`escapement.solvers.solve_exact` as an event
    solver (its event times and velocities, bit for bit)."""
    w = p.omega
    r = 1.0 - p.b
    sqrt, atan2 = math.sqrt, math.atan2
    t_sum, t_err, v, stages = _first_impact(p, x0, v0)
    rows = tuple((k, u, q, d, jump) for (k, u, q), d, jump in zip(stages, (1.0, -1.0, -1.0, 1.0),
                                                                   (True, False, True, False)))
    times, speeds = array("d"), array("d")
    put_t, put_v = times.append, speeds.append
    put_t(t_sum + t_err)
    put_v(v)
    for _ in range(n_cycles):
        for k, u, q, d, jump in rows:
            if jump:
                v = r * v
            v1 = d * sqrt(v * v + k)
            w0, w1 = v / w, v1 / w
            angle = atan2(w0 * q - u * w1, u * q + w0 * w1)
            dt = (angle + TWO_PI * (angle <= 0.0)) / w
            new = t_sum + dt
            t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
            t_sum = new
            put_t(t_sum + t_err)
            put_v(v1)
            v = v1
    return times, speeds


def _speeds(r: float, v: float, k1: float, k2: float, k3: float, k4: float, n_cycles: int):
    """Each event's velocity before it from the first impact at a1, a cycle unrolled: yielded, no call per event."""
    sqrt = math.sqrt
    yield v
    for _ in range(n_cycles):
        v = r * v
        v1 = sqrt(v * v + k1)
        yield v1
        v1 = -sqrt(v1 * v1 + k2)
        yield v1
        v = r * v1
        v1 = -sqrt(v * v + k3)
        yield v1
        v = sqrt(v1 * v1 + k4)
        yield v


def minimal_blocked(p: Parameters, x0: float, v0: float, n_cycles: int) -> tuple[tuple, tuple]:
    """The floor of the kernel since it works in blocks: the loop follows the velocity, the arcs are on arrays."""
    w, r = p.omega, 1.0 - p.b
    t_sum, t_err, v, ((k1, u1, q1), (k2, u2, q2), (k3, u3, q3), (k4, u4, q4)) = _first_impact(p, x0, v0)
    n = 4 * n_cycles + 1
    v_before = np.fromiter(_speeds(r, v, k1, k2, k3, k4, n_cycles), float, n)
    v_after = np.tile([r, 1.0, r, 1.0], n_cycles + 1)[:n] * v_before
    u, q = np.tile([u1, u2, u3, u4], n_cycles), np.tile([q1, q2, q3, q4], n_cycles)
    w0, w1 = v_after[:-1] / w, v_before[1:] / w  # crossing() on arrays, libm's atan2 (NumPy's may differ by an ulp)
    angle = np.fromiter(map(math.atan2, memoryview(w0 * q - u * w1), memoryview(u * q + w0 * w1)), float, n - 1)
    dt = (angle + TWO_PI * (angle <= 0.0)) / w
    t_sum = np.cumsum(np.concatenate(([t_sum], dt)))  # the compensated sum: the running sum, and that of the
    part = t_sum[1:] - t_sum[:-1]  # roundings of its additions (TwoSum)
    t_err = np.cumsum(np.concatenate(([t_err], (t_sum[:-1] - (t_sum[1:] - part)) + (dt - part))))
    t = t_sum + t_err
    arcs = dt.reshape(n_cycles, 4)
    top = 0.0 + np.hypot(u2, v_before[1::4] / w)
    cycles = (t[:-1:4], v_before[:-1:4], arcs[:, 0] + arcs[:, 1] + arcs[:, 2] + arcs[:, 3],
              np.maximum(top, max(p.a2, p.a3)))
    return (t, np.tile([p.a1, p.a2, p.a3, p.a4], n_cycles + 1)[:n], v_before, v_after), cycles


def _numpy_arc(v, k, u, q, omega, direction: float):
    """One arc of every trajectory: ``crossing()`` on arrays with the arc's surface terms ``k, u, q``;
    the velocity on arrival and the time."""
    v1 = np.sqrt(v * v + k)
    if direction < 0:
        np.negative(v1, out=v1)
    w0 = v / omega
    w1 = v1 / omega
    angle = np.arctan2(w0 * q - u * w1, u * q + w0 * w1)
    angle[angle <= 0.0] += TWO_PI
    angle /= omega
    return v1, angle


def _numpy_add(t_sum, t_err, dt):
    """Neumaier's compensated sum, in place (``t_sum >= 0``, ``dt > 0``: ``|t_sum| >= |dt|`` is ``t_sum >= dt``)."""
    new = t_sum + dt
    t_err += np.where(t_sum >= dt, (t_sum - new) + dt, (dt - new) + t_sum)
    t_sum[:] = new


def numpy_cycles(M, K, F, b, a1, a2, a3=None, a4=None, x0=1.0, v0=0.0, *, n_cycles: int) -> Cycles:
    """:func:`minimal_cycles` vectorised over trajectories: the cycle table, each column of shape
    ``(N, n_cycles)``, of every trajectory (the inputs broadcast to ``(N,)``, as for
    :func:`escapement.solvers.solve_ensemble`; ``a3``, ``a4`` default to ``-a1``, ``-a2``).

    The first arc picks, per trajectory, the first of a1 moving right and a3 moving left; the trajectories
    that hit a3 first then take the zone to a4 and the swing to a1; from there every cycle is four arcs of
    every trajectory at once.
    """
    a3 = -np.asarray(a1, dtype=float) if a3 is None else a3
    a4 = -np.asarray(a2, dtype=float) if a4 is None else a4
    M, K, F, b, a1, a2, a3, a4, x0, v0 = (np.array(a, dtype=float).ravel() for a in np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (M, K, F, b, a1, a2, a3, a4, x0, v0))))
    n = len(M)
    omega = np.sqrt(K / M)
    w2 = omega * omega
    c = F / K
    r = 1.0 - b
    # the first arc, free (centre 0): to a1 moving right or to a3 moving left, whichever comes first
    dt = np.full(n, np.inf)
    v = np.zeros(n)
    for target, direction in ((a1, 1.0), (a3, -1.0)):
        v_sq = v0 * v0 + w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0))
        with np.errstate(invalid="ignore"):
            v1, tau = _numpy_arc(v0, w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0)), x0 - 0.0, target - 0.0,
                                 omega, direction)
        take = (v_sq > 0.0) & (tau < dt)
        dt = np.where(take, tau, dt)
        v = np.where(take, v1, v)
    at_a3 = v < 0.0
    t_sum, t_err = np.zeros(n), np.zeros(n)
    _numpy_add(t_sum, t_err, dt)

    def stage(x_from, target, centre):
        return w2 * ((x_from - target) * (x_from + target - 2.0 * centre)), x_from - centre, target - centre

    k1, u1, q1 = stage(a1, a2, c)
    k2, u2, q2 = stage(a2, a3, 0.0)
    k3, u3, q3 = stage(a3, a4, -c)
    k4, u4, q4 = stage(a4, a1, 0.0)
    if at_a3.any():  # the impact at a3, the zone to a4, the free swing to a1
        i = np.flatnonzero(at_a3)
        ts, te = t_sum[i], t_err[i]
        v3, dt = _numpy_arc(r[i] * v[i], k3[i], u3[i], q3[i], omega[i], -1.0)
        _numpy_add(ts, te, dt)
        v1, dt = _numpy_arc(v3, k4[i], u4[i], q4[i], omega[i], 1.0)
        _numpy_add(ts, te, dt)
        t_sum[i], t_err[i], v[i] = ts, te, v1
    times, speeds, periods, amplitudes = (np.empty((n, n_cycles)) for _ in range(4))
    floor = np.maximum(a2, a3)
    for cycle in range(n_cycles):
        times[:, cycle] = t_sum + t_err
        speeds[:, cycle] = v
        v1, dt = _numpy_arc(r * v, k1, u1, q1, omega, 1.0)  # (a1, a2) in the zone
        _numpy_add(t_sum, t_err, dt)
        elapsed = 0.0 + dt
        top = 0.0 + np.hypot(u2, v1 / omega)
        v1, dt = _numpy_arc(v1, k2, u2, q2, omega, -1.0)  # a2 to a3, free, over the top
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        v1, dt = _numpy_arc(r * v1, k3, u3, q3, omega, -1.0)  # (a4, a3) in the zone
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        v, dt = _numpy_arc(v1, k4, u4, q4, omega, 1.0)  # a4 to a1, free
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        periods[:, cycle] = elapsed
        amplitudes[:, cycle] = np.where(top > floor, top, floor)
    return Cycles(impact_time=times, velocity_before_impact=speeds, period=periods, largest_displacement=amplitudes)
