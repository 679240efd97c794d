"""The result of every solver: :class:`Solution` for one run, :class:`EnsembleSolution` for many, each with a
summary of a few lines for a ``repr``, whatever the length of the run."""

from __future__ import annotations

import textwrap
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..model.arguments import ParameterError, check_choice, check_index, sample_times
from ..model.events import EventKind, EventLog
from ..model.parameters import Parameters
from ..model.printing import exact, number, span, texts
from ..model.quantities import INITIAL_STATE, PARAMETERS
from ..model.status import Status, succeeded
from .describe import CYCLE_COLUMNS, CYCLE_UNITS, EVENT_COLUMNS, EXIT_UNITS, ArcTable, CycleTable, Exit, Trajectory

if TYPE_CHECKING:  # pandas is imported on use (see Solution.to_dataframe)
    import pandas as pd

__all__ = ["ArcTable", "CycleTable", "EnsembleSolution", "Ended", "Exit", "Solution", "Trajectory"]


def _line(label: str, text: str, column: int = 12) -> str:
    return f"{label + ':':<{column}}{text}"


class Ended:
    """What a run's ``status`` says of it (the base of every result with a :class:`Status`)."""

    status: Status

    @property
    def success(self) -> bool:
        """True when the requested cycles or end time were reached (:attr:`Status.success`)."""
        return self.status.success


@dataclass(frozen=True, repr=False)
class Solution(Ended):
    """A run: how it ended, its events, its cycles and its trajectory.

    Every scalar solver returns one; a run that leaves the escapement regime is an outcome, not an error.

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
        The Poincare map on ``x = a1, v > 0``, per complete cycle (from an impact at a1 to the next).
    trajectory : Trajectory or None
        The motion between the events, where kept (``record_trajectory=True``); see :meth:`sample`.
    t_final : float
        End of the computed trajectory, s (``inf`` when the escapement stopped: the free swing goes on for ever).
    exit : Exit
        The numbers behind a regime exit (NaN where they do not apply).

    Examples
    --------
    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=-1.0, n_cycles=50)
    >>> run
    <escapement.Solution> completed (exact)
    message:    completed 50 cycles
    time span:  t = 0 .. 316.275 s (t_final)
    events:     201 (101 impacts) from t = 1.47063 s to 316.275 s
    cycles:     50; the last: period 6.29567 s, velocity before impact 1.25656 m/s, largest displacement 1.26053 m
    trajectory: kept (201 harmonic arcs)
    ...
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

    def __repr__(self) -> str:
        ev, cycles = self.events, self.cycles
        impacts = int(np.count_nonzero(np.isin(ev.kind, [k for k in EventKind if k.is_impact])))
        zero, t_final, t_acc, *event_times = texts([0.0, self.t_final, self.exit.t_accumulation,
                                                    *(ev.t[[0, -1]] if len(ev) else ())])
        events = f"{len(ev)} ({impacts} impact{'' if impacts == 1 else 's'})"
        if len(ev):
            events += f" at t = {event_times[0]} s" if len(ev) == 1 else \
                f" from t = {event_times[0]} s to {event_times[1]} s"
        counted = f"{len(cycles)}" + (f"; the last: period {number(cycles.period[-1], 's')}, velocity before impact "
                                      f"{number(cycles.velocity_before_impact[-1], 'm/s')}, largest displacement "
                                      f"{number(cycles.largest_displacement[-1], 'm')}" if len(cycles) else "")
        arcs = len(self.trajectory) if isinstance(self.trajectory, ArcTable) else None
        kept = "not kept" if self.trajectory is None else "kept" if arcs is None else \
            f"kept ({arcs} harmonic arc{'' if arcs == 1 else 's'})"
        state = (("x0", self.x0), ("v0", self.v0))
        message = textwrap.fill(self.message, 120, initial_indent=_line("message", ""), subsequent_indent=" " * 12,
                                break_on_hyphens=False)
        lines = [f"<escapement.Solution> {self.status.value} ({self.method})", message,
                 _line("time span", f"t = {zero} .. {t_final} s (t_final)"), _line("events", events),
                 _line("cycles", counted), _line("trajectory", kept),
                 _line("initial", ", ".join(f"{k} = {exact(v, INITIAL_STATE[k].unit_label)}" for k, v in state)),
                 _line("parameters", ", ".join(f"{k} = {exact(v, PARAMETERS[k].unit_label)}"
                                               for k, v in self.params.as_dict().items()))]
        if self.exit.summary():
            lines.append(_line("exit", self.exit.summary({"t_accumulation": t_acc})))
        return "\n".join(lines)

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s] and acceleration [m/s^2] at times ``t`` [s] (NaN outside [0, t_final])."""
        times = sample_times("t", t)
        if self.trajectory is None:
            raise ParameterError("record_trajectory", False, "True in the solve that made this run, to sample "
                                 "its trajectory (this run kept none: solve again with record_trajectory=True)")
        return self.trajectory.sample(times)

    def to_dataframe(self, table: str = "cycles") -> pd.DataFrame:
        """The run's cycles or events as a :class:`pandas.DataFrame`.

        The columns are the run's CF dataset's variables, indexed by ``cycle`` from 1 or ``event`` from 0;
        ``df.attrs["units"]`` and ``df.attrs["long_names"]`` give their UDUNITS strings and descriptions.

        Parameters
        ----------
        table : {"cycles", "events"}
            Which table.

        Returns
        -------
        pandas.DataFrame
            One row per cycle or per event.

        Examples
        --------
        >>> from escapement import EventKind, Parameters, solve_exact
        >>> run = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=-1.0, n_cycles=3)
        >>> cycles = run.to_dataframe("cycles")
        >>> list(cycles.columns), cycles.index.name, cycles.attrs["units"]["period"]
        (['impact_time', 'velocity_before_impact', 'period', 'largest_displacement'], 'cycle', 's')
        >>> events = run.to_dataframe("events")
        >>> int((events["event_kind"] == EventKind.IMPACT_A1).sum())
        4
        """
        import pandas as pd  # imported on use: a job that only solves does not load it
        if check_choice("table", table, ("cycles", "events")) == "cycles":
            index = pd.Index(self.cycles.cycle, name="cycle")
            columns = {name: (getattr(self.cycles, name), *described) for name, described in CYCLE_COLUMNS.items()}
        else:
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
    """Many runs at once: the fields of :class:`Solution` with one row per trajectory (no events, no trajectory).

    Parameters
    ----------
    status : numpy.ndarray of int, shape (N,)
        How each run ended, as :attr:`Status.code` values.
    cycles : CycleTable
        The per-cycle table, each column of shape ``(N, n_cycles)``, NaN after a trajectory ended.
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
    >>> runs = solve_ensemble(M=1.0, K=1.0, F=[0.5, 1.0], b=0.1, a1=-0.1, a2=0.05, x0=-1.0, n_cycles=3)
    >>> runs.success, runs.cycles.period.shape, runs.outcome(1)
    (array([ True,  True]), (2, 3), <Status.COMPLETED: 'completed'>)
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
        """True for each run that reached the requested cycles (:func:`~escapement.model.status.succeeded`)."""
        return succeeded(self.status)

    def outcome(self, i: int) -> Status:
        """The outcome of trajectory ``i``, an integer in ``[0, N)`` (else :class:`~escapement.ParameterError`)."""
        return Status.from_code(int(self.status[check_index("i", i, len(self.status))]))

    def __repr__(self) -> str:
        codes, counts = np.unique(np.asarray(self.status), return_counts=True)
        outcomes = ", ".join(f"{Status.from_code(code).value} {count}" for code, count in zip(codes, counts))
        shape = np.shape(self.cycles.period)
        lines = [f"<escapement.EnsembleSolution> {len(self.status)} trajectories, "
                 f"{shape[-1] if len(shape) == 2 else 0} cycles ({self.method})",
                 _line("outcomes", outcomes or "none", 25), _line("t_final", span(self.t_final, "s"), 25)]
        lines += [_line(name, span(getattr(self.cycles, name), unit), 25) for name, unit in CYCLE_UNITS.items()]
        for name, unit in EXIT_UNITS.items():
            values = getattr(self, f"exit_{name}")
            if not np.isnan(np.asarray(values, dtype=float)).all():
                lines.append(_line(f"exit_{name}", span(values, unit), 25))
        return "\n".join(lines)
