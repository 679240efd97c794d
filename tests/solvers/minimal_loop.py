"""A minimal closed-form loop for the escapement's periodic regime, written out by hand.

The same closed forms as :func:`escapement.model.kinematics.crossing` (the same operations in the
same order), the same compensated time sum and the paper's impact law ``v+ = (1 - b) v-``, for one
regular cycle after another: the first arc from the release (to a1 moving right or a3 moving
left, whichever comes first), the arcs to the first impact at a1, then per cycle the zone
(a1, a2), the free swing over the top to a3, the zone (a4, a3) and the free swing to a1. No
exits, no event log, no checks: it assumes the regime holds (the paper's cases). The amplitude is
the top of the free swing, the only arc of a regular cycle that passes the top of its circle,
``hypot(a2, v / omega)``, or the largest surface position if that is larger.

It is the floor the exact solver is measured against, and a second path to its cycle table: the
tests compare the two number by number.
"""

from __future__ import annotations

import math
from array import array

TWO_PI = 2.0 * math.pi


def minimal_cycles(p, x0: float, v0: float, n_cycles: int) -> tuple[array, array, array, array]:
    """Impact times at a1, velocities before them, periods and amplitudes of ``n_cycles`` cycles."""
    w = p.omega
    w2 = w * w
    c = p.zone_offset
    r = 1.0 - p.b
    a1, a2, a3, a4 = p.a1, p.a2, p.a3, p.a4
    sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
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
