"""Event kinds and the event log shared by the exact and reference solvers."""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

import numpy as np

__all__ = ["EventKind", "EventLog"]


class EventKind(IntEnum):
    """What happens at an event; the integer codes are stored in netCDF files."""

    IMPACT_A1 = 1  #: impact at a1 moving right; the impulse zone (a1, a2) begins
    ZONE_END_A2 = 2  #: the impulse ends at a2 moving right; free flight begins
    IMPACT_A3 = 3  #: impact at a3 moving left; the impulse zone (a4, a3) begins
    ZONE_END_A4 = 4  #: the impulse ends at a4 moving left; free flight begins

    @property
    def is_impact(self) -> bool:
        return self in (EventKind.IMPACT_A1, EventKind.IMPACT_A3)


@dataclass(frozen=True)
class EventLog:
    """Every event in time order: time [s], kind, position [m], velocity before and after [m/s]."""

    t: np.ndarray
    kind: np.ndarray
    x: np.ndarray
    v_before: np.ndarray
    v_after: np.ndarray

    def __len__(self) -> int:
        return len(self.t)

    def of_kind(self, kind: EventKind) -> np.ndarray:
        """Indices of the events of one kind."""
        return np.flatnonzero(self.kind == int(kind))
