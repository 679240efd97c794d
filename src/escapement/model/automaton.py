"""The escapement as a hybrid automaton, written once as data that every solver drives: the state is the kind of
the last event (:data:`RELEASE` before the first), its row of :data:`ARCS` the arc that follows and the surfaces
that can end it; the event reached is the next state.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING

from .arguments import Numeric
from .events import EventKind
from .status import Status

if TYPE_CHECKING:
    from .parameters import Parameters

__all__ = ["ARCS", "CENTRE_SIGN", "CHOICES", "EXIT_WITHOUT_EVENT", "RELEASE", "SURFACES", "ZONE_OF", "Arc", "Mode",
           "Surface", "centre", "cycle_plan", "is_impact", "opening", "position", "rebound_distance", "reverses",
           "impact_factor", "velocity_after"]


class Mode(IntEnum):
    """Which equation of motion holds: ``x'' = -omega**2 (x - c)`` with the centre ``c`` of :data:`CENTRE_SIGN`."""

    FREE = 0  #: free flight (steps 1, 4, 5, 8 of the paper), centre 0
    ZONE_RIGHT = 1  #: the impulse zone (a1, a2) after the impact at a1 (step 3), centre +F/K
    ZONE_LEFT = 2  #: the impulse zone (a4, a3) after the impact at a3 (step 7), centre -F/K


CENTRE_SIGN = (0.0, 1.0, -1.0)  #: the centre of oscillation of each mode, in units of F/K


@dataclass(frozen=True)
class Surface:
    """An event: ``x`` reaching the parameter ``position`` while moving in ``direction``."""

    kind: EventKind
    position: str  #: the parameter that gives the position (a1 .. a4)
    direction: int  #: +1 moving right, -1 moving left
    impact: bool  #: an impact (the impact law applies), or the end of an impulse zone


SURFACES: dict[EventKind, Surface] = {s.kind: s for s in (
    Surface(EventKind.IMPACT_A1, "a1", +1, True), Surface(EventKind.ZONE_END_A2, "a2", +1, False),
    Surface(EventKind.IMPACT_A3, "a3", -1, True), Surface(EventKind.ZONE_END_A4, "a4", -1, False))}


@dataclass(frozen=True)
class Arc:
    """A row of the automaton: the arc that follows an event, its mode and the surfaces that can end it."""

    mode: Mode
    watched: tuple[EventKind, ...]


RELEASE = 0  #: the state before the first event
#: the arc after each state: the impulse follows an impact only; from the release, whichever impact comes first
ARCS: dict[int, Arc] = {
    RELEASE: Arc(Mode.FREE, (EventKind.IMPACT_A1, EventKind.IMPACT_A3)),
    EventKind.IMPACT_A1: Arc(Mode.ZONE_RIGHT, (EventKind.ZONE_END_A2,)),
    EventKind.ZONE_END_A2: Arc(Mode.FREE, (EventKind.IMPACT_A3,)),
    EventKind.IMPACT_A3: Arc(Mode.ZONE_LEFT, (EventKind.ZONE_END_A4,)),
    EventKind.ZONE_END_A4: Arc(Mode.FREE, (EventKind.IMPACT_A1,)),
}

#: the model's choices where the paper is silent, the default first (Parameters says what each means)
CHOICES = {"release_force": ("after_impact", "eq5"), "past_accumulation": ("stop", "continue")}

#: how a run ends where no watched surface is ever passed in a mode
EXIT_WITHOUT_EVENT = {Mode.FREE: Status.STOPPED, Mode.ZONE_RIGHT: Status.TURNED_BACK_IN_ZONE,
                      Mode.ZONE_LEFT: Status.TURNED_BACK_IN_ZONE}

#: each impulse zone by its mode: its name in messages and the surface that ends it
ZONE_OF = {Mode.ZONE_RIGHT: ("(a1, a2)", EventKind.ZONE_END_A2), Mode.ZONE_LEFT: ("(a4, a3)", EventKind.ZONE_END_A4)}


def cycle_plan() -> tuple[EventKind, ...]:
    """The events of one cycle, after an impact at a1 up to the next, by the rows of :data:`ARCS`."""
    plan, state = [], EventKind.IMPACT_A1
    for _ in range(len(SURFACES)):
        (state,) = ARCS[state].watched
        plan.append(state)
        if state == EventKind.IMPACT_A1:
            return tuple(plan)
    raise RuntimeError("the automaton's rows do not return to the impact at a1")


def opening(params: Parameters, x0: float, v0: float) -> int:
    """The state a run starts in: :data:`RELEASE`, or under ``release_force: eq5`` the impact that opens its zone."""
    moving = v0 if v0 != 0.0 else -x0
    for kind in (EventKind.IMPACT_A1, EventKind.IMPACT_A3) if params.release_force == "eq5" else ():
        ends = sorted((position(kind, params), position(ZONE_OF[ARCS[kind].mode][1], params)))
        if ends[0] < x0 < ends[1] and moving * SURFACES[kind].direction > 0:
            return kind
    return RELEASE


def centre(mode: int, zone_offset: Numeric) -> Numeric:
    """The centre of oscillation in ``mode``; ``zone_offset`` is F/K (a number or an array), m."""
    return CENTRE_SIGN[int(mode)] * zone_offset


def position(kind: int, params: Parameters) -> float:
    """Where the surface ``kind`` lies for these parameters, m."""
    return getattr(params, SURFACES[kind].position)


def is_impact(kind: int) -> bool:
    """True for the impacts at a1 and a3, False for the ends of the impulse zones."""
    return SURFACES[kind].impact


def impact_factor(b: Numeric) -> Numeric:
    """The impact law, Eqs. (A-2), (A-4): ``v+ = r v-`` with ``r = 1 - b`` (floats, arrays, mpmath numbers)."""
    return 1.0 - b


def velocity_after(v_before: Numeric, b: Numeric) -> Numeric:
    """The velocity just after an impact: :func:`impact_factor` times the velocity just before it."""
    return impact_factor(b) * v_before


def reverses(v_before: Numeric, v_after: Numeric) -> Numeric:
    """True where the jump reversed the velocity (``b > 1``): the mass rebounds and chatters."""
    return v_after * v_before < 0.0


def rebound_distance(kind: int, where: Numeric) -> Numeric:
    """After a rebound at the impact ``kind`` at ``where``, its distance from 0 (> 0: the spring drives it back)."""
    return -SURFACES[kind].direction * where
