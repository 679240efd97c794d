"""The integrators' loop: drives the automaton from event to event with a pluggable integrator.

The reference, high-precision and naive solvers integrate the equations of motion numerically and
check the exact solver (:mod:`escapement.solvers.kernel`) against an independent path. An integrator (a
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
``trajectory_bytes_per_event`` and, whatever the run's length, in ``fixed_bytes`` (a stepper without them
is taken to store none).

Before any work the loop estimates the bytes the run's result will hold (:func:`check_memory`) and
refuses a run whose estimate exceeds :attr:`~escapement.model.limits.RunLimits.memory_budget`.
How a run ends (an :class:`~escapement.solvers.outcomes.Outcome`) is decided by the functions of
:mod:`escapement.solvers.outcomes`, which the exact solver's loop shares.
"""

from __future__ import annotations

import math
from array import array
from typing import NamedTuple, Protocol

import mpmath
import numpy as np

from ..model import automaton
from ..model.automaton import RELEASE, Mode
from ..model.events import EventKind, EventLog
from ..model.kinematics import compensated_add
from ..model.limits import RunLimits
from ..model.parameters import Parameters
from ..model.status import Status
from ..solvers.outcomes import (
    Outcome,
    chattering_outcome,
    check_memory,
    completed_outcome,
    event_limit_message,
    finish,
    horizon_outcome,
    no_event_outcome,
)
from ..solvers.result import CycleTable, Exit, Solution, Trajectory

__all__ = ["HORIZON", "NO_EVENT", "Step", "Stepper", "drive"]

NO_EVENT = 0
HORIZON = -1
_A1 = int(EventKind.IMPACT_A1)
#: bytes per event of the loop's event log at its peak: t, x, v_before, v_after (8 bytes each) and kind (1)
#: in growing buffers, and at the end the arrays and masks that pick the cycles' impacts (measured: 48-58
#: bytes an event with the naive stepper, with the cycles' 40)
_FLOAT_EVENT_BYTES = 64
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
    ``trajectory_bytes_per_event``, the bytes its trajectory keeps per event, and ``fixed_bytes``."""

    name: str

    def next_event(self, mode: Mode, centre: float, t: float, x: float, v: float,
                   watched: tuple[EventKind, ...], t_stop: float) -> Step:
        """The next event of ``watched`` on the arc about ``centre`` in ``mode`` from ``(t, x, v)``, or none
        before ``t_stop``."""

    def trajectory(self, t_final: float) -> Trajectory | None:
        """The motion up to ``t_final``, if the integrator keeps it."""


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
                 "escapement.solvers.iter_cycles", fixed_bytes=getattr(stepper, "fixed_bytes", 0))
    target_impacts = None if limits.n_cycles is None else limits.n_cycles + 1
    t_stop = math.inf if limits.t_end is None else limits.t_end
    zero = x * 0  # 0 in the arithmetic of the run (float or mpmath)
    b = zero + params.b
    positions = {kind: automaton.position(kind, params) for kind in EventKind}
    # the automaton's rows, by state: the mode, its centre and the surfaces watched
    arcs = {state: (arc.mode, automaton.centre(arc.mode, params.zone_offset), arc.watched)
            for state, arc in automaton.ARCS.items()}

    ev = _Records(floats, ("t", "x", "v_before", "v_after"))
    kinds = array("b")
    cyc = _Records(floats, ("maxima", "periods"))
    cycle_max = -math.inf
    impacts_a1 = 0
    t_sum = t_err = t = zero
    elapsed = zero  # time since the last impact at a1, summed inside the cycle for an exact period
    state = RELEASE
    outcome = None
    t_final = t

    for _ in range(limits.max_events):
        mode, c, watched = arcs[state]
        step = stepper.next_event(mode, c, t, x, v, watched, t_stop)
        kind = step[0]
        if kind == NO_EVENT:
            outcome = no_event_outcome(params, state, c, t, step.dt, step.x_max, t_stop, impacts_a1)
            break
        _, dt, v_before, x_max, t_abs, x_at = step
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
                outcome = completed_outcome(impacts_a1 - 1, t)
                break
        if automaton.reverses(v_before, v_after):
            outcome = chattering_outcome(params, kind, t, v_before, v_after)
            break
        state = int(kind)
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


def _cycle_table(events: EventLog, maxima: np.ndarray, periods: np.ndarray) -> CycleTable:
    """Complete cycles only: an impact at a1 that starts an unfinished cycle is dropped."""
    impacts = events.of_kind(EventKind.IMPACT_A1)
    n = len(periods)
    return CycleTable(
        impact_time=events.t[impacts][:n],
        velocity_before_impact=events.v_before[impacts][:n],
        period=periods,
        largest_displacement=maxima,
    )
