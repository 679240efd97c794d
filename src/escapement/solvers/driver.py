"""The solver loop: drives the automaton from event to event with a pluggable integrator.

One loop serves the exact, reference, high-precision and naive solvers. An integrator (a
*stepper*) answers one question: starting in ``mode`` from ``(x, v)`` at time ``t``, which of
the watched surfaces is reached first, when, and at what velocity? Everything else, which
surfaces are watched, the impact law, the next mode, the regime exits, the cycle bookkeeping
and the limits of the run, comes from :mod:`escapement.model.automaton` and is done here.

A stepper's :meth:`Stepper.next_event` returns a :class:`Step`:

* ``kind`` an :class:`EventKind`: the surface reached after ``dt`` with velocity ``v``;
  ``x_max`` is the largest displacement on the way; ``t_abs``, if not None, is the event's
  time as the integrator computed it (otherwise the loop sums the durations with compensation),
  and ``x_at``, if not None, the position where it applies the event (otherwise the surface's);
* ``kind`` :data:`NO_EVENT`: no watched surface is ever passed; ``x_max`` is the turning point
  (free flight: the radius of the swing) reached ``dt`` after the start (``inf`` for free flight);
* ``kind`` :data:`HORIZON`: the end time ``t_stop`` comes first.
"""

from __future__ import annotations

import math
from array import array
from typing import NamedTuple, Protocol

import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import compensated_add, rebound_accumulation_time
from ..model.limits import RunLimits
from ..model.parameters import Parameters
from ..model.status import (
    Status,
    chattering_message,
    event_limit_message,
    stopped_message,
    turned_back_message,
)
from .result import ArcTable, CycleTable, Exit, Solution

__all__ = ["HORIZON", "NO_EVENT", "Step", "Stepper", "drive"]

NO_EVENT = 0
HORIZON = -1
_A1 = int(EventKind.IMPACT_A1)


class Step(NamedTuple):
    """What a stepper returns (a plain tuple of these six fields is accepted too)."""

    kind: int
    dt: float
    v: float
    x_max: float
    t_abs: float | None = None
    x_at: float | None = None  #: where the integrator applies the event (None: on the surface)


class Stepper(Protocol):
    name: str

    def next_event(self, mode: Mode, centre: float, t: float, x: float, v: float,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step: ...

    def trajectory(self, t_final: float): ...


class _Records:
    """Growing columns: ``array('d')`` for floats (8 bytes a value), lists for mpmath numbers."""

    def __init__(self, floats: bool, names: tuple[str, ...]) -> None:
        self.floats = floats
        self.columns = {name: (array("d") if floats else []) for name in names}

    def __getitem__(self, name):
        return self.columns[name]

    def numpy(self, name: str) -> np.ndarray:
        column = self.columns[name]
        if self.floats:
            return np.frombuffer(column, dtype=float).copy() if len(column) else np.zeros(0)
        return np.array(column, dtype=object)


def drive(params: Parameters, x: float, v: float, limits: RunLimits, stepper: Stepper, *,
          x0: float, v0: float, floats: bool = True) -> Solution:
    """Run the automaton from ``(x, v)`` at ``t = 0`` until ``limits`` or a regime exit.

    A run that ends ``completed`` holds only finite numbers; one that does not raises
    :class:`FloatingPointError` (the input validation let through what it must refuse)."""
    target_impacts = None if limits.n_cycles is None else limits.n_cycles + 1
    t_stop = math.inf if limits.t_end is None else limits.t_end
    zero = x * 0  # 0 in the arithmetic of the run (float or mpmath)
    b = zero + params.b
    offset = params.zone_offset
    positions = {kind: automaton.position(kind, params) for kind in EventKind}
    impact = automaton.IMPACT_TABLE
    # the automaton's tables, looked up once: centres by mode, watched surfaces by (mode, awaited),
    # the next mode and awaited impact by event
    centres = [automaton.centre(m, offset) for m in Mode]
    watching = {(m, a): automaton.watched(m, a) for m in Mode for a in automaton.Awaited}
    after = {kind: automaton.transition(kind) for kind in EventKind}

    ev = _Records(floats, ("t", "x", "v_before", "v_after"))
    kinds = array("b")
    cyc = _Records(floats, ("maxima", "periods"))
    cycle_max = -math.inf
    impacts_a1 = 0
    t_sum = t_err = t = zero
    elapsed = zero  # time since the last impact at a1, summed inside the cycle for an exact period
    mode, awaited = automaton.INITIAL
    status, message, exit_ = Status.EVENT_LIMIT, "", Exit()
    t_final = t

    for _ in range(limits.max_events):
        c = centres[mode]
        step = stepper.next_event(mode, c, t, x, v, watching[(mode, awaited)], t_stop)
        kind = step[0]
        if kind == NO_EVENT:
            status = automaton.EXIT_WITHOUT_EVENT[mode]
            turning = step.x_max
            if status is Status.STOPPED:
                missed = {name: positions[k] for name, k in (("a1", EventKind.IMPACT_A1), ("a3", EventKind.IMPACT_A3))
                          if k in automaton.watched(mode, awaited)}
                t_final = math.inf
                message = stopped_message(float(t), float(turning), {k: float(m) for k, m in missed.items()})
                exit_ = Exit(turning_point=float(turning), margin=float(min(abs(m) for m in missed.values()) - turning))
            else:
                zone, end_kind = automaton.ZONE_OF[mode]
                end = positions[end_kind]
                t_final = t + step.dt
                message = turned_back_message(float(t_final), zone, float(turning), float(c), float(end))
                exit_ = Exit(turning_point=float(turning), margin=float(abs(end - turning)))
            break
        _, dt, v_before, x_max, t_abs, x_at = step
        if kind == HORIZON or t + dt > t_stop:
            status, t_final = Status.COMPLETED, t_stop
            message = f"reached t_end = {t_stop:.12g} s after {impacts_a1} impacts at a1"
            break
        cycle_max = max(cycle_max, x_max)
        if t_abs is None:
            t_sum, t_err = compensated_add(t_sum, t_err, dt)
            t = t_sum + t_err
        else:
            t = t_sum = t_abs
        elapsed += dt
        x = positions[kind] if x_at is None else x_at
        v_after = automaton.velocity_after(v_before, b, impact[kind])
        ev["t"].append(t), kinds.append(kind), ev["x"].append(x), ev["v_before"].append(v_before)
        ev["v_after"].append(v_after)
        t_final = t
        if kind == _A1:
            impacts_a1 += 1
            if impacts_a1 > 1:
                cyc["maxima"].append(cycle_max)
                cyc["periods"].append(elapsed)
            cycle_max = x
            elapsed = zero
            if target_impacts is not None and impacts_a1 >= target_impacts:
                status, message = Status.COMPLETED, f"completed {impacts_a1 - 1} cycles"
                break
        if automaton.reverses(v_before, v_after):
            distance = automaton.rebound_distance(kind, positions[kind])
            t_acc = math.nan  # unless the spring drives the mass back to the impact position
            ratio = float(v_after / v_before)  # the impact law's v+/v-, negative: a rebound
            if distance > 0.0:
                t_acc = float(t) + rebound_accumulation_time(params.omega, distance, abs(float(v_after)), abs(ratio))
            status = Status.CHATTERING
            position = automaton.SURFACES[EventKind(kind)].position
            message = chattering_message(float(t), position, params.b, ratio, t_acc)
            exit_ = Exit(t_accumulation=t_acc)
            break
        mode, awaited = after[kind]
        v = v_after
    else:
        message = event_limit_message(float(t), limits.max_events)

    events = EventLog(
        t=ev.numpy("t"),
        kind=np.frombuffer(kinds, dtype=np.int8).copy() if len(kinds) else np.zeros(0, dtype=np.int8),
        x=ev.numpy("x"),
        v_before=ev.numpy("v_before"),
        v_after=ev.numpy("v_after"),
    )
    cycles = _cycle_table(events, cyc.numpy("maxima"), cyc.numpy("periods"))
    trajectory = stepper.trajectory(float(t_final))
    if status is Status.COMPLETED:
        _check_finite(stepper.name, events, cycles, trajectory, float(t_final))
    return Solution(
        params=params,
        x0=float(x0),
        v0=float(v0),
        method=stepper.name,
        status=status,
        message=message,
        events=events,
        cycles=cycles,
        trajectory=trajectory,
        t_final=float(t_final),
        exit=exit_,
    )


def _cycle_table(events: EventLog, maxima: np.ndarray, periods: np.ndarray) -> CycleTable:
    """Complete cycles only: an impact at a1 that starts an unfinished cycle is dropped."""
    impacts = events.of_kind(EventKind.IMPACT_A1)
    n = len(periods)
    return CycleTable(
        impact_time=events.t[impacts][:n],
        velocity_before_impact=events.v_before[impacts][:n],
        period=periods,
        amplitude=maxima,
    )


def _check_finite(method: str, events: EventLog, cycles: CycleTable, trajectory, t_final: float) -> None:
    """A completed run holds only finite numbers: its event log, its cycle table, its end time and
    (for a table of arcs) its trajectory. Otherwise the input validation
    (:mod:`escapement.model.parameters`) let through a value whose arithmetic leaves the float64
    range: that is a bug, raised, not an outcome."""
    columns = {f"events.{name}": getattr(events, name) for name in ("t", "x", "v_before", "v_after")}
    columns.update({f"cycles.{name}": getattr(cycles, name)
                    for name in ("impact_time", "velocity_before_impact", "period", "amplitude")})
    if isinstance(trajectory, ArcTable):
        columns.update({f"trajectory.{name}": getattr(trajectory, name)
                        for name in ("t_start", "centre", "x_start", "v_start")})
        columns["trajectory.omega"] = np.array([trajectory.omega])
    columns["t_final"] = np.array([t_final])
    for name, values in columns.items():
        doubles = np.asarray(values, dtype=float)  # mpmath numbers as their nearest doubles
        finite = np.isfinite(doubles)
        if not finite.all():
            index = int(np.flatnonzero(~finite)[0])
            raise FloatingPointError(
                f"{method}: a completed run holds a non-finite {name}[{index}] = {float(doubles[index])!r}; the "
                "input validation (escapement.model.parameters) must refuse the inputs that lead to it"
            )
