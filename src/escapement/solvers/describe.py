"""The tables a run is made of (cycles, harmonic arcs, a regime exit's numbers), their columns' names, units and
long names, and their summaries."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Protocol

import numpy as np

from ..model.arguments import sample_times
from ..model.events import EVENT_COLUMNS as EVENT_NAMES
from ..model.kinematics import sample_arcs
from ..model.printing import number, span, texts, with_unit
from ..model.quantities import VARIABLES

__all__ = ["CYCLE_COLUMNS", "EVENT_COLUMNS", "EXIT_UNITS", "ArcTable", "CycleTable", "Exit", "Trajectory"]


class Trajectory(Protocol):
    """Anything that evaluates the motion at given times."""

    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and acceleration at times ``t`` (NaN outside [0, t_final])."""


@dataclass(frozen=True, repr=False)
class CycleTable:
    """One entry per complete cycle ``k = 1 .. N`` (mpmath numbers for the high-precision solver; for the ensemble,
    a row per trajectory)."""

    impact_time: np.ndarray  #: time of impact k at a1, s
    velocity_before_impact: np.ndarray  #: velocity just before impact k, m/s
    period: np.ndarray  #: time from impact k to impact k+1, s
    largest_displacement: np.ndarray  #: largest x between impact k and impact k+1, m

    def __len__(self) -> int:
        return len(self.period)

    def __repr__(self) -> str:
        shape = np.shape(self.period)
        size = f"{shape[-1]} cycles" + (f" x {shape[0]} trajectories" if len(shape) == 2 else "")
        return "\n".join([f"<CycleTable> {size}", *(f"  {name:<24}{span(getattr(self, name), unit)}"
                                                      for name, unit in CYCLE_UNITS.items())])

    @property
    def cycle(self) -> np.ndarray:
        """Cycle numbers 1 .. N."""
        return np.arange(1, len(self) + 1)


#: the per-cycle table's columns, the fields of :class:`CycleTable`: name: (UDUNITS string, long name)
CYCLE_COLUMNS = {f.name: (VARIABLES[f.name].units, VARIABLES[f.name].long_name) for f in fields(CycleTable)}
#: the event log's columns: name: (field of the EventLog, UDUNITS string or None for the kind, a code, long name)
EVENT_COLUMNS = {name: (field, None if VARIABLES[name].dimensionless else VARIABLES[name].units,
                        VARIABLES[name].long_name) for field, name in EVENT_NAMES.items()}
#: the plain-text units of the per-cycle columns and of the exit's numbers, for the summaries
CYCLE_UNITS = {name: VARIABLES[name].unit_label for name in CYCLE_COLUMNS}
EXIT_UNITS = {"turning_point": "m", "margin": "m", "t_accumulation": "s"}


@dataclass(frozen=True, repr=False)
class ArcTable:
    """The motion as harmonic arcs: arc i starts at t_start[i] from (x_start[i], v_start[i]) about centre[i]."""

    t_start: np.ndarray
    centre: np.ndarray
    x_start: np.ndarray
    v_start: np.ndarray
    omega: float
    t_final: float

    def __len__(self) -> int:
        return len(self.t_start)

    def __repr__(self) -> str:
        omega = number(self.omega, "rad/s")
        if not len(self):
            return f"<ArcTable> no harmonic arcs, omega = {omega}"
        start, end = texts([self.t_start[0], self.t_final])
        arcs = f"{len(self)} harmonic arc{'' if len(self) == 1 else 's'}"
        return f"<ArcTable> {arcs} from t = {start} s to t_final = {end} s, omega = {omega}"

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and smooth acceleration at times ``t`` (NaN outside [0, t_final])."""
        t = sample_times("t", t)
        if len(self.t_start) == 0:
            nan = np.full(np.shape(t), np.nan)
            return nan, nan.copy(), nan.copy()
        return sample_arcs(t, self.t_start, self.centre, self.x_start, self.v_start, self.omega, self.t_final)


@dataclass(frozen=True)
class Exit:
    """The numbers behind a regime exit; NaN where they do not apply to the outcome.

    Parameters
    ----------
    turning_point : float
        Where the motion turns, m: the radius of a ``stopped`` run's free swing (it turns at both signs), the
        turning point of a ``turned_back_in_zone`` run inside the zone.
    margin : float
        How far short of the awaited position the motion turns, m (0 when it grazes): the awaited impact position
        of a ``stopped`` run, the zone's end of a ``turned_back_in_zone`` run.
    t_accumulation : float
        Time at which the rebounds of a ``chattering`` run accumulate (a Zeno point), or the first accumulation a
        ``completed`` run went on past (``past_accumulation: continue``), s; NaN if none.

    Examples
    --------
    A release at 0.01 m swings freely inside ``[-0.01, 0.01]`` m and never reaches ``a1 = -0.1`` m:

    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=0.01, n_cycles=5)
    >>> run.status.value, run.exit.turning_point, round(run.exit.margin, 12), run.exit.t_accumulation
    ('stopped', 0.01, 0.09, nan)
    """

    turning_point: float = math.nan
    margin: float = math.nan
    t_accumulation: float = math.nan

    def summary(self, printed: dict[str, str] | None = None) -> str:
        """The numbers that apply, with their units; ``printed`` gives those already printed."""
        printed = printed or {}
        return ", ".join(f"{name} = {with_unit(printed.get(name) or number(getattr(self, name)), unit)}"
                         for name, unit in EXIT_UNITS.items() if not math.isnan(getattr(self, name)))

    def __repr__(self) -> str:
        values = ", ".join(f"{name}={float(getattr(self, name)) + 0.0!r}" for name in EXIT_UNITS)
        return f"Exit({values})"
