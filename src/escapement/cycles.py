"""Per-cycle quantities of the Poincare map on the section x = a1, v > 0.

Cycle ``k`` begins at the ``k``-th impact at ``a1`` and ends at the next one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .events import EventKind, EventLog

__all__ = ["CycleTable", "cycle_table"]


@dataclass(frozen=True)
class CycleTable:
    """One entry per complete cycle ``k = 1 .. N``."""

    impact_time: np.ndarray  #: time of impact k at a1, s
    velocity_before_impact: np.ndarray  #: velocity just before impact k, m/s
    period: np.ndarray  #: time from impact k to impact k+1, s
    amplitude: np.ndarray  #: largest x between impact k and impact k+1, m

    def __len__(self) -> int:
        return len(self.period)

    @property
    def cycle(self) -> np.ndarray:
        """Cycle numbers 1 .. N."""
        return np.arange(1, len(self) + 1)


def cycle_table(events: EventLog, cycle_maxima: np.ndarray, periods: np.ndarray | None = None) -> CycleTable:
    """Build the table from the event log and the largest x of each complete cycle.

    ``periods``, when given, are the durations summed inside each cycle; otherwise they are
    differences of the impact times, which lose digits once the times grow large.
    """
    impacts = events.of_kind(EventKind.IMPACT_A1)
    n = max(len(impacts) - 1, 0)
    maxima = np.asarray(cycle_maxima, dtype=float)
    if len(maxima) != n:
        raise ValueError(f"cycle_maxima has {len(maxima)} entries for {n} complete cycles")
    times = events.t[impacts]
    period = np.diff(times) if periods is None else np.asarray(periods, dtype=float)
    if len(period) != n:
        raise ValueError(f"periods has {len(period)} entries for {n} complete cycles")
    return CycleTable(
        impact_time=times[:n],
        velocity_before_impact=events.v_before[impacts][:n],
        period=period,
        amplitude=maxima,
    )
