"""The result object returned by every solver."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from .arcs import sample_arcs
from .cycles import CycleTable
from .events import EventLog
from .outcome import Status
from .parameters import Parameters

__all__ = ["ArcTable", "Solution", "Trajectory"]


class Trajectory(Protocol):
    """Anything that evaluates the motion at given times."""

    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...


@dataclass(frozen=True)
class ArcTable:
    """The motion as a table of harmonic arcs: arc i starts at t_start[i] from
    (x_start[i], v_start[i]) and turns about centre[i] until the next arc starts."""

    t_start: np.ndarray
    centre: np.ndarray
    x_start: np.ndarray
    v_start: np.ndarray
    omega: float
    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and smooth acceleration at times ``t`` (NaN outside [0, t_final])."""
        if len(self.t_start) == 0:
            nan = np.full(np.shape(t), np.nan)
            return nan, nan.copy(), nan.copy()
        return sample_arcs(t, self.t_start, self.centre, self.x_start, self.v_start, self.omega, self.t_final)


@dataclass(frozen=True)
class Solution:
    """A run: how it ended, its events, its cycles and its trajectory.

    ``status`` and ``message`` say how the run ended; ``detail`` holds the numbers
    behind the message (for example the turning point that fell short of an impact
    position).  ``t_final`` is the end of the computed trajectory (``inf`` when the
    escapement stopped and the free oscillation goes on for ever).
    """

    params: Parameters
    x0: float
    v0: float
    method: str
    status: Status
    message: str
    events: EventLog
    cycles: CycleTable
    trajectory: Trajectory | None
    detail: dict[str, float] = field(default_factory=dict)

    @property
    def t_final(self) -> float:
        return self.trajectory.t_final if self.trajectory is not None else float(self.detail.get("t_final", np.nan))

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s] and acceleration [m/s^2] at times ``t`` [s]."""
        if self.trajectory is None:
            raise ValueError("this run kept no trajectory; solve again with record_trajectory=True")
        return self.trajectory.sample(np.asarray(t, dtype=float))
