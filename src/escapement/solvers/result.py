"""The result of every solver: :class:`Solution` for one run, :class:`EnsembleSolution` for many.

Both carry the same fields (the ensemble's as arrays with one row per trajectory): how the
run ended (``status``, ``message``, ``success``), the numbers behind a regime exit
(:class:`Exit`), the events, the per-cycle table of the Poincare map on the section
``x = a1, v > 0`` (cycle ``k`` runs from the ``k``-th impact at a1 to the next) and, where
kept, the trajectory.

Their ``repr`` is a short summary (outcome, counts, time span, parameters with units), whatever the
length of the run (written by :mod:`.describe`); the arrays are in the fields.
:meth:`Solution.to_dataframe` gives its cycles or events as a table, and
:func:`escapement.io.run_dataset` the run as the CF dataset the workflow writes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from ..model.arguments import ParameterError, check_choice, check_index, sample_times
from ..model.events import EventLog
from ..model.kinematics import sample_arcs
from ..model.parameters import Parameters
from ..model.status import Status
from .describe import (
    CYCLE_COLUMNS,
    EVENT_COLUMNS,
    arc_table_summary,
    cycle_table_summary,
    ensemble_summary,
    exit_summary,
    solution_summary,
)

if TYPE_CHECKING:  # pandas is imported on use (see Solution.to_dataframe)
    import pandas as pd

__all__ = ["ArcTable", "CycleTable", "EnsembleSolution", "Exit", "Solution", "Trajectory"]


class Trajectory(Protocol):
    """Anything that evaluates the motion at given times."""

    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and acceleration at times ``t`` (NaN outside ``[0, t_final]``)."""


@dataclass(frozen=True, repr=False)
class ArcTable:
    """The motion as a table of harmonic arcs: arc i starts at t_start[i] from
    (x_start[i], v_start[i]) and turns about centre[i] until the next arc starts."""

    t_start: np.ndarray
    centre: np.ndarray
    x_start: np.ndarray
    v_start: np.ndarray
    omega: float
    t_final: float

    def __len__(self) -> int:
        return len(self.t_start)

    def __repr__(self) -> str:
        return arc_table_summary(self)

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and smooth acceleration at times ``t`` (NaN outside [0, t_final]); ``t`` is
        checked as :meth:`Solution.sample` says."""
        t = sample_times("t", t)
        if len(self.t_start) == 0:
            nan = np.full(np.shape(t), np.nan)
            return nan, nan.copy(), nan.copy()
        return sample_arcs(t, self.t_start, self.centre, self.x_start, self.v_start, self.omega, self.t_final)


@dataclass(frozen=True, repr=False)
class CycleTable:
    """One entry per complete cycle ``k = 1 .. N`` (arrays; mpmath numbers in an object array
    for the high-precision solver)."""

    impact_time: np.ndarray  #: time of impact k at a1, s
    velocity_before_impact: np.ndarray  #: velocity just before impact k, m/s
    period: np.ndarray  #: time from impact k to impact k+1, s
    largest_displacement: np.ndarray  #: largest x between impact k and impact k+1, m

    def __len__(self) -> int:
        return len(self.period)

    def __repr__(self) -> str:
        return cycle_table_summary(self)

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

    Parameters
    ----------
    turning_point : float
        Where the motion turns, m (see above); NaN if it does not apply.
    margin : float
        How far short of the awaited position the motion turns, m; NaN if it does not apply.
    t_accumulation : float
        Time at which the rebounds of a chattering run accumulate (a Zeno point), s; NaN if they do
        not, or if the run did not chatter.

    Examples
    --------
    A release at 0.01 m swings freely inside ``[-0.01, 0.01]`` m and never reaches ``a1 = -0.1`` m:

    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=0.01, n_cycles=5)
    >>> run.status
    <Status.STOPPED: 'stopped'>
    >>> run.exit.turning_point, round(run.exit.margin, 12), run.exit.t_accumulation
    (0.01, 0.09, nan)
    """

    turning_point: float = math.nan
    margin: float = math.nan
    t_accumulation: float = math.nan

    def summary(self) -> str:
        """The numbers that apply, with their units (empty if none does)."""
        return exit_summary(self)

    def __repr__(self) -> str:
        """The call that makes this exit, each number as typed back (zero without a sign)."""
        values = ", ".join(f"{name}={float(getattr(self, name)) + 0.0!r}"
                           for name in ("turning_point", "margin", "t_accumulation"))
        return f"Exit({values})"


@dataclass(frozen=True, repr=False)
class Solution:
    """A run: how it ended, its events, its cycles and its trajectory.

    Every solver (:func:`~escapement.solve_exact`, :func:`~escapement.solve_reference`,
    :func:`~escapement.solve_high_precision`, :func:`~escapement.solve_naive`) returns one; a run that
    leaves the escapement regime is not an error but an outcome (``status``, ``message``, ``exit``).
    Its ``repr`` is a summary of a few lines, whatever the length of the run.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float
        Initial velocity at ``t = 0+``, m/s.
    method : str
        The solver that made the run (e.g. ``"exact"``, ``"mpmath 50 digits"``).
    status : Status
        How the run ended.
    message : str
        How the run ended, in words, with the times (s) and positions (m) involved.
    events : EventLog
        Every event in time order: time (s), kind, position (m), velocity before and after (m/s).
    cycles : CycleTable
        The Poincare map per complete cycle: impact time at a1 (s), velocity just before it (m/s),
        period (s) and largest displacement (m).
    trajectory : Trajectory or None
        The motion between the events, where kept (``record_trajectory=True``); see :meth:`sample`.
    t_final : float
        End of the computed trajectory, s (``inf`` when the escapement stopped and the free
        oscillation goes on for ever).
    exit : Exit
        The numbers behind a regime exit (NaN where they do not apply).

    See Also
    --------
    Solution.to_dataframe : its cycles or events as a :class:`pandas.DataFrame`.
    escapement.io.run_dataset : the run as a CF dataset.

    Examples
    --------
    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=1.0, n_cycles=50)
    >>> run
    <escapement.Solution> completed (exact)
    message:    completed 50 cycles
    time span:  t = 0 .. 319.423 s (t_final)
    events:     203 (102 impacts) from t = 1.47063 s to 319.423 s
    cycles:     50; the last: period 6.29567 s, velocity before impact 1.25656 m/s, largest displacement 1.26053 m
    trajectory: kept (203 harmonic arcs)
    initial:    x0 = 1 m, v0 = 0 m/s
    parameters: M = 1 kg, K = 1 N/m, F = 1 N, b = 0.1, a1 = -0.1 m, a2 = 0.05 m, a3 = 0.1 m, a4 = -0.05 m
    >>> run.success, len(run.cycles), len(run.events)
    (True, 50, 203)
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

    def __repr__(self) -> str:
        if self.trajectory is None:
            kept = "not kept"
        elif isinstance(self.trajectory, ArcTable):
            n = len(self.trajectory)
            kept = f"kept ({n} harmonic arc{'' if n == 1 else 's'})"
        else:
            kept = "kept"
        return solution_summary(self, kept)

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s] and acceleration [m/s^2] at times ``t`` [s] (NaN outside
        ``[0, t_final]``), each of the shape of ``t``.

        ``t`` is a real number or a 1-d array of them, finite
        (:func:`~escapement.model.arguments.sample_times`); anything else, and a run that kept no
        trajectory, raises :class:`~escapement.ParameterError` naming it."""
        times = sample_times("t", t)
        if self.trajectory is None:
            raise ParameterError("record_trajectory", False, "True in the solve that made this run, to sample "
                                 "its trajectory (this run kept none: solve again with record_trajectory=True)")
        return self.trajectory.sample(times)

    def to_dataframe(self, table: str = "cycles") -> pd.DataFrame:
        """The run's cycles or events as a :class:`pandas.DataFrame`.

        The columns are the variables of the run's CF dataset (:func:`escapement.io.run_dataset`: the
        same names, values and units, from :mod:`escapement.solvers.describe`), a row per cycle or per
        event: for ``"cycles"`` the index is the cycle number ``cycle`` (1 .. N)
        and the columns ``impact_time`` (s), ``velocity_before_impact`` (m s-1), ``period`` (s) and
        ``largest_displacement`` (m); for ``"events"`` the index ``event`` counts from 0 and the columns are
        ``event_time`` (s), ``event_kind`` (the :class:`~escapement.EventKind` code, which compares
        equal to its member), ``event_position`` (m), ``event_velocity_before`` and
        ``event_velocity_after`` (m s-1). ``df.attrs["units"]`` maps each column with units to its
        UDUNITS string, ``df.attrs["long_names"]`` each column to its description. The high-precision
        solver's mpmath numbers become their nearest doubles.

        Parameters
        ----------
        table : {"cycles", "events"}
            Which table.

        Returns
        -------
        pandas.DataFrame
            One row per cycle or per event.

        Raises
        ------
        ParameterError
            If ``table`` is neither ``"cycles"`` nor ``"events"`` (a :class:`ValueError`).

        Examples
        --------
        >>> from escapement import EventKind, Parameters, solve_exact
        >>> run = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=1.0, n_cycles=3)
        >>> cycles = run.to_dataframe("cycles")
        >>> list(cycles.columns), cycles.index.name, cycles.attrs["units"]["period"]
        (['impact_time', 'velocity_before_impact', 'period', 'largest_displacement'], 'cycle', 's')
        >>> events = run.to_dataframe("events")
        >>> int((events["event_kind"] == EventKind.IMPACT_A1).sum())
        4
        """
        import pandas as pd  # imported on use: a job that only solves does not load it

        table = check_choice("table", table, ("cycles", "events"))
        if table == "cycles":
            index = pd.Index(self.cycles.cycle, name="cycle")
            columns = {name: (getattr(self.cycles, name), units, long_name)
                       for name, (units, long_name) in CYCLE_COLUMNS.items()}
        else:  # "events", the one choice left by check_choice
            index = pd.RangeIndex(len(self.events), name="event")
            columns = {name: (getattr(self.events, field), units, long_name)
                       for name, (field, units, long_name) in EVENT_COLUMNS.items()}
        frame = pd.DataFrame({name: np.asarray(values, dtype=np.int8 if name == "event_kind" else float)
                              for name, (values, _, _) in columns.items()}, index=index)
        frame.attrs["units"] = {name: units for name, (_, units, _) in columns.items() if units is not None}
        frame.attrs["long_names"] = {name: long_name for name, (_, _, long_name) in columns.items()}
        return frame


@dataclass(frozen=True, repr=False)
class EnsembleSolution:
    """Many runs at once: the fields of :class:`Solution` with one row per trajectory.

    Per-cycle arrays have shape ``(N, n_cycles)``, NaN where a trajectory ended earlier;
    ``status`` holds :attr:`Status.code` values. Events and trajectories are not kept. Its ``repr``
    is a summary of a few lines, whatever the number of trajectories.

    Parameters
    ----------
    status : numpy.ndarray of int, shape (N,)
        How each run ended, as :attr:`Status.code` values.
    cycles : CycleTable
        The per-cycle table, each column of shape ``(N, n_cycles)``: impact time at a1 (s), velocity
        before it (m/s), period (s), largest displacement (m); NaN after a trajectory ended.
    t_final : numpy.ndarray of float, shape (N,)
        End of each computed trajectory, s (``inf`` where the escapement stopped).
    exit_turning_point : numpy.ndarray of float, shape (N,)
        :attr:`Exit.turning_point` of each run, m.
    exit_margin : numpy.ndarray of float, shape (N,)
        :attr:`Exit.margin` of each run, m.
    exit_t_accumulation : numpy.ndarray of float, shape (N,)
        :attr:`Exit.t_accumulation` of each run, s.
    method : str
        The solver that made the runs.

    Examples
    --------
    >>> from escapement import solve_ensemble
    >>> runs = solve_ensemble(M=1.0, K=1.0, F=[0.5, 1.0], b=0.1, a1=-0.1, a2=0.05, x0=1.0, n_cycles=3)
    >>> runs.success
    array([ True,  True])
    >>> runs.cycles.period.shape
    (2, 3)
    >>> runs.outcome(1)
    <Status.COMPLETED: 'completed'>
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
        """True for each run that reached the requested cycles."""
        return self.status == Status.COMPLETED.code

    def outcome(self, i: int) -> Status:
        """The outcome of trajectory ``i``, an integer in ``[0, N)`` (else :class:`~escapement.ParameterError`)."""
        return Status.from_code(int(self.status[check_index("i", i, len(self.status))]))

    def __repr__(self) -> str:
        return ensemble_summary(self)
