"""How a run ends, for the event loop and the integrators' loop alike: the automaton's exits with their messages
(the inputs as typed back, computed numbers with the digits that tell them from their bounds), and :func:`finish`."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.arguments import Numeric
from ..model.events import EventKind, EventLog
from ..model.kinematics import rebound_accumulation_time
from ..model.limits import RunSpec
from ..model.parameters import Parameters
from ..model.status import Status
from ..model.printing import compared, exact, texts
from .describe import CYCLE_COLUMNS, EVENT_COLUMNS, ArcTable, CycleTable, Exit, Trajectory
from .result import Solution

__all__ = ["Outcome", "accumulation", "chattering_outcome", "completed_outcome", "event_limit_message", "finish",
           "horizon_outcome", "no_event_outcome"]


class Outcome(NamedTuple):
    """How a run ended: its status and message, the numbers behind a regime exit, the end of its trajectory."""

    status: Status
    message: str
    exit: Exit
    t_final: object  #: a float, or an mpmath number for the high-precision solver


#: the direction in which the free swing would pass each impact position, from the automaton's surfaces
_DIRECTION = {s.position: "moving right" if s.direction > 0 else "moving left" for s in automaton.SURFACES.values()}
_DIGITS = 12  #: the significant digits of the computed times and positions in the messages (more where needed)


def stopped_message(t: float, radius: float, missed: dict[str, float]) -> str:
    """The swing turns at ``-radius``, ``radius``, short of the positions ``missed`` (name: value)."""
    names = " or ".join(f"{name} = {exact(value)} m ({_DIRECTION[name]})" for name, value in missed.items())
    turn = compared(radius, [abs(value) for value in missed.values()], _DIGITS)
    return (f"the escapement stopped at t = {texts([t], _DIGITS)[0]} s: the free swing turns at x = "
            f"{'0' if turn == '0' else '-' + turn} m and x = {turn} m and never passes the next impact position, "
            f"{names}; from then on the mass oscillates freely")


def turned_back_message(t: float, zone: str, turning_point: float, centre: float, end: float) -> str:
    """The motion turned at ``turning_point``, short of the zone's ``end`` (an input), about ``centre``."""
    return (f"the mass turned back inside the impulse zone {zone} at t = {texts([t], _DIGITS)[0]} s: about the "
            f"zone's centre x = {compared(centre, [end], _DIGITS)} m (F/K) the motion turns at "
            f"x = {compared(turning_point, [end, centre], _DIGITS)} m, short of the zone's end at {exact(end)} m; "
            "the escapement model does not cover this")


def event_limit_message(t: float, max_events: int) -> str:
    """The run reached ``max_events`` (an input) at ``t``."""
    return (f"ended after max_events = {max_events} event{'' if max_events == 1 else 's'} at t = "
            f"{texts([t], _DIGITS)[0]} s; raise max_events to go on")


def no_event_outcome(params: Parameters, state: int, centre: Numeric, t: Numeric, dt: Numeric, turning: Numeric,
                     t_stop: float = math.inf, impacts_a1: int = 0) -> Outcome:
    """No surface watched in ``state`` is passed from ``t``: the escapement stopped, or the mass turns in a zone."""
    arc = automaton.ARCS[state]
    status = automaton.EXIT_WITHOUT_EVENT[arc.mode]
    if status is Status.TURNED_BACK_IN_ZONE and t + dt > t_stop:
        return horizon_outcome(t_stop, impacts_a1)
    if status is Status.STOPPED:
        missed = {automaton.SURFACES[kind].position: float(automaton.position(kind, params)) for kind in arc.watched}
        exit_ = Exit(turning_point=float(turning), margin=float(min(abs(m) for m in missed.values()) - turning))
        return Outcome(status, stopped_message(float(t), float(turning), missed), exit_, math.inf)
    zone, end_kind = automaton.ZONE_OF[arc.mode]
    end = automaton.position(end_kind, params)
    message = turned_back_message(float(t + dt), zone, float(turning), float(centre), float(end))
    return Outcome(status, message, Exit(turning_point=float(turning), margin=float(abs(end - turning))), t + dt)


def horizon_outcome(t_stop: float, impacts_a1: int) -> Outcome:
    """The end time comes before the next event."""
    impacts = f"{impacts_a1} impact{'' if impacts_a1 == 1 else 's'}"
    return Outcome(Status.COMPLETED, f"reached t_end = {exact(t_stop)} s after {impacts} at a1", Exit(), t_stop)


def completed_outcome(n_cycles: int, t: Numeric, t_acc: float = math.nan) -> Outcome:
    """The run's last cycle ended at ``t`` (``t_acc``: the first accumulation of impacts it went on past)."""
    return Outcome(Status.COMPLETED, f"completed {n_cycles} cycles", Exit(t_accumulation=t_acc), t)


def accumulation(params: Parameters, kind: EventKind, v_before: Numeric, v_after: Numeric) -> float:
    """After the impact ``kind`` reversed the velocity, the time until the rebounds accumulate, s (NaN: never)."""
    distance = automaton.rebound_distance(kind, automaton.position(kind, params))
    ratio = abs(float(v_after / v_before))  # the impact law's |v+/v-|
    return rebound_accumulation_time(params.omega, distance, abs(float(v_after)), ratio) if distance > 0 else math.nan


def chattering_outcome(params: Parameters, kind: EventKind, t: Numeric, v_before: Numeric, v_after: Numeric
                       ) -> Outcome:
    """The impact ``kind`` at ``t`` reversed the velocity: do the rebounds accumulate (a Zeno point)?"""
    ratio = float(v_after / v_before)  # the impact law's v+/v-, negative: a rebound
    t_acc = float(t) + accumulation(params, kind, v_before, v_after)
    position = automaton.SURFACES[EventKind(kind)].position
    t_text, t_acc_text = texts([float(t), t_acc], _DIGITS)
    message = (f"the impact at {position} at t = {t_text} s reversed the velocity (b = {exact(params.b)} > 1, "
               f"v+ = {compared(ratio, [0.0, -1.0], _DIGITS)} v-): the mass rebounds instead of entering the "
               "impulse zone")
    if math.isnan(t_acc):
        message += (f"; the centre of oscillation lies at {position} or in the direction of the rebound, so the "
                    f"spring does not drive the mass back to {position} (no Zeno point), and the escapement regime "
                    "has ended")
    else:
        message += (f"; the spring drives it back to {position} and the impacts accumulate at t = {t_acc_text} s "
                    "(a Zeno point), past which the impulsive model has no solution")
    return Outcome(Status.CHATTERING, message, Exit(t_accumulation=t_acc), t)


def finish(spec: RunSpec, method: str, outcome: Outcome, events: EventLog, cycles: CycleTable,
           trajectory: Trajectory | None) -> Solution:
    """The run's :class:`Solution`; a completed run holding a non-finite number raises."""
    t_final = float(outcome.t_final)
    if outcome.status is Status.COMPLETED:
        columns = {f"events.{field}": getattr(events, field) for field, units, _ in EVENT_COLUMNS.values() if units}
        columns.update({f"cycles.{name}": getattr(cycles, name) for name in CYCLE_COLUMNS})
        if isinstance(trajectory, ArcTable):
            columns.update({f"trajectory.{name}": getattr(trajectory, name)
                            for name in ("t_start", "centre", "x_start", "v_start", "omega")})
        columns["t_final"] = t_final
        for name, values in columns.items():
            doubles = np.atleast_1d(np.asarray(values, dtype=float))  # mpmath numbers as their nearest doubles
            if len(bad := np.flatnonzero(~np.isfinite(doubles))):
                raise FloatingPointError(
                    f"{method}: a completed run holds a non-finite {name}[{bad[0]}] = {float(doubles[bad[0]])!r}; "
                    "the input validation (escapement.model.parameters) must refuse the inputs that lead to it")
    return Solution(params=spec.params, x0=spec.x0, v0=spec.v0, method=method, status=outcome.status,
                    message=outcome.message, events=events, cycles=cycles, trajectory=trajectory, t_final=t_final,
                    exit=outcome.exit)
