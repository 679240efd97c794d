"""The escapement as a hybrid automaton: its modes, surfaces, transitions, impact law and exits.

This module is the model's rules, written once; every solver (exact, ensemble, reference,
high precision, naive) drives it and none restates it. The rules are tables indexed by small
integers and functions of plain arithmetic, so that they serve floats, NumPy arrays and
mpmath numbers alike.

Modes (Sec. 2 and Appendix A of the paper):

* :attr:`Mode.FREE`: ``x'' = -omega**2 x`` (steps 1, 4, 5, 8); centre 0.
* :attr:`Mode.ZONE_RIGHT`: entered by the impact at a1; ``x'' = -omega**2 x + f`` (step 3);
  centre ``+F/K``; left at a2 moving right.
* :attr:`Mode.ZONE_LEFT`: entered by the impact at a3; ``x'' = -omega**2 x - f`` (step 7);
  centre ``-F/K``; left at a4 moving left.

In free flight the escapement awaits one impact (:class:`Awaited`): at a3 moving left after
the impulse (a1, a2), at a1 moving right after the impulse (a4, a3), and at first whichever
of the two comes first. The impulse follows an impact only (the escapement unlocks at the
impact). The impact law is Eqs. (A-2), (A-4): ``v+ = (1 - b) v-``.

A run leaves the regime (:class:`~escapement.model.status.Status`) when no watched surface is
ever passed (free flight: the escapement stopped; a zone: the mass turned back inside it), or
when an impact reverses the velocity (``b > 1``: the impacts chatter).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from .events import EventKind
from .status import Status

__all__ = [
    "Mode",
    "Awaited",
    "Surface",
    "SURFACES",
    "CENTRE_SIGN",
    "ZONE_OF",
    "EXIT_WITHOUT_EVENT",
    "watched",
    "transition",
    "centre",
    "position",
    "is_impact",
    "velocity_after",
    "reverses",
    "rebound_distance",
]


class Mode(IntEnum):
    """Which equation of motion holds (the integers index the tables below)."""

    FREE = 0
    ZONE_RIGHT = 1
    ZONE_LEFT = 2


class Awaited(IntEnum):
    """The impact the escapement waits for in free flight (the codes of the impact events)."""

    EITHER = 0
    A1 = int(EventKind.IMPACT_A1)
    A3 = int(EventKind.IMPACT_A3)


@dataclass(frozen=True)
class Surface:
    """An event surface: ``x`` reaching the parameter ``position`` while moving in ``direction``."""

    kind: EventKind
    position: str  #: name of the parameter that gives the position (a1 .. a4)
    direction: int  #: +1 moving right, -1 moving left


SURFACES: dict[EventKind, Surface] = {
    EventKind.IMPACT_A1: Surface(EventKind.IMPACT_A1, "a1", +1),
    EventKind.ZONE_END_A2: Surface(EventKind.ZONE_END_A2, "a2", +1),
    EventKind.IMPACT_A3: Surface(EventKind.IMPACT_A3, "a3", -1),
    EventKind.ZONE_END_A4: Surface(EventKind.ZONE_END_A4, "a4", -1),
}

#: the centre of oscillation in each mode, in units of F/K
CENTRE_SIGN = (0.0, 1.0, -1.0)

#: the mode each event leads to, and the impact awaited after it
_TRANSITIONS: dict[EventKind, tuple[Mode, Awaited]] = {
    EventKind.IMPACT_A1: (Mode.ZONE_RIGHT, Awaited.A3),
    EventKind.ZONE_END_A2: (Mode.FREE, Awaited.A3),
    EventKind.IMPACT_A3: (Mode.ZONE_LEFT, Awaited.A1),
    EventKind.ZONE_END_A4: (Mode.FREE, Awaited.A1),
}

_WATCHED: dict[tuple[Mode, Awaited], tuple[EventKind, ...]] = {
    (Mode.FREE, Awaited.EITHER): (EventKind.IMPACT_A1, EventKind.IMPACT_A3),
    (Mode.FREE, Awaited.A1): (EventKind.IMPACT_A1,),
    (Mode.FREE, Awaited.A3): (EventKind.IMPACT_A3,),
}
_ZONE_END = {Mode.ZONE_RIGHT: (EventKind.ZONE_END_A2,), Mode.ZONE_LEFT: (EventKind.ZONE_END_A4,)}

#: each impulse zone by its mode: (name in messages, the surface that ends it)
ZONE_OF = {Mode.ZONE_RIGHT: ("(a1, a2)", EventKind.ZONE_END_A2), Mode.ZONE_LEFT: ("(a4, a3)", EventKind.ZONE_END_A4)}

#: how the run ends when no watched surface is passed in a mode
EXIT_WITHOUT_EVENT = {Mode.FREE: Status.STOPPED, Mode.ZONE_RIGHT: Status.TURNED_BACK_IN_ZONE,
                      Mode.ZONE_LEFT: Status.TURNED_BACK_IN_ZONE}

#: the mode and awaited impact at the start of a run
INITIAL = (Mode.FREE, Awaited.EITHER)

#: event codes that are impacts, as a lookup table by code (index 0 unused)
IMPACT_TABLE = (False, True, False, True, False)


def watched(mode: Mode, awaited: Awaited) -> tuple[EventKind, ...]:
    """The surfaces that can end the current arc."""
    if mode == Mode.FREE:
        return _WATCHED[(Mode.FREE, Awaited(awaited))]
    return _ZONE_END[Mode(mode)]


def transition(kind: EventKind) -> tuple[Mode, Awaited]:
    """The mode after the event ``kind``, and the impact awaited from then on."""
    return _TRANSITIONS[EventKind(kind)]


def centre(mode: int, zone_offset):
    """The centre of oscillation in ``mode``; ``zone_offset`` is F/K (a number or an array)."""
    return CENTRE_SIGN[int(mode)] * zone_offset


def position(kind: EventKind, params) -> float:
    """Where the surface ``kind`` lies for these parameters."""
    return getattr(params, SURFACES[EventKind(kind)].position)


def is_impact(kind: int) -> bool:
    """True for the impacts at a1 and a3, False for the ends of the impulse zones."""
    return IMPACT_TABLE[int(kind)]


def velocity_after(v_before, b, impact):
    """The jump at an event: ``v+ = (1 - b) v-`` at an impact (``impact`` true), none otherwise.

    Works on floats, arrays (``impact`` a boolean array) and mpmath numbers.
    """
    return (1.0 - b * impact) * v_before


def reverses(v_before, v_after):
    """True where the jump reversed the velocity (``b > 1``): the mass rebounds and chatters."""
    return v_after * v_before < 0.0


def rebound_distance(kind: EventKind, where):
    """After a rebound at the impact ``kind`` at position ``where``, the distance from the free
    centre (0) to it on the side the spring pushes towards (> 0 when the spring drives the mass
    back to it)."""
    return -SURFACES[EventKind(kind)].direction * where
