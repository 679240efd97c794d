"""A naive fixed-step integrator, to show what not locating events costs.

Classical RK4 with a fixed step ``h``; an event is noticed when ``x`` has passed its
surface at the end of a step, and applied there, without locating it. The escapement
logic (modes, alternation) is that of the exact solver. Errors are O(h): the impact is
applied up to one step late, at a state up to one step past the surface.
"""

from __future__ import annotations

import math

from .parameters import Parameters

__all__ = ["solve_naive"]


def solve_naive(params: Parameters, x0: float, v0: float, n_cycles: int, step: float, max_steps: int = 100_000_000):
    """Impact times and velocities before impact at a1 for ``n_cycles + 1`` impacts.

    Returns ``(impact_times, velocities)``; raises ``ValueError`` if the motion leaves the
    regime or the step bound is reached first.
    """
    if not (step > 0 and math.isfinite(step)):
        raise ValueError(f"step = {step!r} is invalid: step must be finite and > 0")
    w2, off, keep = params.omega2, params.zone_offset, 1.0 - params.b
    a1, a2, a3, a4 = params.a1, params.a2, params.a3, params.a4
    h, h2, h6 = step, step / 2.0, step / 6.0
    t, x, v = 0.0, float(x0), float(v0)
    centre, mode = 0.0, "free"
    expect = None
    times: list[float] = []
    speeds: list[float] = []
    for _ in range(max_steps):
        # one RK4 step of x'' = -w2 (x - centre)
        k1x, k1v = v, -w2 * (x - centre)
        k2x, k2v = v + h2 * k1v, -w2 * (x + h2 * k1x - centre)
        k3x, k3v = v + h2 * k2v, -w2 * (x + h2 * k2x - centre)
        k4x, k4v = v + h * k3v, -w2 * (x + h * k3x - centre)
        x_new = x + h6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v_new = v + h6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        t += h
        event = None
        if mode == "free":
            if expect != "a3" and x < a1 <= x_new and v_new > 0:
                event = "a1"
            elif expect != "a1" and x > a3 >= x_new and v_new < 0:
                event = "a3"
        elif mode == "zone_right":
            if x_new >= a2:
                event = "a2"
            elif v_new <= 0:
                raise ValueError("the motion turned back inside the impulse zone")
        elif x_new <= a4:
            event = "a4"
        elif v_new >= 0:
            raise ValueError("the motion turned back inside the impulse zone")
        x, v = x_new, v_new
        if event == "a1":
            times.append(t)
            speeds.append(v)
            if len(times) > n_cycles:
                return times, speeds
            v *= keep
            mode, centre = "zone_right", off
        elif event == "a3":
            v *= keep
            mode, centre = "zone_left", -off
        elif event == "a2":
            mode, centre, expect = "free", 0.0, "a3"
        elif event == "a4":
            mode, centre, expect = "free", 0.0, "a1"
    raise ValueError(f"max_steps = {max_steps} reached before {n_cycles} cycles")
