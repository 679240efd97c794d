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

A stepper that keeps a trajectory says how many bytes it stores per event in an attribute
``trajectory_bytes_per_event`` (a stepper without it is taken to store none).

Before any work the loop estimates the bytes the run's result will hold (:func:`check_memory`) and
refuses a run whose estimate exceeds :attr:`~escapement.model.limits.RunLimits.memory_budget`.
How a run ends (an :class:`Outcome`) is decided by :func:`no_event_outcome`,
:func:`horizon_outcome` and :func:`chattering_outcome`, which the exact solver's own loop
(:mod:`escapement.solvers.exact`) shares.
"""

from __future__ import annotations

import math
from array import array
from typing import NamedTuple, Protocol

import mpmath
import numpy as np

from ..model import automaton
from ..model.automaton import Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import compensated_add, rebound_accumulation_time
from ..model.limits import EVENTS_PER_CYCLE, MemoryBudgetError, RunLimits, events_for
from ..model.parameters import Parameters
from ..model.status import (
    Status,
    chattering_message,
    event_limit_message,
    stopped_message,
    turned_back_message,
)
from .result import ArcTable, CycleTable, Exit, Solution

__all__ = [
    "HORIZON",
    "NO_EVENT",
    "Outcome",
    "Step",
    "Stepper",
    "chattering_outcome",
    "check_memory",
    "drive",
    "horizon_outcome",
    "no_event_outcome",
]

NO_EVENT = 0
HORIZON = -1
_A1 = int(EventKind.IMPACT_A1)
#: bytes per event of the loop's event log at its peak: t, x, v_before, v_after (8 bytes each) and kind (1)
#: in growing buffers (up to 1/16 over-allocated), and at the end the masks that pick the cycles' impacts
_FLOAT_EVENT_BYTES = 40
#: bytes per cycle: its largest x and its period while running, its impact time and velocity at the end
_FLOAT_CYCLE_BYTES = 40
#: an mpmath number in a list: the pointer, the mpf object, its (sign, mantissa, exponent, bits) tuple and
#: integers, and the object array it ends in; the high-precision solver's peak, per stored number, measured
#: 197 bytes at 60 digits (199 bits), 263 at 210 and 518 at 1010 (3357 bits)
_MPF_BYTES_BASE = 200
_MPF_BYTES_PER_BIT = 0.12


class Step(NamedTuple):
    """What a stepper returns (a plain tuple of these six fields is accepted too)."""

    kind: int
    dt: float
    v: float
    x_max: float
    t_abs: float | None = None
    x_at: float | None = None  #: where the integrator applies the event (None: on the surface)


class Stepper(Protocol):
    """An integrator for the loop (see the module's docstring); it may also have an attribute
    ``trajectory_bytes_per_event``, the bytes its trajectory keeps per event."""

    name: str

    def next_event(self, mode: Mode, centre: float, t: float, x: float, v: float,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step: ...

    def trajectory(self, t_final: float): ...


class Outcome(NamedTuple):
    """How a run ended: its status and message, the numbers behind a regime exit, and the end of its
    trajectory."""

    status: Status
    message: str
    exit: Exit
    t_final: object  #: a float, or an mpmath number for the high-precision solver


def no_event_outcome(params: Parameters, mode: Mode, awaited: automaton.Awaited, centre, t, dt, turning) -> Outcome:
    """No watched surface is ever passed from time ``t`` in ``mode``: in free flight the escapement
    stopped (``turning`` is the radius of the swing), in a zone the mass turned back at ``turning``,
    ``dt`` after ``t``."""
    status = automaton.EXIT_WITHOUT_EVENT[mode]
    if status is Status.STOPPED:
        watched = automaton.watched(mode, awaited)
        missed = {name: automaton.position(k, params) for name, k in (("a1", EventKind.IMPACT_A1),
                                                                       ("a3", EventKind.IMPACT_A3)) if k in watched}
        message = stopped_message(float(t), float(turning), {k: float(m) for k, m in missed.items()})
        exit_ = Exit(turning_point=float(turning), margin=float(min(abs(m) for m in missed.values()) - turning))
        return Outcome(status, message, exit_, math.inf)
    zone, end_kind = automaton.ZONE_OF[mode]
    end = automaton.position(end_kind, params)
    t_final = t + dt
    message = turned_back_message(float(t_final), zone, float(turning), float(centre), float(end))
    return Outcome(status, message, Exit(turning_point=float(turning), margin=float(abs(end - turning))), t_final)


def horizon_outcome(t_stop: float, impacts_a1: int) -> Outcome:
    """The end time comes before the next event."""
    return Outcome(Status.COMPLETED, f"reached t_end = {t_stop:.12g} s after {impacts_a1} impacts at a1", Exit(),
                   t_stop)


def chattering_outcome(params: Parameters, kind: EventKind, t, v_before, v_after) -> Outcome:
    """The impact ``kind`` at time ``t`` reversed the velocity: the rebounds accumulate (or not)."""
    distance = automaton.rebound_distance(kind, automaton.position(kind, params))
    t_acc = math.nan  # unless the spring drives the mass back to the impact position
    ratio = float(v_after / v_before)  # the impact law's v+/v-, negative: a rebound
    if distance > 0.0:
        t_acc = float(t) + rebound_accumulation_time(params.omega, distance, abs(float(v_after)), abs(ratio))
    position = automaton.SURFACES[EventKind(kind)].position
    message = chattering_message(float(t), position, params.b, ratio, t_acc)
    return Outcome(Status.CHATTERING, message, Exit(t_accumulation=t_acc), t)


def check_memory(limits: RunLimits, event_bytes: float, cycle_bytes: float, contents: str, remedy: str,
                 fixed_bytes: int = 0) -> int:
    """The bytes a run's result will hold at most, from its limits: ``event_bytes`` for each of its
    :attr:`~RunLimits.stored_events` events, ``cycle_bytes`` for each of its
    :attr:`~RunLimits.stored_cycles` cycles, and ``fixed_bytes`` whatever their number. Raise
    :class:`MemoryBudgetError` when that exceeds ``limits.memory_budget``, naming the count that sets the
    size (``n_cycles``, or ``max_events`` when it binds) with its largest value within the budget, what the
    run stores (``contents``) and what to do instead (``remedy``)."""
    budget = limits.memory_budget

    def size(n_events: int, n_cycles: int) -> int:
        return int(math.ceil(n_events * event_bytes + n_cycles * cycle_bytes)) + fixed_bytes

    estimate = size(limits.stored_events, limits.stored_cycles)
    if estimate <= budget:
        return estimate
    if limits.n_cycles is not None and events_for(limits.n_cycles) <= limits.max_events:
        name, value = "n_cycles", limits.n_cycles

        def fits(n: int) -> bool:
            return size(events_for(n), n) <= budget

        # events_for(n) = 4 n + 16 events and n cycles: the largest n that fits, to within rounding
        per_cycle = events_for(1) - events_for(0)
        most = int((budget - fixed_bytes - events_for(0) * event_bytes) // (per_cycle * event_bytes + cycle_bytes))
    else:
        name, value = "max_events", limits.max_events

        def fits(n: int) -> bool:
            return size(n, n // EVENTS_PER_CYCLE) <= budget

        most = int((budget - fixed_bytes) // (event_bytes + cycle_bytes / EVENTS_PER_CYCLE))
    for _ in range(2):  # the division above is within one of the answer
        most = most + 1 if fits(most + 1) else most - 1 if most > 0 and not fits(most) else most
    requirement = (
        f"at most {max(most, 0):_} for this run to fit its memory budget: it would store {contents}, an estimated "
        f"{estimate:_} bytes ({estimate / 1e9:.3g} GB), over the budget of {budget:_} bytes ({budget / 1e9:.3g} GB); "
        f"{remedy}"
    )
    raise MemoryBudgetError(name, value, requirement, estimate, budget)


class _Records:
    """Growing columns: ``array('d')`` for floats (8 bytes a value), lists for mpmath numbers."""

    def __init__(self, floats: bool, names: tuple[str, ...]) -> None:
        self.floats = floats
        self.columns = {name: (array("d") if floats else []) for name in names}

    def __getitem__(self, name):
        return self.columns[name]

    def numpy(self, name: str) -> np.ndarray:
        """The column as an array; for floats a view of the buffer (no second copy), which keeps it alive."""
        column = self.columns[name]
        if self.floats:
            return np.frombuffer(column, dtype=float) if len(column) else np.zeros(0)
        return np.array(column, dtype=object)


def _value_bytes(floats: bool) -> float:
    """Bytes a stored number takes: 8 for a float, for an mpmath number at the working precision more."""
    if floats:
        return 8.0
    return _MPF_BYTES_BASE + _MPF_BYTES_PER_BIT * mpmath.mp.prec


def drive(params: Parameters, x: float, v: float, limits: RunLimits, stepper: Stepper, *,
          x0: float, v0: float, floats: bool = True) -> Solution:
    """Run the automaton from ``(x, v)`` at ``t = 0`` until ``limits`` or a regime exit.

    Before any work, the result's size is estimated from ``limits`` and refused above
    ``limits.memory_budget`` (:func:`check_memory`). A run that ends ``completed`` holds only finite
    numbers; one that does not raises :class:`FloatingPointError` (the input validation let through
    what it must refuse)."""
    value = _value_bytes(floats)
    event_bytes = (_FLOAT_EVENT_BYTES if floats else 4 * value + 1) + getattr(stepper, "trajectory_bytes_per_event", 0)
    cycle_bytes = _FLOAT_CYCLE_BYTES if floats else 4 * value
    check_memory(limits, event_bytes, cycle_bytes, f"the event log and the cycle table of {stepper.name}",
                 "raise memory_budget, or run the exact solver's cycles in constant memory with "
                 "escapement.solvers.iter_cycles")
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
    outcome = None
    t_final = t

    for _ in range(limits.max_events):
        c = centres[mode]
        step = stepper.next_event(mode, c, t, x, v, watching[(mode, awaited)], t_stop)
        kind = step[0]
        if kind == NO_EVENT:
            outcome = no_event_outcome(params, mode, awaited, c, t, step.dt, step.x_max)
            break
        _, dt, v_before, x_max, t_abs, x_at = step
        if kind == HORIZON or t + dt > t_stop:
            outcome = horizon_outcome(t_stop, impacts_a1)
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
                outcome = Outcome(Status.COMPLETED, f"completed {impacts_a1 - 1} cycles", Exit(), t)
                break
        if automaton.reverses(v_before, v_after):
            outcome = chattering_outcome(params, kind, t, v_before, v_after)
            break
        mode, awaited = after[kind]
        v = v_after
    else:
        outcome = Outcome(Status.EVENT_LIMIT, event_limit_message(float(t), limits.max_events), Exit(), t_final)

    events = EventLog(
        t=ev.numpy("t"),
        kind=np.frombuffer(kinds, dtype=np.int8) if len(kinds) else np.zeros(0, dtype=np.int8),
        x=ev.numpy("x"),
        v_before=ev.numpy("v_before"),
        v_after=ev.numpy("v_after"),
    )
    cycles = _cycle_table(events, cyc.numpy("maxima"), cyc.numpy("periods"))
    return finish(params, stepper.name, outcome, events, cycles, stepper.trajectory(float(outcome.t_final)),
                  x0=x0, v0=v0)


def finish(params: Parameters, method: str, outcome: Outcome, events: EventLog, cycles: CycleTable, trajectory, *,
           x0: float, v0: float) -> Solution:
    """The :class:`Solution` of a run that ended with ``outcome``; a completed run holding a non-finite
    number raises (:func:`_check_finite`)."""
    t_final = float(outcome.t_final)
    if outcome.status is Status.COMPLETED:
        _check_finite(method, events, cycles, trajectory, t_final)
    return Solution(
        params=params,
        x0=float(x0),
        v0=float(v0),
        method=method,
        status=outcome.status,
        message=outcome.message,
        events=events,
        cycles=cycles,
        trajectory=trajectory,
        t_final=t_final,
        exit=outcome.exit,
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
