"""A high-precision reference in mpmath (50 significant digits by default).

An independent second implementation of the escapement regime for reference
values: the speed at each surface from energy, the time from the phase angles
``atan2(w, u)`` of the start and end points (the float solver uses the angle
between them instead), all in ``dps``-digit arithmetic.  It covers the regime
only: it raises ``ValueError`` if the motion leaves it.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from .parameters import Parameters

__all__ = ["HighPrecisionCycles", "solve_high_precision"]


@dataclass(frozen=True)
class HighPrecisionCycles:
    """Per-cycle values as mpmath numbers; cycle k starts at the k-th impact at a1."""

    impact_time: list
    velocity_before_impact: list
    period: list
    amplitude: list
    dps: int


def solve_high_precision(params: Parameters, x0: float, v0: float = 0.0, n_cycles: int = 50, dps: int = 50):
    """Impacts at a1 for ``n_cycles`` complete cycles, released from ``(x0, v0)`` at t = 0."""
    with mpmath.workdps(dps + 10):
        mpf = mpmath.mpf
        M, K, F, b = mpf(params.M), mpf(params.K), mpf(params.F), mpf(params.b)
        a1, a2, a3, a4 = mpf(params.a1), mpf(params.a2), mpf(params.a3), mpf(params.a4)
        w = mpmath.sqrt(K / M)
        c = F / K
        two_pi = 2 * mpmath.pi

        def arrive(centre, x, v, target, direction):
            """Time and velocity of the first arrival at ``target`` moving in ``direction``."""
            v_sq = v**2 + w**2 * ((x - centre) ** 2 - (target - centre) ** 2)
            if v_sq <= 0:
                raise ValueError(f"the motion leaves the escapement regime near x = {float(target)}")
            v_end = direction * mpmath.sqrt(v_sq)
            start = mpmath.atan2(v / w, x - centre)
            end = mpmath.atan2(v_end / w, target - centre)
            angle = (start - end) % two_pi  # the phase point turns clockwise
            if angle == 0:
                angle = two_pi
            return angle / w, v_end

        t, x, v = mpf(0), mpf(x0), mpf(v0)
        # From release, the free swing meets first either a1 moving right or a3 moving left.
        options = []
        for target, direction in ((a1, 1), (a3, -1)):
            try:
                options.append((*arrive(0, x, v, target, direction), target, direction))
            except ValueError:
                pass
        if not options:
            raise ValueError("the initial swing never reaches an impact position")
        dt, v, x, direction = min(options, key=lambda o: o[0])
        t += dt
        times, speeds, maxima = [], [], []
        cycle_max = None
        while len(times) < n_cycles + 1:
            if direction == 1:  # impact at a1, zone to a2, free to a3
                times.append(t)
                speeds.append(v)
                if cycle_max is not None:
                    maxima.append(cycle_max)
                v = (1 - b) * v
                dt, v = arrive(c, a1, v, a2, 1)
                t += dt
                cycle_max = mpmath.sqrt(a2**2 + (v / w) ** 2)  # the free swing's right turning point
                dt, v = arrive(0, a2, v, a3, -1)
                t += dt
                x, direction = a3, -1
            else:  # impact at a3, zone to a4, free to a1
                v = (1 - b) * v
                dt, v = arrive(-c, a3, v, a4, -1)
                t += dt
                dt, v = arrive(0, a4, v, a1, 1)
                t += dt
                x, direction = a1, 1
        periods = [times[k + 1] - times[k] for k in range(n_cycles)]
        return HighPrecisionCycles(
            impact_time=times[:n_cycles],
            velocity_before_impact=speeds[:n_cycles],
            period=periods,
            amplitude=maxima,
            dps=dps,
        )
