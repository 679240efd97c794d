"""The exact event-driven solver.

Between events the motion is a harmonic arc about the current mode's centre, so
each event (impact, end of an impulse zone) comes from a closed form
(:func:`escapement.arcs.crossing`): no step size, no root finding, errors at the
level of floating-point rounding.

Modes (a hybrid automaton):

* ``FREE``: centre 0; the next event is the impact the escapement expects: at a3
  moving left after the impulse (a1, a2), at a1 moving right after the impulse
  (a4, a3), and at first whichever of the two comes first.  If the expected
  impact position is never reached the escapement has stopped (it stays locked).
* ``ZONE_RIGHT``: entered by the impact at a1; centre ``+F/K``; ends at a2 moving
  right.
* ``ZONE_LEFT``: entered by the impact at a3; centre ``-F/K``; ends at a4 moving
  left.

The impulse is delivered only after an impact (the escapement unlocks at the
impact); the run starts in ``FREE``.
"""

from __future__ import annotations

import math
from array import array

import numpy as np

from . import outcome
from .arcs import arc_maximum, crossing, rebound_accumulation_time, time_to_rest
from .cycles import cycle_table
from .events import EventKind, EventLog
from .limits import RunLimits
from .outcome import Status
from .parameters import Parameters, check_initial_state
from .solution import ArcTable, Solution

__all__ = ["solve_exact"]

FREE, ZONE_RIGHT, ZONE_LEFT = 0, 1, 2
_A1, _A2, _A3, _A4 = (int(k) for k in EventKind)


def solve_exact(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int | None = None,
    t_end: float | None = None,
    max_events: int | None = None,
    record_trajectory: bool = True,
) -> Solution:
    """Integrate the escapement model exactly from ``(x0, v0)`` at ``t = 0``.

    The run ends after ``n_cycles`` complete cycles, at ``t_end``, after
    ``max_events`` events, or when the motion leaves the escapement regime; the
    returned :class:`~escapement.solution.Solution` says which, in ``status``
    and ``message``.  With ``record_trajectory=False`` the arcs are not kept (for
    very long runs that need only events and cycles).
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    target_impacts = None if limits.n_cycles is None else limits.n_cycles + 1
    t_stop = math.inf if limits.t_end is None else limits.t_end

    omega = params.omega
    offset = params.zone_offset
    keep = 1.0 - params.b
    a1, a2, a3, a4 = params.a1, params.a2, params.a3, params.a4

    ev_t, ev_kind, ev_x, ev_vb, ev_va = array("d"), array("b"), array("d"), array("d"), array("d")
    arc_t, arc_c, arc_x, arc_v = array("d"), array("d"), array("d"), array("d")
    maxima = array("d")
    periods = array("d")
    cycle_max = -math.inf
    impacts_a1 = 0
    t = 0.0  # time of the last event: t_sum + t_err, a compensated (Neumaier) sum of the durations
    t_sum = t_err = 0.0
    elapsed = 0.0  # time since the last impact at a1, summed inside the cycle for an exact period
    mode = FREE
    expect = 0  # the impact the escapement waits for: 0 (either, at the start), _A1 or _A3
    status = Status.EVENT_LIMIT
    message = ""
    detail: dict[str, float] = {}
    t_final = t

    for _ in range(limits.max_events):
        if mode == FREE:
            centre = 0.0
            hit_a1 = crossing(0.0, x, v, omega, a1, 1) if expect != _A3 else None
            hit_a3 = crossing(0.0, x, v, omega, a3, -1) if expect != _A1 else None
            if hit_a1 is None and hit_a3 is None:
                radius = math.hypot(x, v / omega)
                if record_trajectory:
                    arc_t.append(t), arc_c.append(centre), arc_x.append(x), arc_v.append(v)
                status, t_final = Status.STOPPED, math.inf
                missed = {_A1: {"a1": a1}, _A3: {"a3": a3}}.get(expect, {"a1": a1, "a3": a3})
                message = outcome.stopped_message(t, radius, missed)
                detail = {"turning_point": radius, "margin": min(abs(m) for m in missed.values()) - radius}
                break
            if hit_a3 is None or (hit_a1 is not None and hit_a1[0] <= hit_a3[0]):
                hit, target, kind = hit_a1, a1, _A1
            else:
                hit, target, kind = hit_a3, a3, _A3
        elif mode == ZONE_RIGHT:
            centre, target, kind = offset, a2, _A2
            hit = crossing(centre, x, v, omega, a2, 1)
        else:
            centre, target, kind = -offset, a4, _A4
            hit = crossing(centre, x, v, omega, a4, -1)

        if record_trajectory:
            arc_t.append(t), arc_c.append(centre), arc_x.append(x), arc_v.append(v)
        if hit is None:
            rest_dt, turning_point = time_to_rest(centre, x, v, omega)
            zone, end = ("(a1, a2)", a2) if mode == ZONE_RIGHT else ("(a4, a3)", a4)
            status, t_final = Status.TURNED_BACK_IN_ZONE, t + rest_dt
            message = outcome.turned_back_message(t_final, zone, turning_point, centre, end)
            detail = {"turning_point": turning_point, "margin": abs(end - turning_point)}
            break
        dt, v_new, angle = hit
        if t + dt > t_stop:
            status, t_final = Status.COMPLETED, t_stop
            message = f"reached t_end = {t_stop:.12g} s after {impacts_a1} impacts at a1"
            break
        cycle_max = max(cycle_max, arc_maximum(centre, x, v, omega, angle, target))
        total = t_sum + dt
        t_err += (t_sum - total) + dt if abs(t_sum) >= dt else (dt - total) + t_sum
        t_sum = total
        t = t_sum + t_err
        elapsed += dt
        x = target
        v_after = keep * v_new if kind in (_A1, _A3) else v_new
        ev_t.append(t), ev_kind.append(kind), ev_x.append(x), ev_vb.append(v_new), ev_va.append(v_after)
        t_final = t
        if kind == _A1:
            impacts_a1 += 1
            if impacts_a1 > 1:
                maxima.append(cycle_max)
                periods.append(elapsed)
            cycle_max = x
            elapsed = 0.0
            if target_impacts is not None and impacts_a1 >= target_impacts:
                status = Status.COMPLETED
                message = f"completed {impacts_a1 - 1} cycles"
                break
        if kind in (_A1, _A3):
            if v_after * v_new < 0.0:
                position, distance = ("a1", -a1) if kind == _A1 else ("a3", a3)
                t_acc = None
                if distance > 0.0:
                    rest = rebound_accumulation_time(omega, distance, abs(v_after), abs(keep))
                    t_acc = None if rest is None else t + rest
                status = Status.CHATTERING
                message = outcome.chattering_message(t, position, params.b, t_acc)
                detail = {"t_accumulation": math.nan if t_acc is None else t_acc}
                break
            mode = ZONE_RIGHT if kind == _A1 else ZONE_LEFT
        else:
            mode = FREE
            expect = _A3 if kind == _A2 else _A1
        v = v_after
    else:
        message = outcome.event_limit_message(t, limits.max_events)

    events = EventLog(
        t=np.frombuffer(ev_t, dtype=float).copy(),
        kind=np.frombuffer(ev_kind, dtype=np.int8).copy(),
        x=np.frombuffer(ev_x, dtype=float).copy(),
        v_before=np.frombuffer(ev_vb, dtype=float).copy(),
        v_after=np.frombuffer(ev_va, dtype=float).copy(),
    )
    trajectory = None
    if record_trajectory:
        trajectory = ArcTable(
            t_start=np.frombuffer(arc_t, dtype=float).copy(),
            centre=np.frombuffer(arc_c, dtype=float).copy(),
            x_start=np.frombuffer(arc_x, dtype=float).copy(),
            v_start=np.frombuffer(arc_v, dtype=float).copy(),
            omega=omega,
            t_final=t_final,
        )
    detail["t_final"] = t_final
    return Solution(
        params=params,
        x0=float(x0),
        v0=float(v0),
        method="exact",
        status=status,
        message=message,
        events=events,
        cycles=cycle_table(
            events, np.frombuffer(maxima, dtype=float).copy(), np.frombuffer(periods, dtype=float).copy()
        ),
        trajectory=trajectory,
        detail=detail,
    )
