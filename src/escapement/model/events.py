"""Event kinds and the event log that the exact and the integrating solvers share."""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from .printing import texts

__all__ = ["EVENT_COLUMNS", "EventKind", "EventLog"]


class EventKind(IntEnum):
    """What happens at an event; the integer codes are stored in netCDF files.

    Parameters
    ----------
    value : int
        The stored code, 1 to 4: ``EventKind(3)`` is :attr:`IMPACT_A3`.

    Attributes
    ----------
    IMPACT_A1 : int
        1: impact at ``a1`` (m) moving right; the impulse zone ``(a1, a2)`` begins.
    ZONE_END_A2 : int
        2: the impulse ends at ``a2`` (m) moving right; free flight begins.
    IMPACT_A3 : int
        3: impact at ``a3`` (m) moving left; the impulse zone ``(a4, a3)`` begins.
    ZONE_END_A4 : int
        4: the impulse ends at ``a4`` (m) moving left; free flight begins.

    Examples
    --------
    >>> from escapement import EventKind
    >>> EventKind(3), EventKind.IMPACT_A3.is_impact, EventKind.ZONE_END_A4.is_impact, EventKind.IMPACT_A1 == 1
    (<EventKind.IMPACT_A3: 3>, True, False, True)
    """

    IMPACT_A1 = 1
    ZONE_END_A2 = 2
    IMPACT_A3 = 3
    ZONE_END_A4 = 4

    @property
    def is_impact(self) -> bool:
        """True for the impacts (at ``a1`` and ``a3``), False for the ends of the impulse zones."""
        return self in (EventKind.IMPACT_A1, EventKind.IMPACT_A3)


@dataclass(frozen=True)
class EventLog:
    """Every event of a run (:attr:`escapement.Solution.events`) in time order; the 50-digit solver's in mpmath.

    Parameters
    ----------
    t : numpy.ndarray of float, shape (n,)
        Time of each event, s.
    kind : numpy.ndarray of int, shape (n,)
        Kind of each event, as :class:`EventKind` codes.
    x : numpy.ndarray of float, shape (n,)
        Position of each event (``a1`` .. ``a4``), m.
    v_before : numpy.ndarray of float, shape (n,)
        Velocity just before each event, m/s.
    v_after : numpy.ndarray of float, shape (n,)
        Velocity just after each event, m/s (``v+ = (1 - b) v-`` at an impact, ``v-`` at a zone's end).

    Examples
    --------
    >>> from escapement import EventKind, Parameters, solve_exact
    >>> log = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=1.0, n_cycles=2).events
    >>> len(log), [EventKind(k).name for k in log.kind[:3]]
    (11, ['IMPACT_A3', 'ZONE_END_A4', 'IMPACT_A1'])
    >>> i = log.of_kind(EventKind.IMPACT_A1)[0]  # v+ = (1 - b) v-
    >>> float(log.x[i]), bool(abs(log.v_after[i] - 0.9 * log.v_before[i]) < 1e-15)
    (-0.1, True)
    """

    t: np.ndarray
    kind: np.ndarray
    x: np.ndarray
    v_before: np.ndarray
    v_after: np.ndarray

    def __len__(self) -> int:
        """The number of events."""
        return len(self.t)

    def __repr__(self) -> str:
        """One line: the events of each kind and the times of the first and the last, never the arrays."""
        n = len(self)
        head = f"<EventLog> {n} event{'' if n == 1 else 's'}"
        if not n:
            return head
        codes, counts = np.unique(np.asarray(self.kind, dtype=int), return_counts=True)
        kinds = ", ".join(f"{EventKind(code).name} {count}" for code, count in zip(codes, counts))
        first, last = texts([self.t[0], self.t[-1]])
        return f"{head} {f'at t = {first} s' if n == 1 else f'from t = {first} s to {last} s'}: {kinds}"

    def of_kind(self, kind: EventKind) -> np.ndarray:
        """The indices of the events of ``kind``, in time order."""
        return np.flatnonzero(self.kind == int(kind))


#: the event log's columns in tables and datasets by the field each holds (units and long names: ``VARIABLES``)
EVENT_COLUMNS = {"t": "event_time", "kind": "event_kind", "x": "event_position", "v_before": "event_velocity_before",
                 "v_after": "event_velocity_after"}
