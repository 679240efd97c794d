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

The cost. The loop is Python, so its cost is the interpreter's per operation: from each impact at a1
the four arcs of a cycle run unrolled (:meth:`ClosedFormRun._cycles`), their stage terms in local
variables, and only the operations the per-event loop needs on its common path. Both loops are put
together from one text of an arc's arithmetic (:data:`_CROSSING`, :data:`_TIME_SUM`) and compiled once
per kind of run (:func:`_compiled`). A cycle stores its four events with one call, packing their doubles
into a buffer (no Python float is kept; an event's time as the two terms of its compensated sum, added
on arrays); between passes the buffer's rows go into numpy columns allocated once for the run's most
events when ``n_cycles`` bounds them (:class:`_Columns`), which become the result without a second copy.
:mod:`escapement.studies.floor` measures the loop against a minimal loop that computes the cycle table
alone.

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

import linecache
import math
import struct
import textwrap
from array import array
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import arc_maximum, compensated_add, crossing, time_to_rest
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state
from ..model.quantities import MODEL_KEYS
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
#: events per pass of the loop, between which the stored rows move from the loop's buffers into the columns
SEGMENT = 1 << 12
#: bytes per event at the peak of :func:`solve_exact`: its time, position and velocities (8 bytes each) and
#: kind (1) in the result; for a run to an end time, whose length is not known in advance, its time and
#: velocity in buffers that grow by doubling, up to 16 more (a run of ``n_cycles`` allocates them once);
#: and at the end, the impacts at a1 picked out for the cycle table and the masks of the checks (up to 7)
EVENT_BYTES = 52
#: bytes per event of the arcs when the trajectory is kept: start time, centre, position, velocity
ARC_BYTES = 32
#: bytes per cycle: impact time, velocity, period and amplitude (8 bytes each), allocated once for a run of
#: ``n_cycles``, a fraction more for the growing buffers of a run to an end time
CYCLE_BYTES = 36
#: bytes of one pass of the loop, whatever the run's length: its buffer (ROW doubles an event) and the arrays
#: taken from it, or lists of Python floats (32 bytes each with its pointer: the four columns of the
#: SEGMENT / 4 cycles of iter_cycles), with a margin
PASS_BYTES = 32 * (2 * SEGMENT + SEGMENT)
#: the automaton's own impact law and test of a rebound, which the loop may apply in the form of a factor
_PAPER_LAW, _PAPER_REVERSES = automaton.velocity_after, automaton.reverses
#: the stage tables kept, with their plans (see :func:`stages`)
_STAGE_CACHE_SIZE = 256
_STAGE_CACHE: dict[bytes, tuple] = {}
_BITS = struct.Struct(f"{len(MODEL_KEYS)}d").pack  # the parameters' bits, the key of the cache
#: rows the growing columns of solve_exact start with when the run's length is not known in advance
_FIRST_ROWS = 1 << 16
# how a pass of the loop ends
_PAUSE, _NO_EVENT, _HORIZON, _COMPLETED, _CHATTERING = range(5)
_A1 = int(EventKind.IMPACT_A1)
_KINDS = tuple(EventKind)
_CODES = range(len(EventKind) + 1)  # the event kinds' codes (0: none)
_IS_A1 = [kind == _A1 for kind in _CODES]  # by event kind
_REMEDY = "raise memory_budget, or stream the cycles in constant memory with escapement.solvers.iter_cycles"


class ClosedFormStepper:
    """Each event in closed form; keeps the arcs for sampling when asked to (the generic loop's stepper)."""

    name = "exact"

    def __init__(self, params: Parameters, record_trajectory: bool) -> None:
        self.omega = params.omega
        # automaton.position(kind, params), without the conversion of kind it makes
        self.targets = {kind: (getattr(params, s.position), s.direction) for kind, s in automaton.SURFACES.items()}
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
    return _prepared(params)[0]


def _prepared(params: Parameters) -> tuple[tuple[Stage | None, ...], tuple | None, tuple | None]:
    """:func:`stages`, and kept with it its :func:`cycle_plan` where every factor is positive (the plan the
    unrolled cycles take with the paper's impact law) and that plan's shape, the key of its loop
    (:func:`_cycles_source`); the plan and shape None where there is none."""
    key = _BITS(*params.as_dict().values())
    prepared = _STAGE_CACHE.get(key)
    if prepared is None:
        if len(_STAGE_CACHE) >= _STAGE_CACHE_SIZE:
            _STAGE_CACHE.clear()
        table = _stages(params)
        plan = cycle_plan(table) if all(stage is None or stage.factor >= 0.0 for stage in table) else None
        shape = None if plan is None else tuple(tuple(getattr(stage, name) for stage in plan)
                                                for name in ("top", "start", "direction"))
        prepared = _STAGE_CACHE[key] = table, plan, shape
    return prepared


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


# --- the loops' source --------------------------------------------------------------------------------------------
# The arithmetic of an arc is written once, here, as text: the closed form of crossing() with the stage's surface
# terms (_CROSSING) and the compensated time sum (_TIME_SUM). ClosedFormRun's two loops, the per-event loop
# (_LOOP) and the unrolled cycles (_cycles_source), are put together from these pieces and compiled once per kind
# of run (_compiled): a Python function called per arc would cost more than the rest of the arc's bookkeeping.
# In a piece, {s} is the suffix of the stage's unpacked fields (c, u, q, k: Stage's centre, u0, q, k), {signed}
# the direction of arrival (d{s} * , or a sign where it is known) and {no_event} what to do where the arc
# reaches no surface. The loops' source is kept in linecache, so tracebacks, pdb and inspect show it.
_CROSSING = """\
# crossing(c{s}, x_from, v, omega, target, d{s}), its surface terms taken from the stage
v_sq = v * v + k{s}
if not v_sq > 0.0:
    {no_event}
v1 = {signed}sqrt(v_sq)
w0 = v / omega
w1 = v1 / omega
angle = atan2(w0 * q{s} - u{s} * w1, u{s} * q{s} + w0 * w1)
if angle <= 0.0:
    angle += TWO_PI
dt = angle / omega
"""
_TIME_SUM = """\
# compensated_add(t_sum, t_err, dt): t_sum >= 0 and dt > 0, so |t_sum| >= |dt| is t_sum >= dt
new = t_sum + dt
if t_sum >= dt:
    t_err += (t_sum - new) + dt
else:
    t_err += (dt - new) + t_sum
t_sum = new
elapsed += dt
"""
#: the event's time, from the compensated sum
_EVENT_TIME = "t = t_sum + t_err"
#: doubles per row of :attr:`ClosedFormRun.row_buffer`, one row per event: its time as the two terms of the
#: compensated sum, its velocity before, and at an impact at a1 that ends a cycle the cycle's period and
#: amplitude (0.0 elsewhere)
ROW = 5
_PACKERS: dict[int, object] = {}


def _packer(n: int):
    """``pack_into`` of ``n`` native doubles (the bits as they are), made once."""
    packer = _PACKERS.get(n)
    if packer is None:
        packer = _PACKERS[n] = struct.Struct(f"{n}d").pack_into
    return packer


def _sink(keep: bool) -> dict[str, str]:
    """How the loops store: with ``keep`` a row of :data:`ROW` doubles per event packed into
    :attr:`ClosedFormRun.row_buffer` at the offset ``eo`` (bytes), one call per cycle for its four events;
    else each cycle's numbers appended to the four lists of :attr:`~ClosedFormRun.cycle_columns`."""
    if keep:  # at an event that ends a cycle, elapsed and cycle_max are the cycle's
        return dict(bind="rows, eo, pack_row = self.row_buffer, self.row_offset, _packer(ROW)",
                    event="pack_row(rows, eo, t_sum, t_err, v1, elapsed, cycle_max); eo += 8 * ROW",
                    cycle="pass", save="self.row_offset = eo")
    return dict(bind="cy_t, cy_v, cy_p, cy_m = (column.append for column in self.cycle_columns)", event="pass",
                cycle="cy_t(pending_t); cy_v(pending_v); cy_p(elapsed); cy_m(cycle_max)", save="pass")


_LOOP = """\
def _loop(self, n, max_cycles):
    table = self.stages
    omega, b, zero, t_stop = self.params.omega, self.b, self.zero, self.t_stop
    sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
    law, reverses = automaton.velocity_after, automaton.reverses
    factors = self.factors
    hand_over = self.plan is not None  # stop at an impact at a1, where the unrolled cycles take over
    {bind}
    kind, v, t_sum, t_err, t = self.kind, self.v, self.t_sum, self.t_err, self.t
    elapsed, cycle_max, impacts, target_impacts = self.elapsed, self.cycle_max, self.impacts_a1, self.target_impacts
    pending_t, pending_v = self.pending
    done = count = 0
    ending = _PAUSE
    v1 = v_after = v
    for count in range(1, n + 1):
        nxt, x_from, target, d, c, u, q, k, grazing, floor, top, cap, start, impact, at_a1, factor = table[kind]
{crossing}
        if t + dt > t_stop:
            ending = _HORIZON
            break
        if w0 * start > 0.0 and angle < cap and w1 * w1 > grazing:
            m = c + hypot(u, w0) if top else floor
        else:
            m = arc_maximum(c, x_from, v, omega, angle, target)
        if m > cycle_max:  # max(cycle_max, m), NaN included
            cycle_max = m
{time_sum}
        t = t_sum + t_err
        {event}
        v_after = factor * v1 if factors else law(v1, b, impact)
        if at_a1:
            impacts += 1
            if impacts > 1:
                {cycle}
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
    {save}
    inside = ending == _NO_EVENT or ending == _HORIZON  # the pass ended inside an arc, without its event
    self.events += count - inside
    self.cycles += done
    self.v, self.t_sum, self.t_err, self.t, self.elapsed = v, t_sum, t_err, t, elapsed
    self.cycle_max, self.impacts_a1, self.pending = cycle_max, impacts, (pending_t, pending_v)
    self.kind = kind if inside or ending == _PAUSE else table[kind].next_kind
    self._pass_ended(ending, kind, v1, v_after)
"""


def _loop_source(keep: bool) -> str:
    """The source of :meth:`ClosedFormRun._loop`, storing as ``keep`` says (:func:`_sink`)."""
    indent = " " * 8
    crossing = _CROSSING.format(s="", signed="d * ", no_event="ending = _NO_EVENT; break")
    return _LOOP.format(crossing=textwrap.indent(crossing, indent),
                        time_sum=textwrap.indent(_TIME_SUM, indent), **_sink(keep))


def _cycles_source(tops: tuple[bool, ...], starts: tuple[float, ...], directions: tuple[float, ...], keep: bool,
                   timed: bool) -> str:
    """The source of :meth:`ClosedFormRun._cycles` for a plan whose arcs pass the top of their circle where
    ``tops`` says, start in the directions ``starts`` and arrive in the directions ``directions``
    (:attr:`Stage.top`, :attr:`Stage.start`, :attr:`Stage.direction`: the automaton's, whatever the
    parameters), storing as ``keep`` says (:func:`_sink`), with an end time or not (``timed``).

    Each arc is :data:`_CROSSING`, the checks of the common path, the amplitude and :data:`_TIME_SUM`, with
    these specialisations, each giving the per-event loop's numbers (and its decisions, or stricter ones):

    * the amplitude takes one closed form per cycle: an arc that does not pass the top ends at its ``floor``,
      a constant, so the largest ``x`` from the impact at a1 (``a1``) up to the first arc that passes it
      (``floor_i`` before arc ``i``) is computed once per call, and only the arcs from there on compare their
      maximum with the cycle's, in the order of the per-event loop (the same number, ties and ``-0.0``
      included);
    * the arrival away from a turning point, ``w1 * w1 > grazing``, asked with the stricter
      ``v_sq > s_i`` (:func:`_speed_bound`), which implies ``v_sq > 0.0`` too: an arc between the two bounds
      goes to the per-event loop, which takes it with the same arithmetic and decides as before;
    * the start direction ``s`` (+1.0 or -1.0) tested as the sign of ``w0``: ``w0 * s > 0.0`` is
      ``w0 > 0.0`` or ``w0 < 0.0``, NaN included; the direction of arrival ``d`` as a sign, ``d * sqrt()``
      being ``sqrt()`` or ``-sqrt()``;
    * without an end time (``t_stop`` infinite) ``t + dt > t_stop`` never holds, so it is not asked; and
      without events to store, an event's time ``t_sum + t_err`` is taken only at the impact at a1 and where
      the loop stops (the same sum of the same two numbers).
    """
    arcs = len(tops)
    first_top = tops.index(True) if True in tops else arcs
    fields = ", ".join(f"(_, _, _, _, c{i}, u{i}, q{i}, k{i}, g{i}, f{i}, _, cap{i}, _, _, _, r{i})"
                       for i in range(arcs))
    sink = _sink(keep)
    head = [
        "def _cycles(self, n):",
        f"    {fields} = self.plan",
        "    a1 = self.plan[-1].target",
        "    omega, zero, t_stop = self.params.omega, self.zero, self.t_stop",
        "    sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot",
        f"    {sink['bind']}",
        "    v, t_sum, t_err, t = self.v, self.t_sum, self.t_err, self.t",
        "    elapsed, cycle_max = self.elapsed, self.cycle_max",
        "    pending_t, pending_v = self.pending",
        "    floor0 = a1",
    ]
    head += [f"    floor{i + 1} = f{i} if f{i} > floor{i} else floor{i}" for i in range(first_top)]
    head.append("    " + ", ".join(f"s{i}" for i in range(arcs)) + " = "
                + ", ".join(f"_speed_bound(g{i}, omega)" for i in range(arcs)))
    if keep:  # each event's time (as its two sums) and velocity before it, stored at the end of the cycle
        head.append(f"    pack_cycle = _packer({ROW * arcs})")
        head.append("    " + " = ".join(f"p{i} = e{i} = y{i}" for i in range(arcs - 1)) + " = zero")
    head += ["    arc = cycle = 0", "    for cycle in range(n):"]
    body = []
    for i, top in enumerate(tops):
        body.append(f"# arc {i}, as in _loop on its common path; where it leaves that path, stop before it")
        signed = "" if directions[i] > 0 else "-"
        crossing = _CROSSING.format(s=i, signed=signed, no_event=f"arc = {i}; break")
        body += crossing.replace("if not v_sq > 0.0:", f"if not v_sq > s{i}:").splitlines()
        sign = "w0 > 0.0" if starts[i] > 0 else "w0 < 0.0"
        body += [f"if {'t + dt > t_stop or ' if timed else ''}not ({sign} and angle < cap{i}):",
                 f"    arc = {i}", "    break"]
        if i == first_top:
            body += [f"m = c{i} + hypot(u{i}, w0)", f"cycle_max = m if m > floor{i} else floor{i}"]
        elif i > first_top and top:
            body += [f"m = c{i} + hypot(u{i}, w0)", "if m > cycle_max:", "    cycle_max = m"]
        elif i > first_top:
            body += [f"if f{i} > cycle_max:", f"    cycle_max = f{i}"]
        body += _TIME_SUM.splitlines()
        if timed or (not keep and i == arcs - 1):  # for the end time; the cycle's impact time
            body.append(_EVENT_TIME)
        if keep and i < arcs - 1:  # the last is stored as it is
            body.append(f"p{i}, e{i}, y{i} = t_sum, t_err, v1")
        body.append(f"v = r{i} * v1")
    body.append("# the impact at a1 ends the cycle")
    if first_top == arcs:
        body.append(f"cycle_max = floor{arcs}")
    if keep:  # the cycle's events, the last with the cycle's period and amplitude
        events = ", ".join(f"p{i}, e{i}, y{i}, zero, zero" for i in range(arcs - 1))
        body.append(f"pack_cycle(rows, eo, {events}, t_sum, t_err, v1, elapsed, cycle_max)")
        body.append(f"eo += {8 * ROW * arcs}")
    else:
        body += sink["cycle"].split("; ")
        body.append("pending_t, pending_v = t, v1")
    body += ["cycle_max = a1", "elapsed = zero"]
    tail = ["    else:", "        cycle, arc = n, 0"]
    if first_top:  # stopped before the first arc over the top: the constant part of the amplitude so far
        floors = ", ".join(f"floor{i}" for i in range(1, first_top + 1))
        tail += [f"    if 0 < arc <= {first_top}:", f"        cycle_max = ({floors},)[arc - 1]"]
    if keep:  # the events of the cycle under way
        events = ", ".join(f"p{i}, e{i}, y{i}, zero, zero" for i in range(arcs - 1))
        tail += ["    if arc:", f"        _packer(ROW * arc)(rows, eo, *({events},)[:ROW * arc])",
                 "        eo += 8 * ROW * arc"]
    if not timed:
        tail.append(f"    {_EVENT_TIME}")
    tail += [
        f"    {sink['save']}",
        "    self.events += len(self.plan) * cycle + arc",
        "    self.cycles += cycle",
        "    self.impacts_a1 += cycle",
        "    self.kind = self.plan[arc - 1].next_kind  # the event before the arc it stopped at",
        "    self.v, self.t_sum, self.t_err, self.t, self.elapsed = v, t_sum, t_err, t, elapsed",
        "    self.cycle_max, self.pending = cycle_max, (pending_t, pending_v)",
        "    return cycle == n",
    ]
    return "\n".join([*head, *("        " + line for line in body), *tail, ""])


def _speed_bound(grazing: float, omega: float) -> float:
    """A bound on ``v_sq = v1**2`` above which ``w1 * w1 > grazing`` holds whatever the rounding, ``w1 = v1 /
    omega``: ``2 omega**2 max(grazing, 1e-290)`` (a margin of a factor 2 over a few ulps, and away from the
    subnormal numbers where ``w1 * w1`` loses its precision), or ``inf`` where that is not a normal float."""
    bound = 2.0 * (omega * omega) * max(grazing, 1e-290)
    return bound if 1e-300 < bound < math.inf else math.inf


_COMPILED: dict[tuple, object] = {}


def _compiled(name: str, *key):
    """The loop ``name`` (``"_loop"`` or ``"_cycles"``) for ``key`` (the arguments of its source function),
    compiled once, with this module's globals."""
    function = _COMPILED.get((name, *key))
    if function is None:
        source = _loop_source(*key) if name == "_loop" else _cycles_source(*key)
        filename = f"<escapement.solvers.exact: {name}{key!r}>"
        linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
        namespace: dict = {}
        exec(compile(source, filename, "exec"), globals(), namespace)  # noqa: S102 (the module's own source)
        function = _COMPILED[(name, *key)] = namespace[name]
        function.__qualname__ = f"ClosedFormRun.{name}"
    return function


class ClosedFormRun:
    """The exact solver's event loop, resumable: :meth:`advance` runs it for a bounded number of events
    and leaves its state (time sums, state, the cycle under way) for the next call, so that a run in
    several passes gives the numbers of a run in one.

    With ``keep_events`` each event stores its time (the two terms of its compensated sum) and velocity
    before it, and the impact at a1 that ends a cycle the cycle's period and amplitude, as a row of
    :data:`ROW` doubles packed into :attr:`row_buffer` (one call per cycle for its four events; no Python
    float is kept); :meth:`take` gives a pass's events and cycles as arrays and empties the buffer. A
    cycle's impact time and velocity are its first event's. Without, each complete cycle appends its impact
    time, velocity before the impact, period and amplitude to the four lists of :attr:`cycle_columns`
    (which :class:`Packed` takes); the caller empties them between passes. When the run ends,
    :attr:`outcome` is set.
    """

    def __init__(self, params: Parameters, x: float, v: float, limits: RunLimits, keep_events: bool) -> None:
        self.params = params
        self.limits = limits
        self.keep_events = keep_events = bool(keep_events)
        self.stepper = ClosedFormStepper(params, record_trajectory=False)
        self.stages, plan, shape = _prepared(params)
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
        # time and velocity of the impact at a1 that began the cycle (kept without keep_events)
        self.pending = (math.nan, math.nan)
        self.events = 0
        self.cycles = 0  # complete cycles
        self.first_kind: int | None = None
        self._kind_chain: tuple | None = None
        # the paper's impact law as factors, none negative: the loop need not call the law nor test for rebounds
        self.factors = (automaton.velocity_after is _PAPER_LAW and automaton.reverses is _PAPER_REVERSES
                        and all(stage is None or stage.factor >= 0.0 for stage in self.stages))
        self.plan = plan if self.factors else None  # cycle_plan(self.stages)
        self.open_arc = False  # the run ended inside an arc (no surface reached, or the end time)
        self.outcome: Outcome | None = None
        self.cycle_columns: tuple[list, list, list, list] = ([], [], [], [])
        self.row_buffer = bytearray()  # with keep_events: sized for a pass in advance()
        self.row_offset = 0  # the bytes it holds
        self.taken = 0  # the events before those in the buffer
        self._loop_function = _compiled("_loop", keep_events)
        self._cycles_function = None if self.plan is None else _compiled("_cycles", *shape, keep_events,
                                                                          limits.t_end is not None)

    def advance(self, max_events: int, max_cycles: float = math.inf) -> None:
        """Run at most ``max_events`` more events; stop earlier after ``max_cycles`` more complete
        cycles, or when the run ends (:attr:`outcome` set).

        From each impact at a1 the cycles run unrolled (:meth:`_cycles`) while they take the common
        path; the per-event loop (:meth:`_loop`) takes the first cycle, every arc the unrolled one leaves
        (an ending, an amplitude it does not take in its shortcut) up to the next impact at a1, and the
        whole run when there is no plan."""
        if self.outcome is not None:
            return
        if self.keep_events:
            self._reserve(min(max_events, self.limits.max_events - self.events))
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

    def _reserve(self, max_events: int) -> None:
        """Room in the buffer for ``max_events`` more events after what it holds (a new buffer: a view of the
        old one may be alive)."""
        used, size = self.row_offset, 8 * ROW * max_events
        if len(self.row_buffer) < used + size:
            grown = bytearray(used + size)
            grown[:used] = self.row_buffer[:used]
            self.row_buffer = grown

    def take(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The events and cycles stored since the last call, and empty the buffer: the events' times as the
        two terms of the compensated sum (the time is their sum, ``t_sum + t_err``) and velocities before them,
        and the cycles' periods and amplitudes, from the rows of the impacts at a1 that end them (every one but
        the run's first, which the kinds of the events tell: :meth:`by_kind`). Views of the buffer, valid until
        the next :meth:`advance`, but the cycles'."""
        rows = np.frombuffer(self.row_buffer, dtype=float, count=self.row_offset // 8).reshape(-1, ROW)
        start, self.taken, self.row_offset = self.taken, self.events, 0
        if len(rows) != self.taken - start:
            raise RuntimeError(f"the closed-form loop stored {len(rows)} rows for {self.taken - start} events")
        ends = np.zeros(len(rows), dtype=bool)  # the events that end a cycle
        if len(rows):
            chain = self._chain()[0]
            first = chain.index(_A1) if _A1 in chain else self.taken
            self.by_kind(_IS_A1, ends, start)
            ends[:max(first + 1 - start, 0)] = False  # the first impact at a1 begins the first cycle
        return rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3][ends], rows[:, 4][ends]

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
        if self.keep_events:  # it ends no cycle
            _packer(ROW)(self.row_buffer, self.row_offset, self.t_sum, self.t_err, v_before, 0.0, 0.0)
            self.row_offset += 8 * ROW
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
        """At most ``n`` events from the state after the last one (see the module's docstring); its source
        is :data:`_LOOP`, with the arc's arithmetic of :data:`_CROSSING` and :data:`_TIME_SUM`.

        The impact law is the automaton's :func:`~escapement.model.automaton.velocity_after`, called at
        each impact; while it is the paper's, ``(1 - b * impact) * v``, it is applied as the stage's
        ``factor`` (the same operations: the same number), and when no factor is negative (``b <= 1``)
        ``v_after * v_before = factor * v_before**2`` is never negative, so no impact can reverse the
        velocity and :func:`~escapement.model.automaton.reverses` need not be asked."""
        self._loop_function(self, n, max_cycles)

    def _pass_ended(self, ending: int, kind: int, v1: float, v_after: float) -> None:
        """How a pass of :meth:`_loop` ended, its state written back: an outcome where the run ends."""
        t, t_stop = self.t, self.t_stop
        if ending == _NO_EVENT:
            mode, awaited = automaton.transition(kind)
            stage = self.stages[kind]
            step = self.stepper.next_event(mode, stage.centre, t, stage.x_from, self.v,
                                           automaton.watched(mode, awaited), t_stop)
            if step[0] != NO_EVENT:
                raise RuntimeError(f"the closed-form loop and its stepper disagree at t = {t!r}: {step}")
            self._end(no_event_outcome(self.params, mode, awaited, stage.centre, t, step.dt, step.x_max), True)
        elif ending == _HORIZON:
            self._end(horizon_outcome(t_stop, self.impacts_a1), open_arc=True)
        elif ending == _COMPLETED:
            self._end(Outcome(Status.COMPLETED, f"completed {self.impacts_a1 - 1} cycles", Exit(), t))
        elif ending == _CHATTERING:
            self._end(chattering_outcome(self.params, EventKind(self.kind), t, v1, v_after))

    def _cycles(self, n: int) -> bool:
        """At most ``n`` cycles from an impact at a1, the four arcs of :attr:`plan` unrolled: the per-event
        loop's arithmetic on the common path only (an event is reached before the end time, the amplitude's
        shortcut holds, the impact law is the paper's with ``b < 1``). Where an arc leaves it, stop before
        that arc, the state that of the event before it; the per-event loop goes on from there. True if
        all ``n`` cycles ran. Its source is :func:`_cycles_source` for the plan."""
        return self._cycles_function(self, n)

    def _end(self, outcome: Outcome, open_arc: bool = False) -> None:
        self.outcome = outcome
        self.open_arc = open_arc

    def kinds(self, n: int) -> np.ndarray:
        """The kinds of the first ``n`` events: the first, then each the next of the one before (:func:`stages`)."""
        return self.by_kind(_CODES, np.empty(n, dtype=np.int8))

    def _chain(self) -> tuple[list[int], list[int], list[int]]:
        """The kinds from the first event until they repeat, the head before the repetition and its period
        (empty where they do not repeat)."""
        if self._kind_chain is None:
            chain = [self.first_kind]
            for _ in range(len(EventKind)):  # the kinds repeat within as many steps as there are kinds
                stage = self.stages[chain[-1]]
                if stage is None:
                    break
                chain.append(stage.next_kind)
            repeat = chain.index(chain[-1])  # chain[repeat:-1] is the period
            head, period = (chain, []) if repeat == len(chain) - 1 else (chain[:repeat], chain[repeat:-1])
            self._kind_chain = chain, head, period
        return self._kind_chain

    def by_kind(self, values, out: np.ndarray, start: int = 0) -> np.ndarray:
        """``out`` (contiguous), its entry ``i`` filled with ``values[k]``, ``k`` the kind of event ``start + i``:
        the kinds repeat after a head (:func:`stages`), so the values do (filled a period at a time)."""
        n = len(out)
        if n == 0:
            return out
        chain, head, period = self._chain()
        if start + n > len(head) and not period:
            raise RuntimeError(f"the event kinds after {chain} do not repeat")
        done = max(min(len(head) - start, n), 0)
        if n - done <= 2 * len(period):  # a few: one by one
            out[:] = [values[k] for k in head[start:start + done]] + [
                values[period[(i - len(head)) % len(period)]] for i in range(start + done, start + n)]
            return out
        if done:
            out[:done] = [values[k] for k in head[start:start + done]]
        if done < n:
            phase = (start + done - len(head)) % len(period)
            cycle = [values[k] for k in period[phase:] + period[:phase]]
            full, part = divmod(n - done, len(cycle))
            if full:
                out[done:done + full * len(cycle)].reshape(full, len(cycle))[:] = cycle
            if part:
                out[n - part:] = cycle[:part]
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


class _Columns:
    """Float columns filled between passes from a run's arrays (:meth:`ClosedFormRun.take`): the rows of one
    numpy block (one allocation; from 4 MB NumPy asks the kernel for huge pages), allocated once for the most
    entries the run can take when that is known (``known``), else grown (doubling, up to that bound).
    :meth:`numpy` gives views of the filled part, no second copy, unless less than 7/8 of the block was
    filled (a run that ended early): then a copy of it."""

    def __init__(self, width: int, most: int, known: bool) -> None:
        self.most = most
        self.block = np.empty((width, most if known else min(most, _FIRST_ROWS)))
        self.rows = 0  # entries filled

    def extend(self, n: int, at: int | None = None) -> np.ndarray:
        """Views of ``n`` entries of every column after those filled (or from ``at``), to be filled."""
        start = self.rows if at is None else at
        end = start + n
        if end > self.block.shape[1]:
            grown = np.empty((len(self.block), max(end, min(2 * self.block.shape[1], self.most))))
            grown[:, :self.rows] = self.block[:, :self.rows]
            self.block = grown
        self.rows = max(self.rows, end)
        return self.block[:, start:end]

    def take(self, first: int, *columns: np.ndarray, at: int | None = None) -> None:
        """``columns`` into the block's rows from ``first`` on, after the entries filled (or from ``at``)."""
        self.extend(len(columns[0]), at)[first:first + len(columns)] = columns

    def numpy(self) -> tuple[np.ndarray, ...]:
        """The columns (once: a copy lets the block go)."""
        rows, block = self.rows, self.block
        if 8 * rows < 7 * block.shape[1]:
            self.block = None
            return tuple(np.array(column[:rows]) for column in block)
        return tuple(block[:, :rows])


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
    known = limits.n_cycles is not None  # the most events and cycles are those of n_cycles: allocated once
    # the events' times and velocities before them; the cycles' impact times and velocities (filled at the end),
    # periods and amplitudes
    events, cycles = _Columns(2, limits.stored_events, known), _Columns(4, limits.stored_cycles, known)
    for _ in range(limits.max_events // SEGMENT + 2):  # each pass but the last runs SEGMENT events
        run.advance(SEGMENT)
        t_sum, t_err, v_before, period, amplitude = run.take()
        t_column, v_column = events.extend(len(v_before))
        np.add(t_sum, t_err, out=t_column)  # the loop's t = t_sum + t_err, on arrays
        v_column[:] = v_before
        cycles.take(2, period, amplitude)
        if run.outcome is not None:
            break
    else:
        raise RuntimeError(f"the closed-form loop did not end within max_events = {limits.max_events} events")
    t, v_before = events.numpy()
    log = _event_log(run, params, t, v_before)
    impacts_a1 = np.flatnonzero(log.kind == _A1)[:cycles.rows]  # each cycle's first event
    cycles.take(0, t[impacts_a1], v_before[impacts_a1], at=0)
    impact_time, velocity, period, amplitude = cycles.numpy()
    table = CycleTable(impact_time=impact_time, velocity_before_impact=velocity, period=period, amplitude=amplitude)
    t_final = float(run.outcome.t_final)
    trajectory = _arcs(run, params, log, t_final) if record_trajectory else None
    return finish(params, "exact", run.outcome, log, table, trajectory, x0=x, v0=v)


def _by_kind(run: ClosedFormRun, field: str, default) -> list[float]:
    """A table by event kind (its code; NaN at 0, which is no kind) of the stages' ``field`` (:func:`stages`:
    the position of the event, the centre of the mode it enters), ``default(kind)`` where there is no stage."""
    return [math.nan, *(default(kind) if stage is None else getattr(stage, field)
                        for kind, stage in zip(_KINDS, run.stages[1:]))]


def _event_log(run: ClosedFormRun, params: Parameters, t: np.ndarray, v_before: np.ndarray) -> EventLog:
    """The event log from the times and velocities the loop stored: the kinds follow the automaton from
    the first, the positions are the surfaces', the velocities after are the impact law's at impacts
    (while it is the paper's, as a factor by kind: ``1.0 - b`` at impacts, ``1.0`` elsewhere, which keeps
    ``v`` as it is: the loop's numbers)."""
    n = len(t)
    kinds = run.kinds(n)
    x, v_after = np.empty((2, n))  # one block
    run.by_kind(_by_kind(run, "x_from", lambda kind: automaton.position(kind, params)), x)
    if run.factors:
        run.by_kind([1.0 - run.b * impact for impact in automaton.IMPACT_TABLE], v_after)
        v_after *= v_before
    else:
        impacts = np.array(automaton.IMPACT_TABLE)[kinds]
        v_after[:] = v_before
        v_after[impacts] = automaton.velocity_after(v_before[impacts], run.b, True)
    return EventLog(t=t, kind=kinds, x=x, v_before=v_before, v_after=v_after)


def _arcs(run: ClosedFormRun, params: Parameters, log: EventLog, t_final: float) -> ArcTable:
    """The arcs: the first from the initial state, then one from each event (with the centre of the mode it
    enters), the last only if the run ended inside it."""
    n = len(log) + run.open_arc
    t_start, centre, x_start, v_start = columns = np.empty((4, n))  # one block
    if n:
        t_start[0], t_start[1:] = run.zero, log.t[:n - 1]
        centre[0] = automaton.centre(Mode.FREE, params.zone_offset)
        centres = _by_kind(run, "centre",
                           lambda kind: automaton.centre(automaton.transition(kind)[0], params.zone_offset))
        run.by_kind(centres, centre[1:])
        x_start[0], x_start[1:] = run.x0, log.x[:n - 1]
        v_start[0], v_start[1:] = run.v0, log.v_after[:n - 1]
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
