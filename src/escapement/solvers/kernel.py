"""The exact solver's event loop, in blocks of events: a loop follows the velocity alone through the automaton's rows
(:func:`rows`; by energy each arc arrives with ``v**2 = v0**2 + k``), then ``crossing`` gives each arc's angle and
duration on the block's arrays and a compensated running sum the events' times: an event-by-event loop's numbers,
bit for bit. Kinds, positions, arcs and cycles follow (:func:`event_block`).
"""

from __future__ import annotations

import math
from array import array
from types import SimpleNamespace
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.arguments import Numeric
from ..model.automaton import RELEASE, Mode
from ..model.events import EventKind
from ..model.kinematics import arc_maximum, arc_terms, compensated_add, crossing, time_to_rest, two_sum
from ..model.limits import RunSpec
from ..model.parameters import ParameterArrays, Parameters
from ..model.status import Status
from .describe import Exit
from .outcomes import (Outcome, accumulation, chattering_outcome, completed_outcome, event_limit_message,
                       horizon_outcome, no_event_outcome)

__all__ = ["A1", "BLOCK_EVENTS", "PLAN", "Block", "EventRun", "Row", "event_block", "kinds_from", "row", "rows"]

A1 = int(EventKind.IMPACT_A1)
PLAN = tuple(int(kind) for kind in automaton.cycle_plan())  #: a cycle's events after an impact at a1, up to the next
BLOCK_EVENTS = 1 << 12  #: the most events of a block: a run to an end time computes at most this many past it
NO_EVENT, HORIZON, REBOUND = "no event", "end time", "rebound"  #: how a block can end before its last event


def _atan2(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    """libm's ``atan2`` element by element: NumPy's ``arctan2`` may differ from it by an ulp where it uses SIMD."""
    return np.fromiter(map(math.atan2, memoryview(y), memoryview(x)), float, len(y))


#: ``crossing`` on arrays with the scalar closed form's numbers, bit for bit (NumPy's sqrt is correctly rounded)
LIBM = SimpleNamespace(sqrt=np.sqrt, atan2=_atan2)


class Row(NamedTuple):
    """The arc after a state, to the surface it watches (numbers, or arrays a run each)."""

    u0: Numeric  #: where the arc starts, from its centre, m
    q: Numeric  #: where it ends, from its centre, m
    k: Numeric  #: the change of v**2 on the way, m2 s-2 (:func:`~escapement.model.kinematics.arc_terms`)
    direction: float  #: the direction of motion at its end, +1.0 or -1.0
    impact: bool  #: reaching its end is an impact
    following: int  #: the event it ends at: the next state


def rows(params: Parameters | ParameterArrays) -> list[Row | None]:
    """The arcs of :data:`~escapement.model.automaton.ARCS` by state; ``None`` for the release."""
    table: list[Row | None] = [None] * (len(automaton.SURFACES) + 1)
    for state, arc in automaton.ARCS.items():
        if len(arc.watched) == 1:
            table[state] = row(params, automaton.position(state, params), arc.mode, arc.watched[0])
    return table


def row(params: Parameters | ParameterArrays, start: Numeric, mode: Mode, kind: EventKind) -> Row:
    """The arc from ``start`` in ``mode`` to the surface ``kind``."""
    surface = automaton.SURFACES[kind]
    u0, q, k = arc_terms(automaton.centre(mode, params.zone_offset), start, params.omega,
                         automaton.position(kind, params))
    return Row(u0, q, k, float(surface.direction), surface.impact, int(kind))


def kinds_from(first: int, start: int, n: int) -> np.ndarray:
    """The kinds of the events ``start .. start + n - 1``: after the first they go round :data:`PLAN`."""
    shift = (PLAN.index(first) + start) % len(PLAN)
    return np.tile(np.array(PLAN[shift:] + PLAN[:shift], dtype=np.intp), n // len(PLAN) + 1)[:n]


class EventRun:
    """One run of the exact solver, resumable: :meth:`advance` runs events, :meth:`take` hands them over."""

    def __init__(self, spec: RunSpec) -> None:
        params, x, v, limits = spec.params, spec.x0, spec.v0, spec.limits
        self.params, self.limits, self.omega, self.b = params, limits, params.omega, params.b
        self.release = (RELEASE, x, v)  # the state before the first event
        self.opening = automaton.opening(params, x, v)  # the row of the automaton the release's arc follows
        # the rebounds the run went on past: the event, the time until they accumulated (s), the first's end (s)
        self.wait_at, self.wait, self.t_acc = array("q"), array("d"), math.nan
        self.t_stop = math.inf if limits.t_end is None else limits.t_end
        self.state, self.v = RELEASE, v  # the last event's kind, and the velocity after it
        self.t_sum = self.t_err = self.time = 0.0
        self.events, self.first = 0, None  # the events so far, and the first one's kind
        self.last = limits.max_events  # the events of the whole run (n_cycles: up to the last impact at a1)
        # per event: its time (s), the velocity before it (m/s), the angle its arc swept (rad)
        self.t, self.v_before, self.angle = array("d"), array("d"), array("d")
        self.outcome: Outcome | None = None
        self.open_arc = False  # the run ended inside an arc (no surface reached, or the end time)
        self.rows = rows(params)
        self.rows[RELEASE] = self.release_row()
        # by event kind (the release at 0): position, the jump of the velocity and the centre of the arc after it
        kinds, factor = range(1, len(self.rows)), automaton.impact_factor(self.b)
        self.position = np.array([math.nan, *(automaton.position(kind, params) for kind in kinds)])
        self.jump = np.array([1.0, *(factor if automaton.is_impact(kind) else 1.0 for kind in kinds)])
        self.centre = np.array([automaton.centre(automaton.ARCS[state or self.opening].mode, params.zone_offset)
                                for state in range(len(self.rows))])
        # by state, the arc after it: for the loop (k, direction, jump, next state), and as arrays (NaN: none)
        self.loop = [None if r is None else (r.k, r.direction, float(self.jump[r.following]), r.following)
                     for r in self.rows]
        self.terms = {name: np.array([math.nan if r is None else getattr(r, name) for r in self.rows])
                      for name in ("u0", "q", "k", "direction")}

    def release_row(self) -> Row | None:
        """The release's arc to the surface reached first (None: none); sets :attr:`first`, :attr:`last`."""
        best, opening = None, automaton.ARCS[self.opening]
        for kind in opening.watched:
            arc = row(self.params, self.release[1], opening.mode, kind)
            reached, dt, _, _ = crossing(arc.u0, arc.q, arc.k, self.v, self.omega, arc.direction)
            if reached and (best is None or dt < best[0]):
                best = (dt, arc)
        if best is None:
            return None
        self.first = best[1].following
        if self.limits.n_cycles is not None:  # the (n_cycles + 1)-th impact at a1 ends the run
            self.last = min(self.last, self._before_a1() + len(PLAN) * self.limits.n_cycles + 1)
        return best[1]

    def _before_a1(self) -> int:
        """The events before the first impact at a1."""
        return (PLAN.index(A1) - PLAN.index(self.first)) % len(PLAN)

    def advance(self, n: int) -> None:
        """Run at most ``n`` more events, or until the run ends (:attr:`outcome` set)."""
        while n > 0 and self.outcome is None:
            n -= self._block(min(n, BLOCK_EVENTS, self.last - self.events))

    def _arrivals(self, limit: int):
        """The velocity before each of at most ``limit`` events; then :attr:`walked` and :attr:`ending` are set."""
        loop, state, v, sqrt = self.loop, self.state, self.v, math.sqrt
        self.ending = NO_EVENT if loop[state] is None else None  # from the release, neither impact is reached
        for _ in range(limit if self.ending is None else 0):
            k, direction, jump, following = loop[state]
            v_sq = v * v + k
            if not v_sq > 0.0:  # the arc turns short of its surface (crossing's ``reached``)
                self.ending = NO_EVENT
                break
            v1 = direction * sqrt(v_sq)
            yield v1
            state, v = following, jump * v1
            if jump < 0.0:  # the impact reversed the velocity (b > 1)
                self.ending = REBOUND
                break
        self.walked = (state, v)

    def _block(self, limit: int) -> int:
        """At most ``limit`` events: the velocities by the loop, then angles and times on arrays; the events kept."""
        v_before = np.fromiter(self._arrivals(limit), float)
        (state, v), ending, kept = self.walked, self.ending, len(v_before)
        if kept:
            kind = kinds_from(self.first, self.events, kept)
            start = np.concatenate(([self.state], kind[:-1]))  # the state each arc starts from
            v_start = np.concatenate(([self.v], self.jump[kind[:-1]] * v_before[:-1]))
            u0, q, k, direction = (column[start] for column in self.terms.values())
            _, dt, _, angle = crossing(u0, q, k, v_start, self.omega, direction, LIBM)
            # the compensated sum as the loop would add it: the running sum, and that of each addition's rounding
            t_sum = np.cumsum(np.concatenate(([self.t_sum], dt)))
            t_err = np.cumsum(np.concatenate(([self.t_err], two_sum(t_sum[:-1], dt)[1])))
            t = t_sum[1:] + t_err[1:]
            late = np.flatnonzero(t > self.t_stop)
            if len(late):  # the end time comes before event ``kept``: the run ends inside its arc
                kept, ending = int(late[0]), HORIZON
                state, v = (int(kind[kept - 1]) if kept else self.state), float(v_start[kept])
            for stored, column in ((self.t, t), (self.v_before, v_before), (self.angle, angle)):
                stored.frombytes(column[:kept].view(np.uint8))
            self.t_sum, self.t_err = float(t_sum[kept]), float(t_err[kept])
            self.time = float(t[kept - 1]) if kept else self.time
            self.state, self.v, self.events = state, v, self.events + kept
        self._end(ending, float(v_before[-1]) if ending == REBOUND else math.nan)
        return kept

    def past(self, v1: float) -> str | None:
        """After a rebound (``v1`` the velocity before it): None if the run goes on past it, else :data:`REBOUND`."""
        wait = accumulation(self.params, EventKind(self.state), v1, self.v)
        if self.params.past_accumulation == "stop" or math.isnan(wait):
            return REBOUND
        self.wait_at.append(self.events - 1)
        self.wait.append(wait)
        self.t_acc, self.v = self.time + wait if math.isnan(self.t_acc) else self.t_acc, 0.0
        self.t_sum, self.t_err = compensated_add(self.t_sum, self.t_err, wait)
        return None

    def _end(self, ending: str | None, v1: float) -> None:
        """The outcome of a block that ended with ``ending``, or at the run's last event."""
        last_cycle = self.limits.n_cycles is not None and self.impacts_a1() == self.limits.n_cycles + 1
        ending = self.past(v1) if ending == REBOUND and not last_cycle else ending
        if ending in (NO_EVENT, HORIZON):
            self.open_arc = True
            self.outcome = self._no_event() if ending == NO_EVENT else horizon_outcome(self.t_stop, self.impacts_a1())
        elif last_cycle:
            self.outcome = completed_outcome(self.limits.n_cycles, self.time, self.t_acc)
        elif ending == REBOUND:
            self.outcome = chattering_outcome(self.params, EventKind(self.state), self.time, v1, self.v)
        elif self.events >= self.last:
            message = event_limit_message(float(self.time), self.limits.max_events)
            self.outcome = Outcome(Status.EVENT_LIMIT, message, Exit(), self.time)

    def _no_event(self) -> Outcome:
        """No watched surface is passed from the last state: the turning point of its arc."""
        x = self.release[1] if self.state == RELEASE else automaton.position(self.state, self.params)
        state = self.state or self.opening
        mode = automaton.ARCS[state].mode
        centre = automaton.centre(mode, self.params.zone_offset)
        if mode == Mode.FREE:  # the swing's radius, for ever
            dt, turning = math.inf, math.hypot(x - centre, self.v / self.omega)
        else:
            dt, turning = time_to_rest(centre, x, self.v, self.omega)
        return no_event_outcome(self.params, state, centre, self.time, dt, turning, self.t_stop, self.impacts_a1())

    def impacts_a1(self) -> int:
        """The impacts at a1 so far: one in each :data:`PLAN` of events from the first."""
        return 0 if self.first is None else (self.events - self._before_a1() + len(PLAN) - 1) // len(PLAN)

    def take(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The events stored since the last call (t, v_before, angle), as arrays over the buffers."""
        columns = tuple(np.frombuffer(column) if len(column) else np.zeros(0)
                        for column in (self.t, self.v_before, self.angle))
        self.t, self.v_before, self.angle = array("d"), array("d"), array("d")
        return columns


class Block(NamedTuple):
    """Consecutive events of a run, each with the arc that ends at it, on arrays, and the cycles they complete."""

    kind: np.ndarray
    t: np.ndarray  #: s
    x: np.ndarray  #: m
    v_before: np.ndarray  #: m/s
    v_after: np.ndarray  #: m/s
    arc_centre: np.ndarray  #: the centre of the arc, m (one more than the events: the arc after the last)
    arc_x: np.ndarray  #: where the arc starts, m (likewise)
    arc_v: np.ndarray  #: the velocity it starts with, m/s (likewise)
    cycles: tuple  #: impact times (s), velocities before them (m/s), periods (s) and amplitudes (m)
    begins: int  #: the index of the impact at a1 that begins the unfinished cycle (the events' number: none)


def event_block(run: EventRun, start: int, t: np.ndarray, v_before: np.ndarray, angle: np.ndarray,
                before: tuple[int, float, float]) -> Block:
    """The events ``start ..`` of ``run`` on arrays (``before``: the state before the first) and their cycles."""
    n = len(t)
    kind = kinds_from(run.first, start, n) if n else np.zeros(0, dtype=np.intp)
    x, v_after = run.position[kind], run.jump[kind] * v_before
    arc_centre = np.concatenate(([run.centre[before[0]]], run.centre[kind]))
    arc_x, arc_v = np.concatenate(([before[1]], x)), np.concatenate(([before[2]], v_after))
    waited = np.zeros(n + 1)  # by arc, the time its start waited for the rebounds before it to accumulate
    if len(run.wait_at):  # the arcs after the rebounds the run went on past start from rest
        at = np.frombuffer(run.wait_at, np.int64)
        lo, hi = np.searchsorted(at, [start - 1, start + n])
        arc_v[at[lo:hi] - start + 1], waited[at[lo:hi] - start + 1] = 0.0, np.frombuffer(run.wait)[lo:hi]
    at_a1, width = np.flatnonzero(kind == A1), len(PLAN)
    m = max(len(at_a1) - 1, 0)
    arcs = slice(at_a1[0] + 1, at_a1[0] + 1 + m * width) if m else slice(0, 0)  # the arcs of the complete cycles
    dt = (angle[arcs] / run.omega + waited[arcs]).reshape(m, width)
    arc_max = arc_maximum(arc_centre[arcs], arc_x[arcs], arc_v[arcs], run.omega, angle[arcs], x[arcs], v_before[arcs])
    arc_max = arc_max.reshape(m, width)
    period, amplitude = dt[:, 0].copy(), np.maximum(x[at_a1[:m]], arc_max[:, 0])
    for j in range(1, width):  # in the order of the events, as a running sum and maximum
        period += dt[:, j]
        amplitude = np.maximum(amplitude, arc_max[:, j])
    return Block(kind.astype(np.int8), t, x, v_before, v_after, arc_centre, arc_x, arc_v,
                 (t[at_a1[:m]], v_before[at_a1[:m]], period, amplitude), int(at_a1[-1]) if len(at_a1) else n)
