"""The exact event-driven solver.

Between events the motion is a harmonic arc about the current mode's centre, so each event
(impact, end of an impulse zone) comes from a closed form
(:func:`escapement.model.kinematics.crossing`): no step size, no root finding, errors at the
level of floating-point rounding. The escapement's rules come from
:mod:`escapement.model.automaton`.

The loop. The generic solver loop (:func:`escapement.solvers.driver.drive`) asks a stepper for
every event; the exact solver runs its own loop over the same automaton (:class:`ClosedFormRun`),
specialised to the closed forms. After the first event every mode the automaton enters watches a
single surface, so the arc that follows each kind of event is known in advance: :func:`stages`
builds it from the automaton's transitions, centres and watched surfaces, with the terms of
:func:`~escapement.model.kinematics.crossing` that depend only on the surfaces computed once.
Per event the loop does the rest of that closed form (the same operations in the same order: the
same numbers), the compensated time sum, the impact law at impacts, and stores the event's time
and velocity; each event's kind, position and velocity after it, and the trajectory's arcs,
follow from the automaton and are filled in at the end, on arrays. The first arc (two watched
surfaces) and every ending (no surface reached, end time, chattering) go through
:class:`ClosedFormStepper` and the outcome functions of :mod:`escapement.solvers.driver`, as in
the generic loop (:func:`solve_exact_stepwise`), which the test suite compares with this one number by
number.

The amplitude. The largest ``x`` of an arc is the top of its circle, ``c + R``, if the arc passes
it, otherwise the larger of its two ends (:func:`~escapement.model.kinematics.arc_maximum`, which
tells the two apart by comparing the phase of the top with the angle swept). The arc after an
event starts moving in that surface's direction (the impact law keeps the sign for ``b < 1``) and
arrives moving in its target's, which decides the case without an ``atan2``: in the phase plane the
top is at phase 0 and the motion turns clockwise, so

* starting right and arriving left (a2 to a3, the free swing), the arc passes the top: its angle
  exceeds the phase of the top by the end's phase, ``|atan2(w1, q)|``;
* starting and arriving right towards a larger ``x`` (a1 to a2), or left towards a smaller ``x``
  (a3 to a4), the arc turns through less than the phase of the top and less than ``pi``;
* starting left and arriving right (a4 to a1, round the bottom), it stops short of the top by the
  end's phase.

The margin, the end's phase, is at least about ``|w1 / q|``, far above the rounding of the two
``atan2`` (a few 1e-16 rad) unless the arc arrives within ``|w1| <= 1e-6 |q|`` of a turning point.
So the loop takes ``c + hypot(u0, w0)`` or the larger end directly, and calls ``arc_maximum`` itself
where the arc starts at rest or against the expected direction (``b = 1`` leaves the mass at rest
after an impact), arrives that close to a turning point, or sweeps an angle outside the range its
case implies: the same number as ``arc_maximum`` in every case. Only the arcs after the first impact
at a1 count (the table starts there).
"""

from __future__ import annotations

import math
from array import array
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import arc_maximum, compensated_add, crossing, time_to_rest
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state
from ..model.status import Status, event_limit_message
from .driver import (
    HORIZON,
    NO_EVENT,
    Outcome,
    Step,
    chattering_outcome,
    check_memory,
    drive,
    finish,
    horizon_outcome,
    no_event_outcome,
)
from .result import ArcTable, CycleTable, Exit, Solution

__all__ = [
    "ClosedFormRun",
    "ClosedFormStepper",
    "Packed",
    "Stage",
    "cycle_plan",
    "solve_exact",
    "solve_exact_stepwise",
    "stages",
]

TWO_PI = 2.0 * math.pi
#: ``arc_maximum`` is called where the arc arrives with ``w1**2 <= GRAZING * q**2`` (``|w1| <= 1e-6 |q|``)
GRAZING = 1e-12
#: events per pass of the loop, between which the stored columns move from lists into packed arrays
SEGMENT = 1 << 12
#: bytes per event at the peak of :func:`solve_exact`: its time, position and velocities (8 bytes each) and
#: kind (1) in the result; the time and velocity in growing buffers up to 1/16 over-allocated; and while
#: the velocities after the impacts are filled in, the impacts' mask and their velocities (up to 17)
EVENT_BYTES = 52
#: bytes per event of the arcs when the trajectory is kept: start time, centre, position, velocity
ARC_BYTES = 32
#: bytes per cycle: impact time, velocity, period and amplitude (8 bytes each), in growing buffers
CYCLE_BYTES = 36
#: bytes of one pass of the loop as Python floats in lists (32 bytes each with its pointer), whatever the run's
#: length: the time and velocity of SEGMENT events and the four columns of the SEGMENT / 4 cycles they make
PASS_BYTES = 32 * (2 * SEGMENT + SEGMENT)
#: the automaton's own impact law and test of a rebound, which the loop may apply in the form of a factor
_PAPER_LAW, _PAPER_REVERSES = automaton.velocity_after, automaton.reverses
#: the stage tables kept (see :func:`stages`)
_STAGE_CACHE_SIZE = 256
_STAGE_CACHE: dict[tuple[str, ...], tuple] = {}
# how a pass of the loop ends
_PAUSE, _NO_EVENT, _HORIZON, _COMPLETED, _CHATTERING = range(5)
_REMEDY = "raise memory_budget, or stream the cycles in constant memory with escapement.solvers.iter_cycles"


class ClosedFormStepper:
    """Each event in closed form; keeps the arcs for sampling when asked to (the generic loop's stepper)."""

    name = "exact"

    def __init__(self, params: Parameters, record_trajectory: bool) -> None:
        self.omega = params.omega
        self.targets = {kind: (automaton.position(kind, params), s.direction) for kind, s in automaton.SURFACES.items()}
        self.record = record_trajectory
        self.arcs = tuple(array("d") for _ in range(4))
        self.trajectory_bytes_per_event = 34 if record_trajectory else 0  # four growing columns of floats

    def next_event(self, mode, centre, t, x, v, watched, t_stop) -> Step:
        omega = self.omega
        if self.record:
            for column, value in zip(self.arcs, (t, centre, x, v)):
                column.append(value)
        best = None
        for kind in watched:
            target, direction = self.targets[kind]
            reached, dt, v_new, angle = crossing(centre, x, v, omega, target, direction)
            if reached and (best is None or dt < best[1]):
                best = (kind, dt, v_new, angle, target)
        if best is None:
            if mode == automaton.Mode.FREE:
                return Step(NO_EVENT, math.inf, 0.0, math.hypot(x, v / omega))
            rest_dt, turning_point = time_to_rest(centre, x, v, omega)
            return Step(NO_EVENT, rest_dt, 0.0, turning_point)
        kind, dt, v_new, angle, target = best
        return kind, dt, v_new, arc_maximum(centre, x, v, omega, angle, target), None, None  # a Step

    def trajectory(self, t_final: float) -> ArcTable | None:
        if not self.record:
            return None
        t_start, centre, x_start, v_start = (np.frombuffer(c, dtype=float) for c in self.arcs)
        return ArcTable(t_start, centre, x_start, v_start, self.omega, t_final)


class Stage(NamedTuple):
    """The arc that follows an event of one kind: the mode's single watched surface and the terms of
    :func:`~escapement.model.kinematics.crossing` that depend on the surfaces only."""

    next_kind: int  #: the event that ends the arc
    x_from: float  #: where the arc starts: the position of the event before it
    target: float  #: where it ends
    direction: float  #: the direction of motion at the end, +1.0 or -1.0
    centre: float  #: the centre of the arc's mode
    u0: float  #: x_from - centre
    q: float  #: target - centre
    k: float  #: omega**2 (x_from - target)(x_from + target - 2 centre): v_end**2 = v**2 + k
    grazing: float  #: GRAZING * q**2
    floor: float  #: max(x_from, target), the arc's largest x if it does not pass the top
    top: bool  #: the arc passes the top of its circle (starting right, arriving left)
    angle_cap: float  #: the shortcut for the amplitude holds only for angles below this (-inf: never)
    start: float  #: the direction of motion at the start the shortcut assumes, +1.0 or -1.0
    impact: bool  #: the event that ends the arc is an impact (the impact law applies)
    at_a1: bool  #: the event that ends the arc is the impact at a1 (a cycle ends)
    factor: float  #: the paper's impact law as a factor, ``1.0 - b * impact`` (see ClosedFormRun)


def stages(params: Parameters) -> tuple[Stage | None, ...]:
    """For each event kind (by its code), the arc that follows it, from the automaton: the mode it
    enters (:func:`~escapement.model.automaton.transition`), that mode's centre and its single watched
    surface. None where the automaton's mode after the event watches several surfaces (there is no
    such event: only the initial mode watches two). Kept for :data:`_STAGE_CACHE_SIZE` parameter sets, by
    the exact bits of their values (``0.0`` and ``-0.0`` apart)."""
    key = tuple(value.hex() for value in params.as_dict().values())
    table = _STAGE_CACHE.get(key)
    if table is None:
        if len(_STAGE_CACHE) >= _STAGE_CACHE_SIZE:
            _STAGE_CACHE.clear()
        table = _STAGE_CACHE[key] = _stages(params)
    return table


def _stages(params: Parameters) -> tuple[Stage | None, ...]:
    omega = params.omega
    table: list[Stage | None] = [None] * (max(EventKind) + 1)
    for kind in EventKind:
        mode, awaited = automaton.transition(kind)
        watched = automaton.watched(mode, awaited)
        if len(watched) != 1:
            continue
        (nxt,) = watched
        x_from, target = automaton.position(kind, params), automaton.position(nxt, params)
        centre = automaton.centre(mode, params.zone_offset)
        start, end = automaton.SURFACES[kind].direction, automaton.SURFACES[nxt].direction
        top = start > 0 > end
        if top or (start < 0 < end):
            cap = math.inf  # over the top, or round the bottom: a margin of the end's phase
        elif (start > 0 and end > 0 and target > x_from) or (start < 0 and end < 0 and target < x_from):
            cap = math.pi  # straight on: less than half a turn
        else:
            cap = -math.inf  # not a case above: arc_maximum every time
        q = target - centre
        table[kind] = Stage(
            next_kind=int(nxt), x_from=x_from, target=target, direction=float(end), centre=centre,
            u0=x_from - centre, q=q, k=(omega * omega) * ((x_from - target) * (x_from + target - 2.0 * centre)),
            grazing=GRAZING * (q * q), floor=max(x_from, target), top=top, angle_cap=cap, start=float(start),
            impact=automaton.is_impact(nxt), at_a1=nxt == EventKind.IMPACT_A1,
            factor=1.0 - params.b * automaton.is_impact(nxt),
        )
    return tuple(table)


def cycle_plan(table: tuple[Stage | None, ...]) -> tuple[Stage, Stage, Stage, Stage] | None:
    """The arcs of a cycle, from an impact at a1 to the next, as the automaton gives them (:func:`stages`),
    when they are four with a single impact at a1, the last (the unrolled loop of :class:`ClosedFormRun` is
    written for that), each ending in a jump that keeps the direction (``factor > 0``: ``b < 1``); else None."""
    plan = []
    kind = int(EventKind.IMPACT_A1)
    for _ in range(4):
        stage = table[kind]
        if stage is None or not stage.factor > 0.0:
            return None
        plan.append(stage)
        kind = stage.next_kind
    if kind != EventKind.IMPACT_A1 or any(stage.at_a1 for stage in plan[:-1]):
        return None
    return tuple(plan)


class ClosedFormRun:
    """The exact solver's event loop, resumable: :meth:`advance` runs it for a bounded number of events
    and leaves its state (time sums, state, the cycle under way) for the next call, so that a run in
    several passes gives the numbers of a run in one.

    Each complete cycle appends its impact time, velocity before the impact, period and amplitude to
    :attr:`cycle_columns` (lists); with ``keep_events`` each event appends its time and velocity
    before it to :attr:`event_columns`. The caller empties the lists between passes. When the run
    ends, :attr:`outcome` is set.
    """

    def __init__(self, params: Parameters, x: float, v: float, limits: RunLimits, keep_events: bool) -> None:
        self.params = params
        self.limits = limits
        self.keep_events = keep_events
        self.stepper = ClosedFormStepper(params, record_trajectory=False)
        self.stages = stages(params)
        self.target_impacts = math.inf if limits.n_cycles is None else limits.n_cycles + 1
        self.t_stop = math.inf if limits.t_end is None else limits.t_end
        self.x0, self.v0 = x, v
        self.zero = x * 0
        self.b = self.zero + params.b
        # the state after the last event: its kind (None before the first), the velocity after it
        self.kind: int | None = None
        self.v = v
        self.t_sum = self.t_err = self.t = self.zero
        self.elapsed = self.zero  # time since the last impact at a1, summed inside the cycle for an exact period
        self.cycle_max = -math.inf
        self.impacts_a1 = 0
        self.pending = (math.nan, math.nan)  # time and velocity of the impact at a1 that began the cycle
        self.events = 0
        self.cycles = 0  # complete cycles
        self.first_kind: int | None = None
        # the paper's impact law as factors, none negative: the loop need not call the law nor test for rebounds
        self.factors = (automaton.velocity_after is _PAPER_LAW and automaton.reverses is _PAPER_REVERSES
                        and all(stage is None or stage.factor >= 0.0 for stage in self.stages))
        self.plan = cycle_plan(self.stages) if self.factors else None
        self.open_arc = False  # the run ended inside an arc (no surface reached, or the end time)
        self.outcome: Outcome | None = None
        self.event_columns: tuple[list, list] = ([], [])
        self.cycle_columns: tuple[list, list, list, list] = ([], [], [], [])

    def advance(self, max_events: int, max_cycles: float = math.inf) -> None:
        """Run at most ``max_events`` more events; stop earlier after ``max_cycles`` more complete
        cycles, or when the run ends (:attr:`outcome` set).

        From each impact at a1 the cycles run unrolled (:meth:`_cycles`) while they take the common
        path; the per-event loop (:meth:`_loop`) takes the first cycle, every arc the unrolled one leaves
        (an ending, an amplitude it does not take in its shortcut) up to the next impact at a1, and the
        whole run when there is no plan."""
        if self.outcome is not None:
            return
        last_event = min(self.events + max_events, self.limits.max_events)
        last_cycle = self.cycles + max_cycles
        if self.kind is None:
            self._first_event()
        # each pass runs at least one event, or a cycle-run that stops before its first event and then one
        for _ in range(2 * max_events + 2):
            if self.outcome is not None or self.events >= last_event or self.cycles >= last_cycle:
                break
            if self.plan is not None and self.kind == EventKind.IMPACT_A1:
                n = min(last_cycle - self.cycles, self.target_impacts - self.impacts_a1,
                        (last_event - self.events) // len(self.plan))
                if n >= 1 and self._cycles(int(n)):
                    if self.impacts_a1 >= self.target_impacts:  # the last impact at a1 completes the run
                        self._end(Outcome(Status.COMPLETED, f"completed {self.impacts_a1 - 1} cycles", Exit(), self.t))
                    continue
            self._loop(last_event - self.events, last_cycle - self.cycles)
        else:
            raise RuntimeError(f"the closed-form loop made no progress at t = {self.t!r}")
        if self.outcome is None and self.events >= self.limits.max_events:
            self._end(Outcome(Status.EVENT_LIMIT, event_limit_message(float(self.t), self.limits.max_events), Exit(),
                              self.t))

    def _first_event(self) -> None:
        """The first arc, in the automaton's initial mode (which watches two surfaces), by the stepper."""
        mode, awaited = automaton.INITIAL
        centre = automaton.centre(mode, self.params.zone_offset)
        x, v, t = self.x0, self.v, self.t
        step = self.stepper.next_event(mode, centre, t, x, v, automaton.watched(mode, awaited), self.t_stop)
        if step[0] == NO_EVENT:
            self._end(no_event_outcome(self.params, mode, awaited, centre, t, step.dt, step.x_max), open_arc=True)
            return
        kind, dt, v_before = step[0], step[1], step[2]
        if kind == HORIZON or t + dt > self.t_stop:
            self._end(horizon_outcome(self.t_stop, 0), open_arc=True)
            return
        self.t_sum, self.t_err = compensated_add(self.t_sum, self.t_err, dt)
        self.t = t = self.t_sum + self.t_err
        self.elapsed += dt
        self.events = 1
        self.first_kind = int(kind)
        if self.keep_events:
            self.event_columns[0].append(t)
            self.event_columns[1].append(v_before)
        v_after = automaton.velocity_after(v_before, self.b, automaton.is_impact(kind))
        if kind == EventKind.IMPACT_A1:
            self.impacts_a1 = 1
            self.pending = (t, v_before)
            self.cycle_max = automaton.position(kind, self.params)
            self.elapsed = self.zero
        if automaton.reverses(v_before, v_after):
            self._end(chattering_outcome(self.params, kind, t, v_before, v_after))
            return
        self.kind, self.v = int(kind), v_after

    def _loop(self, n: int, max_cycles: float) -> None:
        """At most ``n`` events from the state after the last one (see the module's docstring).

        The impact law is the automaton's :func:`~escapement.model.automaton.velocity_after`, called at
        each impact; while it is the paper's, ``(1 - b * impact) * v``, it is applied as the stage's
        ``factor`` (the same operations: the same number), and when no factor is negative (``b <= 1``)
        ``v_after * v_before = factor * v_before**2`` is never negative, so no impact can reverse the
        velocity and :func:`~escapement.model.automaton.reverses` need not be asked."""
        table = self.stages
        omega, b, zero, t_stop = self.params.omega, self.b, self.zero, self.t_stop
        sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
        law, reverses = automaton.velocity_after, automaton.reverses
        factors = self.factors
        hand_over = self.plan is not None  # stop at an impact at a1, where the unrolled cycles take over
        keep = self.keep_events
        ev_t, ev_v = (column.append for column in self.event_columns)
        cy_t, cy_v, cy_p, cy_m = (column.append for column in self.cycle_columns)
        kind, v, t_sum, t_err, t = self.kind, self.v, self.t_sum, self.t_err, self.t
        elapsed, cycle_max, impacts, target_impacts = self.elapsed, self.cycle_max, self.impacts_a1, self.target_impacts
        pending_t, pending_v = self.pending
        done = 0
        ending = _PAUSE
        count = 0
        for count in range(1, n + 1):
            (nxt, x_from, target, direction, c, u0, q, k, grazing, floor, top, cap, start, impact, at_a1,
             factor) = table[kind]
            # crossing(c, x_from, v, omega, target, direction), its surface terms taken from the stage
            v_sq = v * v + k
            if not v_sq > 0.0:
                ending = _NO_EVENT
                break
            v1 = direction * sqrt(v_sq)
            w0 = v / omega
            w1 = v1 / omega
            angle = atan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
            if angle <= 0.0:
                angle += TWO_PI
            dt = angle / omega
            if t + dt > t_stop:
                ending = _HORIZON
                break
            if w0 * start > 0.0 and angle < cap and w1 * w1 > grazing:
                m = c + hypot(u0, w0) if top else floor
            else:
                m = arc_maximum(c, x_from, v, omega, angle, target)
            if m > cycle_max:  # max(cycle_max, m), NaN included
                cycle_max = m
            # compensated_add(t_sum, t_err, dt): t_sum >= 0 and dt > 0, so |t_sum| >= |dt| is t_sum >= dt
            new = t_sum + dt
            if t_sum >= dt:
                t_err += (t_sum - new) + dt
            else:
                t_err += (dt - new) + t_sum
            t_sum = new
            t = t_sum + t_err
            elapsed += dt
            if keep:
                ev_t(t)
                ev_v(v1)
            v_after = factor * v1 if factors else law(v1, b, impact)
            if at_a1:
                impacts += 1
                if impacts > 1:
                    cy_t(pending_t)
                    cy_v(pending_v)
                    cy_p(elapsed)
                    cy_m(cycle_max)
                    done += 1
                pending_t, pending_v = t, v1
                cycle_max = target
                elapsed = zero
                if impacts >= target_impacts:
                    ending = _COMPLETED
                    break
                if not factors and reverses(v1, v_after):
                    ending = _CHATTERING
                    break
                v = v_after
                kind = nxt
                if hand_over or done >= max_cycles:
                    break
                continue
            if not factors and reverses(v1, v_after):
                ending = _CHATTERING
                break
            v = v_after
            kind = nxt
        inside = ending == _NO_EVENT or ending == _HORIZON  # the pass ended inside an arc, without its event
        self.events += count - inside
        self.cycles += done
        self.v, self.t_sum, self.t_err, self.t, self.elapsed = v, t_sum, t_err, t, elapsed
        self.cycle_max, self.impacts_a1, self.pending = cycle_max, impacts, (pending_t, pending_v)
        self.kind = kind if inside or ending == _PAUSE else table[kind].next_kind
        if ending == _NO_EVENT:
            mode, awaited = automaton.transition(kind)
            stage = table[kind]
            step = self.stepper.next_event(mode, stage.centre, t, stage.x_from, v, automaton.watched(mode, awaited),
                                           t_stop)
            if step[0] != NO_EVENT:
                raise RuntimeError(f"the closed-form loop and its stepper disagree at t = {t!r}: {step}")
            self._end(no_event_outcome(self.params, mode, awaited, stage.centre, t, step.dt, step.x_max), True)
        elif ending == _HORIZON:
            self._end(horizon_outcome(t_stop, impacts), open_arc=True)
        elif ending == _COMPLETED:
            self._end(Outcome(Status.COMPLETED, f"completed {impacts - 1} cycles", Exit(), t))
        elif ending == _CHATTERING:
            self._end(chattering_outcome(self.params, EventKind(self.kind), t, v1, v_after))

    def _cycles(self, n: int) -> bool:
        """At most ``n`` cycles from an impact at a1, the four arcs of :attr:`plan` unrolled: the per-event
        loop's arithmetic on the common path only (an event is reached before the end time, the amplitude's
        shortcut holds, the impact law is the paper's with ``b < 1``). Where an arc leaves it, stop before
        that arc, the state that of the event before it; the per-event loop goes on from there. True if
        all ``n`` cycles ran."""
        (_, _, _, d0, c0, u0, q0, k0, g0, f0, top0, cap0, s0, _, _, r0), \
            (_, _, _, d1, c1, u1, q1, k1, g1, f1, top1, cap1, s1, _, _, r1), \
            (_, _, _, d2, c2, u2, q2, k2, g2, f2, top2, cap2, s2, _, _, r2), \
            (_, _, _, d3, c3, u3, q3, k3, g3, f3, top3, cap3, s3, _, _, r3) = self.plan
        a1 = self.plan[-1].target
        omega, zero, t_stop = self.params.omega, self.zero, self.t_stop
        sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
        keep = self.keep_events
        ev_t, ev_v = (column.append for column in self.event_columns)
        cy_t, cy_v, cy_p, cy_m = (column.append for column in self.cycle_columns)
        v, t_sum, t_err, t = self.v, self.t_sum, self.t_err, self.t
        elapsed, cycle_max = self.elapsed, self.cycle_max
        pending_t, pending_v = self.pending
        arc = cycle = 0
        for cycle in range(n):
            # each arc as in _loop: crossing() with the stage's terms, the amplitude's shortcut, the
            # compensated time sum, the stored event, the impact law as the stage's factor
            arc = 0
            v_sq = v * v + k0
            if not v_sq > 0.0:
                break
            v1 = d0 * sqrt(v_sq)
            w0 = v / omega
            w1 = v1 / omega
            angle = atan2(w0 * q0 - u0 * w1, u0 * q0 + w0 * w1)
            if angle <= 0.0:
                angle += TWO_PI
            dt = angle / omega
            if t + dt > t_stop or not (w0 * s0 > 0.0 and angle < cap0 and w1 * w1 > g0):
                break
            m = c0 + hypot(u0, w0) if top0 else f0
            if m > cycle_max:
                cycle_max = m
            new = t_sum + dt
            if t_sum >= dt:
                t_err += (t_sum - new) + dt
            else:
                t_err += (dt - new) + t_sum
            t_sum = new
            t = t_sum + t_err
            elapsed += dt
            if keep:
                ev_t(t)
                ev_v(v1)
            v = r0 * v1

            arc = 1
            v_sq = v * v + k1
            if not v_sq > 0.0:
                break
            v1 = d1 * sqrt(v_sq)
            w0 = v / omega
            w1 = v1 / omega
            angle = atan2(w0 * q1 - u1 * w1, u1 * q1 + w0 * w1)
            if angle <= 0.0:
                angle += TWO_PI
            dt = angle / omega
            if t + dt > t_stop or not (w0 * s1 > 0.0 and angle < cap1 and w1 * w1 > g1):
                break
            m = c1 + hypot(u1, w0) if top1 else f1
            if m > cycle_max:
                cycle_max = m
            new = t_sum + dt
            if t_sum >= dt:
                t_err += (t_sum - new) + dt
            else:
                t_err += (dt - new) + t_sum
            t_sum = new
            t = t_sum + t_err
            elapsed += dt
            if keep:
                ev_t(t)
                ev_v(v1)
            v = r1 * v1

            arc = 2
            v_sq = v * v + k2
            if not v_sq > 0.0:
                break
            v1 = d2 * sqrt(v_sq)
            w0 = v / omega
            w1 = v1 / omega
            angle = atan2(w0 * q2 - u2 * w1, u2 * q2 + w0 * w1)
            if angle <= 0.0:
                angle += TWO_PI
            dt = angle / omega
            if t + dt > t_stop or not (w0 * s2 > 0.0 and angle < cap2 and w1 * w1 > g2):
                break
            m = c2 + hypot(u2, w0) if top2 else f2
            if m > cycle_max:
                cycle_max = m
            new = t_sum + dt
            if t_sum >= dt:
                t_err += (t_sum - new) + dt
            else:
                t_err += (dt - new) + t_sum
            t_sum = new
            t = t_sum + t_err
            elapsed += dt
            if keep:
                ev_t(t)
                ev_v(v1)
            v = r2 * v1

            arc = 3
            v_sq = v * v + k3
            if not v_sq > 0.0:
                break
            v1 = d3 * sqrt(v_sq)
            w0 = v / omega
            w1 = v1 / omega
            angle = atan2(w0 * q3 - u3 * w1, u3 * q3 + w0 * w1)
            if angle <= 0.0:
                angle += TWO_PI
            dt = angle / omega
            if t + dt > t_stop or not (w0 * s3 > 0.0 and angle < cap3 and w1 * w1 > g3):
                break
            m = c3 + hypot(u3, w0) if top3 else f3
            if m > cycle_max:
                cycle_max = m
            new = t_sum + dt
            if t_sum >= dt:
                t_err += (t_sum - new) + dt
            else:
                t_err += (dt - new) + t_sum
            t_sum = new
            t = t_sum + t_err
            elapsed += dt
            if keep:
                ev_t(t)
                ev_v(v1)
            v = r3 * v1
            # the impact at a1 ends the cycle
            cy_t(pending_t)
            cy_v(pending_v)
            cy_p(elapsed)
            cy_m(cycle_max)
            pending_t, pending_v = t, v1
            cycle_max = a1
            elapsed = zero
        else:
            cycle, arc = n, 0
        self.events += len(self.plan) * cycle + arc
        self.cycles += cycle
        self.impacts_a1 += cycle
        self.kind = self.plan[arc - 1].next_kind  # the event before the arc it stopped at
        self.v, self.t_sum, self.t_err, self.t, self.elapsed = v, t_sum, t_err, t, elapsed
        self.cycle_max, self.pending = cycle_max, (pending_t, pending_v)
        return cycle == n

    def _end(self, outcome: Outcome, open_arc: bool = False) -> None:
        self.outcome = outcome
        self.open_arc = open_arc

    def kinds(self, n: int) -> np.ndarray:
        """The kinds of the first ``n`` events: the first, then each the next of the one before (:func:`stages`)."""
        if n == 0:
            return np.zeros(0, dtype=np.int8)
        chain = [self.first_kind]
        for _ in range(len(EventKind)):  # the kinds repeat within as many steps as there are kinds
            stage = self.stages[chain[-1]]
            if stage is None:
                break
            chain.append(stage.next_kind)
        repeat = chain.index(chain[-1])  # chain[repeat:-1] is the period
        if repeat == len(chain) - 1:
            if n > len(chain):
                raise RuntimeError(f"the event kinds after {chain} do not repeat")
            return np.array(chain[:n], dtype=np.int8)
        head, period = chain[:repeat], chain[repeat:-1]
        out = np.empty(n, dtype=np.int8)
        out[:len(head)] = head[:n]
        if n > len(head):
            rest = n - len(head)
            out[len(head):] = np.tile(np.array(period, dtype=np.int8), -(-rest // len(period)))[:rest]
        return out


class Packed:
    """Float columns packed in ``array('d')``, filled from a run's lists between passes."""

    def __init__(self, lists: tuple[list, ...]) -> None:
        self.lists = lists
        self.arrays = tuple(array("d") for _ in lists)

    def take(self) -> None:
        for packed, values in zip(self.arrays, self.lists):
            packed.fromlist(values)
            values.clear()

    def numpy(self) -> tuple[np.ndarray, ...]:
        """Views of the packed columns (no copy; they keep the buffers alive)."""
        return tuple(np.frombuffer(a, dtype=float) if len(a) else np.zeros(0) for a in self.arrays)


def solve_exact(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int | None = None,
    t_end: float | None = None,
    max_events: int | None = None,
    record_trajectory: bool = True,
    memory_budget: int | None = None,
) -> Solution:
    """Integrate the escapement model exactly from ``(x0, v0)`` at ``t = 0+``.

    The run ends after ``n_cycles`` complete cycles, at ``t_end``, after ``max_events``
    events, or when the motion leaves the escapement regime; the returned
    :class:`~escapement.solvers.result.Solution` says which, in ``status`` and ``message``.
    With ``record_trajectory=False`` the arcs are not kept (for long runs that need only
    events and cycles).

    Before any work the size of the result is estimated from the limits (per event
    :data:`EVENT_BYTES`, plus :data:`ARC_BYTES` with the trajectory; per cycle :data:`CYCLE_BYTES`; and
    :data:`PASS_BYTES` for the loop's lists) and a
    run above ``memory_budget`` bytes (default :data:`~escapement.model.limits.MEMORY_BUDGET`) is refused
    with a :class:`~escapement.model.limits.MemoryBudgetError`; :func:`escapement.solvers.stream.iter_cycles`
    gives the cycles of any run in constant memory.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run (cycle ``k`` runs from the ``k``-th impact at ``a1`` to the next); at
        least one of ``n_cycles`` and ``t_end`` is given.
    t_end : float, optional
        End time, s.
    max_events : int, optional
        Bound on the number of events (default: those of ``n_cycles`` cycles with a margin, or
        10**7 for a run to ``t_end`` alone).
    record_trajectory : bool, default True
        Keep the harmonic arcs, for :meth:`Solution.sample <escapement.Solution.sample>`.
    memory_budget : int, optional
        The most bytes the result may hold (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    Solution
        The run: ``status`` and ``message`` (how it ended), ``events``, ``cycles`` (the Poincare
        map: impact time in s, velocity before impact in m/s, period in s, amplitude in m),
        ``trajectory`` and ``t_final`` (s). Leaving the escapement regime is an outcome, not an error.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0`` or a limit is invalid (the message names it); a
        :class:`~escapement.model.limits.MemoryBudgetError` if the run would exceed ``memory_budget``.

    Examples
    --------
    The paper's Fig. 3 (a), released from rest at ``x0 = 1`` m:

    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=1.0, n_cycles=50)
    >>> run.status, len(run.cycles)
    (<Status.COMPLETED: 'completed'>, 50)
    >>> round(float(run.cycles.period[-1]), 4)  # s
    6.2957
    >>> x, v, a = run.sample([0.0, 1.0])  # m, m/s, m/s**2
    >>> round(float(x[1]), 6)
    0.540302

    A release too close to the centre never reaches an impact position:

    >>> solve_exact(p, x0=0.01, n_cycles=5).status
    <Status.STOPPED: 'stopped'>
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events, memory_budget=memory_budget)
    record_trajectory = bool(record_trajectory)
    contents = "its event log, cycle table and arcs" if record_trajectory else "its event log and cycle table"
    remedy = ("pass record_trajectory=False (the arcs take 40 %), " if record_trajectory else "") + _REMEDY
    check_memory(limits, EVENT_BYTES + (ARC_BYTES if record_trajectory else 0), CYCLE_BYTES, contents, remedy,
                 fixed_bytes=PASS_BYTES)
    run = ClosedFormRun(params, x, v, limits, keep_events=True)
    events, cycles = Packed(run.event_columns), Packed(run.cycle_columns)
    for _ in range(limits.max_events // SEGMENT + 2):  # each pass but the last runs SEGMENT events
        run.advance(SEGMENT)
        events.take()
        cycles.take()
        if run.outcome is not None:
            break
    else:
        raise RuntimeError(f"the closed-form loop did not end within max_events = {limits.max_events} events")
    t, v_before = events.numpy()
    log = _event_log(run, params, t, v_before)
    impact_time, velocity, period, amplitude = cycles.numpy()
    table = CycleTable(impact_time=impact_time, velocity_before_impact=velocity, period=period, amplitude=amplitude)
    t_final = float(run.outcome.t_final)
    trajectory = _arcs(run, params, log, t_final) if record_trajectory else None
    return finish(params, "exact", run.outcome, log, table, trajectory, x0=x, v0=v)


def _event_log(run: ClosedFormRun, params: Parameters, t: np.ndarray, v_before: np.ndarray) -> EventLog:
    """The event log from the times and velocities the loop stored: the kinds follow the automaton from
    the first, the positions are the surfaces', the velocities after are the impact law's at impacts."""
    kinds = run.kinds(len(t))
    positions = np.array([math.nan] + [automaton.position(k, params) for k in EventKind])
    impacts = np.array(automaton.IMPACT_TABLE)[kinds]
    v_after = v_before.copy()
    v_after[impacts] = automaton.velocity_after(v_before[impacts], run.b, True)
    return EventLog(t=t, kind=kinds, x=positions[kinds], v_before=v_before, v_after=v_after)


def _arcs(run: ClosedFormRun, params: Parameters, log: EventLog, t_final: float) -> ArcTable:
    """The arcs: the first from the initial state, then one from each event (with the centre of the mode it
    enters), the last only if the run ended inside it."""
    n = len(log) + run.open_arc
    centres = np.array([math.nan] + [automaton.centre(automaton.transition(k)[0], params.zone_offset)
                                     for k in EventKind])
    columns = []
    for first, rest in ((run.zero, log.t), (automaton.centre(Mode.FREE, params.zone_offset), centres[log.kind]),
                        (run.x0, log.x), (run.v0, log.v_after)):
        column = np.empty(n)
        if n:
            column[0] = first
            column[1:] = rest[:n - 1]
        columns.append(column)
    return ArcTable(*columns, params.omega, t_final)


def solve_exact_stepwise(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                         t_end: float | None = None, max_events: int | None = None, record_trajectory: bool = True,
                         memory_budget: int | None = None) -> Solution:
    """The run of :func:`solve_exact` through the generic solver loop
    (:func:`~escapement.solvers.driver.drive`), one :class:`ClosedFormStepper` call per event, with
    :func:`~escapement.model.kinematics.arc_maximum` on every arc: some four times slower, the same numbers.
    A second path to them, for checking the specialised loop."""
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events, memory_budget=memory_budget)
    return drive(params, x, v, limits, ClosedFormStepper(params, bool(record_trajectory)), x0=x, v0=v)
