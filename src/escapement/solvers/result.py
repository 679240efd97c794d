"""The result of every solver: :class:`Solution` for one run, :class:`EnsembleSolution` for many.

Both carry the same fields (the ensemble's as arrays with one row per trajectory): how the
run ended (``status``, ``message``, ``success``), the numbers behind a regime exit
(:class:`Exit`), the events, the per-cycle table of the Poincare map on the section
``x = a1, v > 0`` (cycle ``k`` runs from the ``k``-th impact at a1 to the next) and, where
kept, the trajectory.

Their ``repr`` is a short summary (outcome, counts, time span, parameters with units), whatever the
length of the run; the arrays are in the fields. :meth:`Solution.to_xarray` gives the run as the
CF dataset the workflow writes, :meth:`Solution.to_dataframe` its cycles or events as a table.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from ..model.events import EventKind, EventLog
from ..model.kinematics import sample_arcs
from ..model.parameters import Parameters
from ..model.quantities import INITIAL_STATE, PARAMETERS
from ..model.status import Status

if TYPE_CHECKING:  # io and pandas are imported on use (see Solution.to_xarray)
    import pandas as pd
    import xarray as xr

__all__ = ["ArcTable", "CycleTable", "EnsembleSolution", "Exit", "Solution", "Trajectory"]

#: the plain-text units of the per-cycle columns and of the exit's numbers, for the summaries
CYCLE_UNITS = {"impact_time": "s", "velocity_before_impact": "m/s", "period": "s", "amplitude": "m"}
EXIT_UNITS = {"turning_point": "m", "margin": "m", "t_accumulation": "s"}
#: the width the summaries wrap the message to, and of their column of labels
_WIDTH = 120
_LABEL = 12


def _number(value, unit: str = "") -> str:
    """``value`` to 6 significant digits (an mpmath number as its nearest double), with its unit."""
    text = f"{float(value):.6g}"
    return text if unit in ("", "1") else f"{text} {unit}"


def _span(values, unit: str) -> str:
    """The range of ``values`` (NaN ignored): ``lo .. hi unit``, one number if they agree."""
    finite = np.asarray(values, dtype=float)
    finite = finite[~np.isnan(finite)]
    if not finite.size:
        return "none"
    lo, hi = finite.min(), finite.max()
    return _number(lo, unit) if lo == hi else f"{_number(lo)} .. {_number(hi, unit)}"


def _line(label: str, text: str, column: int = _LABEL, wrap: bool = False) -> str:
    """One line of a summary: the label in a column ``column`` wide, ``text`` beside it (wrapped
    with ``wrap``)."""
    head = f"{label + ':':<{column}}"
    if not wrap:
        return head + text
    return textwrap.fill(text, _WIDTH, initial_indent=head, subsequent_indent=" " * column, break_on_hyphens=False)


def _parameters_text(params: Parameters) -> str:
    return ", ".join(f"{name} = {_number(value, PARAMETERS[name].unit_label)}"
                     for name, value in params.as_dict().items())


class Trajectory(Protocol):
    """Anything that evaluates the motion at given times."""

    t_final: float

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...


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
        return (f"<ArcTable> {len(self)} harmonic arcs from t = {_span(self.t_start[:1], 's')} to "
                f"t_final = {_number(self.t_final, 's')}, omega = {_number(self.omega, 'rad/s')}")

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and smooth acceleration at times ``t`` (NaN outside [0, t_final])."""
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
    amplitude: np.ndarray  #: largest x between impact k and impact k+1, m

    def __len__(self) -> int:
        return len(self.period)

    def __repr__(self) -> str:
        shape = np.shape(self.period)
        size = f"{shape[-1]} cycles" + (f" x {shape[0]} trajectories" if len(shape) == 2 else "")
        lines = [f"<CycleTable> {size}"]
        for name, unit in CYCLE_UNITS.items():
            lines.append(f"  {name:<24}{_span(getattr(self, name), unit)}")
        return "\n".join(lines)

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
        return ", ".join(f"{name} = {_number(getattr(self, name), unit)}" for name, unit in EXIT_UNITS.items()
                         if not math.isnan(getattr(self, name)))


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
        period (s) and amplitude (m).
    trajectory : Trajectory or None
        The motion between the events, where kept (``record_trajectory=True``); see :meth:`sample`.
    t_final : float
        End of the computed trajectory, s (``inf`` when the escapement stopped and the free
        oscillation goes on for ever).
    exit : Exit
        The numbers behind a regime exit (NaN where they do not apply).

    See Also
    --------
    Solution.to_xarray : the run as a CF dataset.
    Solution.to_dataframe : its cycles or events as a :class:`pandas.DataFrame`.

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
    cycles:     50; the last: period 6.29567 s, velocity before impact 1.25656 m/s, amplitude 1.26053 m
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
        ev, cycles = self.events, self.cycles
        impacts = int(np.count_nonzero(np.isin(ev.kind, [int(EventKind.IMPACT_A1), int(EventKind.IMPACT_A3)])))
        lines = [
            f"<escapement.Solution> {self.status.value} ({self.method})",
            _line("message", self.message, wrap=True),
            _line("time span", f"t = 0 .. {_number(self.t_final, 's')} (t_final)"),
        ]
        events = f"{len(ev)} ({impacts} impacts)"
        if len(ev):
            events += f" from t = {_number(ev.t[0], 's')} to {_number(ev.t[-1], 's')}"
        lines.append(_line("events", events))
        text = f"{len(cycles)}"
        if len(cycles):
            text += (f"; the last: period {_number(cycles.period[-1], 's')}, velocity before impact "
                     f"{_number(cycles.velocity_before_impact[-1], 'm/s')}, amplitude {_number(cycles.amplitude[-1], 'm')}")
        lines.append(_line("cycles", text))
        if self.trajectory is None:
            kept = "not kept"
        elif isinstance(self.trajectory, ArcTable):
            n = len(self.trajectory)
            kept = f"kept ({n} harmonic arc{'' if n == 1 else 's'})"
        else:
            kept = "kept"
        lines.append(_line("trajectory", kept))
        state = ", ".join(f"{name} = {_number(value, INITIAL_STATE[name].unit_label)}"
                          for name, value in (("x0", self.x0), ("v0", self.v0)))
        lines.append(_line("initial", state))
        lines.append(_line("parameters", _parameters_text(self.params)))
        if self.exit.summary():
            lines.append(_line("exit", self.exit.summary()))
        return "\n".join(lines)

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s] and acceleration [m/s^2] at times ``t`` [s]."""
        if self.trajectory is None:
            raise ValueError("this run kept no trajectory; solve again with record_trajectory=True")
        return self.trajectory.sample(np.asarray(t, dtype=float))

    def to_xarray(self) -> xr.Dataset:
        """The run as the CF-1.11 / ACDD-1.3 dataset the workflow writes for it.

        The per-cycle table on the coordinate ``cycle`` (``impact_time`` in s,
        ``velocity_before_impact`` in m s-1, ``period`` in s, ``amplitude`` in m), every event
        (``event_time``, ``event_kind``, ``event_position``, ``event_velocity_before`` and
        ``event_velocity_after``), ``t_final`` and the exit's numbers, and the parameters and initial
        state as 0-d variables, each with its ``units`` and ``long_name``; the outcome, the solver and
        the provenance as global attributes. Built by :func:`escapement.io.dataset.run_dataset`, from
        the builders of the workflow's files; the high-precision solver's mpmath numbers become their
        nearest doubles. Write it with :func:`escapement.io.write_netcdf`.

        Returns
        -------
        xarray.Dataset
            The dataset, in memory.

        Examples
        --------
        >>> from escapement import Parameters, solve_exact
        >>> run = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=1.0, n_cycles=3)
        >>> ds = run.to_xarray()
        >>> ds.sizes["cycle"], ds.sizes["event"], ds.attrs["outcome"]
        (3, 15, 'completed')
        >>> ds["period"].attrs["units"], bool(ds["period"][0] == run.cycles.period[0])
        ('s', True)
        """
        # io sits above solvers in the package's layers (escapement/__init__.py): imported here, on
        # use, never at module level, as pandas' DataFrame.to_xarray imports xarray when called.
        from ..io.dataset import run_dataset

        return run_dataset(self)

    def to_dataframe(self, table: str = "cycles") -> pd.DataFrame:
        """The run's cycles or events as a :class:`pandas.DataFrame`.

        The columns are the variables of :meth:`to_xarray` (the same names, values and units), a
        row per cycle or per event: for ``"cycles"`` the index is the cycle number ``cycle`` (1 .. N)
        and the columns ``impact_time`` (s), ``velocity_before_impact`` (m s-1), ``period`` (s) and
        ``amplitude`` (m); for ``"events"`` the index ``event`` counts from 0 and the columns are
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
        ValueError
            If ``table`` is neither ``"cycles"`` nor ``"events"``.

        Examples
        --------
        >>> from escapement import EventKind, Parameters, solve_exact
        >>> run = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=1.0, n_cycles=3)
        >>> cycles = run.to_dataframe("cycles")
        >>> list(cycles.columns), cycles.index.name, cycles.attrs["units"]["period"]
        (['impact_time', 'velocity_before_impact', 'period', 'amplitude'], 'cycle', 's')
        >>> events = run.to_dataframe("events")
        >>> int((events["event_kind"] == EventKind.IMPACT_A1).sum())
        4
        """
        # io (and pandas with it) sits above solvers: imported on use, as in to_xarray
        import pandas as pd

        from ..io.dataset import cycle_variables, event_variables

        builders = {"cycles": cycle_variables, "events": event_variables}
        if table not in builders:
            raise ValueError(f"table = {table!r} is invalid: table must be one of {', '.join(map(repr, builders))}")
        variables = builders[table](self)
        if table == "cycles":
            index = pd.Index(self.cycles.cycle, name="cycle")
        else:
            index = pd.RangeIndex(len(self.events), name="event")
        columns = {name: da.values.astype(float) if da.dtype == object else da.values
                   for name, da in variables.items()}
        frame = pd.DataFrame(columns, index=index)
        frame.attrs["units"] = {name: da.attrs["units"] for name, da in variables.items() if "units" in da.attrs}
        frame.attrs["long_names"] = {name: da.attrs["long_name"] for name, da in variables.items()}
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
        before it (m/s), period (s), amplitude (m); NaN after a trajectory ended.
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
        """The outcome of trajectory ``i``."""
        return Status.from_code(int(self.status[i]))

    def __repr__(self) -> str:
        n = len(self.status)
        codes, counts = np.unique(np.asarray(self.status), return_counts=True)
        outcomes = ", ".join(f"{Status.from_code(code).value} {count}" for code, count in zip(codes, counts))
        shape = np.shape(self.cycles.period)
        column = 25
        lines = [
            f"<escapement.EnsembleSolution> {n} trajectories, {shape[-1] if len(shape) == 2 else 0} cycles "
            f"({self.method})",
            _line("outcomes", outcomes or "none", column),
            _line("t_final", _span(self.t_final, "s"), column),
        ]
        for name, unit in CYCLE_UNITS.items():
            lines.append(_line(name, _span(getattr(self.cycles, name), unit), column))
        for name, unit in EXIT_UNITS.items():
            values = getattr(self, f"exit_{name}")
            if not np.isnan(np.asarray(values, dtype=float)).all():
                lines.append(_line(f"exit_{name}", _span(values, unit), column))
        return "\n".join(lines)
