"""The integrators' loop: drives the automaton from event to event with a stepper that says only which watched
surface is reached first, when and at what velocity; a run ends as the exact solver's does.
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Callable
from typing import NamedTuple, Protocol

import mpmath
import numpy as np

from ..model import automaton
from ..model.automaton import RELEASE, Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import compensated_add
from ..model.limits import RunSpec
from ..model.status import Status
from ..solvers.describe import CycleTable, Exit
from ..solvers.outcomes import (Outcome, chattering_outcome, completed_outcome, event_limit_message, finish,
                                horizon_outcome, no_event_outcome)
from ..solvers.result import Solution

__all__ = ["HORIZON", "NO_EVENT", "Step", "Stepper", "drive"]

#: a :class:`Step`'s kind where no watched surface is ever passed, and where the end time comes first
NO_EVENT, HORIZON = 0, -1
_A1 = int(EventKind.IMPACT_A1)
#: bytes at the peak per event (measured 48-58 with the naive stepper) and per cycle
_FLOAT_EVENT_BYTES, _FLOAT_CYCLE_BYTES = 64, 40
#: bytes per mpmath number in a list and its object array: measured 197 at 60 digits, 263 at 210, 518 at 1010
_MPF_BYTES_BASE, _MPF_BYTES_PER_BIT = 200, 0.12


class Step(NamedTuple):
    """What a stepper returns: the surface ``kind`` reached after ``dt`` with velocity ``v``, ``x_max`` the largest
    displacement on the way; with :data:`NO_EVENT`, ``x_max`` is the turning point (free flight: the radius)."""

    kind: int
    dt: float
    v: float
    x_max: float
    t_abs: float | None = None  #: the event's time as the integrator computed it (None: the loop sums ``dt``)
    x_at: float | None = None  #: where the integrator applies the event (None: on the surface)


class Stepper(Protocol):
    """An integrator for the loop; one that keeps the motion has ``trajectory(t_final)`` and may say the bytes it
    keeps per event (``trajectory_bytes_per_event``) and whatever the run's length (``fixed_bytes``)."""

    name: str

    def next_event(self, mode: Mode, centre: float, t: float, x: float, v: float,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step:
        """The next event of ``watched`` on the arc about ``centre`` in ``mode`` from ``(t, x, v)``, or none
        before ``t_stop``."""


def drive(spec: RunSpec, stepper: Stepper, number: Callable = float) -> Solution:
    """Run the automaton of ``spec`` until its limits or a regime exit in the arithmetic of ``number`` (``float``
    or ``mpmath.mpf``); a result over the memory budget is refused before any work."""
    params, limits, floats = spec.params, spec.limits, number is float
    stored = _MPF_BYTES_BASE + _MPF_BYTES_PER_BIT * mpmath.mp.prec  # bytes an mpmath number takes
    event_bytes = (_FLOAT_EVENT_BYTES if floats else 4 * stored + 1) + getattr(stepper, "trajectory_bytes_per_event", 0)
    limits.check_memory(event_bytes, _FLOAT_CYCLE_BYTES if floats else 4 * stored,
                        f"the event log and the cycle table of {stepper.name}", "raise memory_budget, or run the exact "
                        "solver's cycles in constant memory with escapement.solvers.iter_cycles",
                        fixed_bytes=getattr(stepper, "fixed_bytes", 0))
    target_impacts = None if limits.n_cycles is None else limits.n_cycles + 1
    t_stop = math.inf if limits.t_end is None else limits.t_end
    x, v, b = number(spec.x0), number(spec.v0), number(params.b)
    positions = {kind: automaton.position(kind, params) for kind in EventKind}
    arcs = {state: (arc.mode, automaton.centre(arc.mode, params.zone_offset), arc.watched)
            for state, arc in automaton.ARCS.items()}
    # growing columns: array('d') for floats (8 bytes a value), lists for mpmath numbers
    columns = {name: array("d") if floats else [] for name in ("t", "x", "v_before", "v_after", "max", "period")}
    kinds = array("b")
    cycle_max, impacts_a1, state, outcome = -math.inf, 0, RELEASE, None
    t_sum = t_err = t = elapsed = number(0)  # elapsed: since the last impact at a1, for an exact period

    for _ in range(limits.max_events):
        mode, c, watched = arcs[state]
        kind, dt, v_before, x_max, t_abs, x_at = stepper.next_event(mode, c, t, x, v, watched, t_stop)
        if kind == NO_EVENT:
            outcome = no_event_outcome(params, state, c, t, dt, x_max, t_stop, impacts_a1)
            break
        # the event's time, compared with the end time as it is stored
        new_sum, new_err = compensated_add(t_sum, t_err, dt) if t_abs is None else (t_abs, t_err)
        t_new = new_sum + new_err if t_abs is None else t_abs
        if kind == HORIZON or t_new > t_stop:
            outcome = horizon_outcome(t_stop, impacts_a1)
            break
        cycle_max = max(cycle_max, x_max)
        t_sum, t_err, t = new_sum, new_err, t_new
        elapsed += dt
        x = positions[kind] if x_at is None else x_at
        v_after = automaton.velocity_after(v_before, b) if automaton.is_impact(kind) else v_before
        for name, value in (("t", t), ("x", x), ("v_before", v_before), ("v_after", v_after)):
            columns[name].append(value)
        kinds.append(kind)
        if kind == _A1:
            impacts_a1 += 1
            if impacts_a1 > 1:
                columns["max"].append(cycle_max)
                columns["period"].append(elapsed)
            cycle_max, elapsed = x, number(0)
            if target_impacts is not None and impacts_a1 >= target_impacts:
                outcome = completed_outcome(impacts_a1 - 1, t)
                break
        if automaton.reverses(v_before, v_after):
            outcome = chattering_outcome(params, kind, t, v_before, v_after)
            break
        state, v = int(kind), v_after
    else:
        outcome = Outcome(Status.EVENT_LIMIT, event_limit_message(float(t), limits.max_events), Exit(), t)

    def numbers(name: str) -> np.ndarray:  # a view of a float buffer (no second copy); an object array of mpf
        column = columns[name]
        return (np.frombuffer(column, dtype=float) if len(column) else np.zeros(0)) if floats else \
            np.array(column, dtype=object)

    events = EventLog(t=numbers("t"), x=numbers("x"), v_before=numbers("v_before"), v_after=numbers("v_after"),
                      kind=np.frombuffer(kinds, dtype=np.int8) if len(kinds) else np.zeros(0, dtype=np.int8))
    periods = numbers("period")
    impacts = events.of_kind(EventKind.IMPACT_A1)[:len(periods)]  # complete cycles only
    cycles = CycleTable(impact_time=events.t[impacts], velocity_before_impact=events.v_before[impacts],
                        period=periods, largest_displacement=numbers("max"))
    keeps = getattr(stepper, "trajectory", None)
    return finish(spec, stepper.name, outcome, events, cycles, keeps(float(outcome.t_final)) if keeps else None)
