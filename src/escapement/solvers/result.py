"""The result of every solver: :class:`Solution` for one run, :class:`EnsembleSolution` for many.

Both carry the same fields (the ensemble's as arrays with one row per trajectory): how the
run ended (``status``, ``message``, ``success``), the numbers behind a regime exit
(:class:`Exit`), the events, the per-cycle table of the Poincare map on the section
``x = a1, v > 0`` (cycle ``k`` runs from the ``k``-th impact at a1 to the next) and, where
kept, the trajectory.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..model.events import EventLog
from ..model.kinematics import sample_arcs
from ..model.parameters import Parameters
from ..model.status import Status

__all__ = ["ArcTable", "CycleTable", "EnsembleSolution", "Exit", "Solution", "Trajectory"]


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
class CycleTable:
    """One entry per complete cycle ``k = 1 .. N`` (arrays; mpmath numbers in an object array
    for the high-precision solver)."""

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


@dataclass(frozen=True)
class Exit:
    """The numbers behind a regime exit; NaN where they do not apply to the outcome.

    * ``stopped``: ``turning_point`` is the radius of the free swing (it turns at
      ``-turning_point`` and ``+turning_point``), ``margin`` how far short of the awaited impact
      position it turns (0 when it grazes it).
    * ``turned_back_in_zone``: ``turning_point`` is where the motion turns inside the zone,
      ``margin`` its distance from the zone's end.
    * ``chattering``: ``t_accumulation`` is the time at which the rebounds accumulate (NaN when
      they do not).
    """

    turning_point: float = math.nan
    margin: float = math.nan
    t_accumulation: float = math.nan


@dataclass(frozen=True)
class Solution:
    """A run: how it ended, its events, its cycles and its trajectory.

    ``t_final`` is the end of the computed trajectory (``inf`` when the escapement stopped and
    the free oscillation goes on for ever).
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
    t_final: float
    exit: Exit = Exit()

    @property
    def success(self) -> bool:
        """True when the requested cycles or end time were reached."""
        return self.status.success

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s] and acceleration [m/s^2] at times ``t`` [s]."""
        if self.trajectory is None:
            raise ValueError("this run kept no trajectory; solve again with record_trajectory=True")
        return self.trajectory.sample(np.asarray(t, dtype=float))


@dataclass(frozen=True)
class EnsembleSolution:
    """Many runs at once: the fields of :class:`Solution` with one row per trajectory.

    Per-cycle arrays have shape ``(N, n_cycles)``, NaN where a trajectory ended earlier;
    ``status`` holds :attr:`Status.code` values. Events and trajectories are not kept.
    """

    status: np.ndarray
    cycles: CycleTable
    t_final: np.ndarray
    exit_turning_point: np.ndarray
    exit_margin: np.ndarray
    exit_t_accumulation: np.ndarray
    method: str = "exact, vectorised ensemble"

    @property
    def success(self) -> np.ndarray:
        return self.status == Status.COMPLETED.code

    def outcome(self, i: int) -> Status:
        """The outcome of trajectory ``i``."""
        return Status.from_code(int(self.status[i]))
