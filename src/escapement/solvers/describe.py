"""How a run describes itself: its columns' units and long names, and the text of its summaries.

The per-cycle table and the event log have named columns, each with its UDUNITS string and long
name (:data:`CYCLE_COLUMNS`, :data:`EVENT_COLUMNS`), the same in a run's data frames
(:meth:`escapement.Solution.to_dataframe`) and in the CF datasets of :mod:`escapement.io`. The
summaries are what the results' ``repr`` shows: the outcome, counts, time span and the parameters
with their units, a few lines whatever the length of the run.

Every number printed is true as printed (:mod:`escapement.model.printing`): an input (a parameter, the
initial state, an end time) as it can be typed back, so that it is told apart from any bound it is compared
with; a computed value to a few significant digits, with more where two values that differ would otherwise
print alike; zero without a sign.
"""

from __future__ import annotations

import math
import textwrap

from typing import TYPE_CHECKING

import numpy as np

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.printing import exact, number, span, texts, with_unit
from ..model.quantities import INITIAL_STATE, PARAMETERS, VARIABLES
from ..model.status import Status

if TYPE_CHECKING:  # the results these summaries describe (they describe themselves by these functions)
    from .result import ArcTable, CycleTable, EnsembleSolution, Exit, Solution

__all__ = [
    "CYCLE_COLUMNS",
    "CYCLE_UNITS",
    "EVENT_COLUMNS",
    "EXIT_UNITS",
    "arc_table_summary",
    "cycle_table_summary",
    "ensemble_summary",
    "exit_summary",
    "solution_summary",
]

_CYCLE_NAMES = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
#: the per-cycle table's columns: name: (UDUNITS string, long name), from the quantities' table
CYCLE_COLUMNS = {name: (VARIABLES[name].units, VARIABLES[name].long_name) for name in _CYCLE_NAMES}
#: the event log's columns: name: (field of the EventLog, UDUNITS string or None for a code, long name)
EVENT_COLUMNS = {
    "event_time": ("t", "s", "time of the event"),
    "event_kind": ("kind", None, "kind of event"),
    "event_position": ("x", "m", "position of the event"),
    "event_velocity_before": ("v_before", "m s-1", "velocity just before the event"),
    "event_velocity_after": ("v_after", "m s-1", "velocity just after the event"),
}

#: the plain-text units of the per-cycle columns and of the exit's numbers, for the summaries
CYCLE_UNITS = {name: VARIABLES[name].unit_label for name in _CYCLE_NAMES}
EXIT_UNITS = {"turning_point": "m", "margin": "m", "t_accumulation": "s"}
#: the width the summaries wrap the message to, and of their column of labels
_WIDTH = 120
_LABEL = 12


def _line(label: str, text: str, column: int = _LABEL, wrap: bool = False) -> str:
    """One line of a summary: the label in a column ``column`` wide, ``text`` beside it (wrapped
    with ``wrap``)."""
    head = f"{label + ':':<{column}}"
    if not wrap:
        return head + text
    return textwrap.fill(text, _WIDTH, initial_indent=head, subsequent_indent=" " * column, break_on_hyphens=False)


def _parameters_text(params: Parameters) -> str:
    return ", ".join(f"{name} = {exact(value, PARAMETERS[name].unit_label)}"
                     for name, value in params.as_dict().items())


def arc_table_summary(arcs: ArcTable) -> str:
    """One line on a table of harmonic arcs (:class:`~escapement.solvers.result.ArcTable`)."""
    if not len(arcs):
        return f"<ArcTable> no harmonic arcs, omega = {number(arcs.omega, 'rad/s')}"
    start, end = texts([arcs.t_start[0], arcs.t_final])
    arcs_ = f"{len(arcs)} harmonic arc{'' if len(arcs) == 1 else 's'}"
    return f"<ArcTable> {arcs_} from t = {start} s to t_final = {end} s, omega = {number(arcs.omega, 'rad/s')}"


def cycle_table_summary(cycles: CycleTable) -> str:
    """The range of each column of a per-cycle table, one or many trajectories."""
    shape = np.shape(cycles.period)
    size = f"{shape[-1]} cycles" + (f" x {shape[0]} trajectories" if len(shape) == 2 else "")
    lines = [f"<CycleTable> {size}"]
    for name, unit in CYCLE_UNITS.items():
        lines.append(f"  {name:<24}{span(getattr(cycles, name), unit)}")
    return "\n".join(lines)


def exit_summary(exit: Exit, printed: dict[str, str] | None = None) -> str:
    """The numbers of a regime exit that apply, with their units (empty if none does); ``printed``
    gives the text of those already printed beside other numbers."""
    printed = printed or {}
    return ", ".join(f"{name} = {with_unit(printed.get(name) or number(getattr(exit, name)), unit)}"
                     for name, unit in EXIT_UNITS.items() if not math.isnan(getattr(exit, name)))


def solution_summary(solution: Solution, trajectory: str) -> str:
    """A run in a few lines: outcome, message, time span, events, cycles, initial state, parameters
    and the exit's numbers; ``trajectory`` says whether (and how) the motion was kept."""
    ev, cycles = solution.events, solution.cycles
    impacts = int(np.count_nonzero(np.isin(ev.kind, [int(EventKind.IMPACT_A1), int(EventKind.IMPACT_A3)])))
    # the times side by side, each printed so that it compares with the others as it does
    times = [0.0, solution.t_final, solution.exit.t_accumulation, *(ev.t[[0, -1]] if len(ev) else ())]
    zero, t_final, t_acc, *event_times = texts(times)
    lines = [
        f"<escapement.Solution> {solution.status.value} ({solution.method})",
        _line("message", solution.message, wrap=True),
        _line("time span", f"t = {zero} .. {t_final} s (t_final)"),
    ]
    events = f"{len(ev)} ({impacts} impact{'' if impacts == 1 else 's'})"
    if len(ev) == 1:
        events += f" at t = {event_times[0]} s"
    elif len(ev):
        events += f" from t = {event_times[0]} s to {event_times[1]} s"
    lines.append(_line("events", events))
    text = f"{len(cycles)}"
    if len(cycles):
        text += (f"; the last: period {number(cycles.period[-1], 's')}, velocity before impact "
                 f"{number(cycles.velocity_before_impact[-1], 'm/s')}, largest displacement {number(cycles.largest_displacement[-1], 'm')}")
    lines.append(_line("cycles", text))
    lines.append(_line("trajectory", trajectory))
    state = ", ".join(f"{name} = {exact(value, INITIAL_STATE[name].unit_label)}"
                      for name, value in (("x0", solution.x0), ("v0", solution.v0)))
    lines.append(_line("initial", state))
    lines.append(_line("parameters", _parameters_text(solution.params)))
    if exit_summary(solution.exit):
        lines.append(_line("exit", exit_summary(solution.exit, {"t_accumulation": t_acc})))
    return "\n".join(lines)


def ensemble_summary(runs: EnsembleSolution) -> str:
    """Many runs in a few lines: the count of each outcome and the range of each column."""
    n = len(runs.status)
    codes, counts = np.unique(np.asarray(runs.status), return_counts=True)
    outcomes = ", ".join(f"{Status.from_code(code).value} {count}" for code, count in zip(codes, counts))
    shape = np.shape(runs.cycles.period)
    column = 25
    lines = [
        f"<escapement.EnsembleSolution> {n} trajectories, {shape[-1] if len(shape) == 2 else 0} cycles "
        f"({runs.method})",
        _line("outcomes", outcomes or "none", column),
        _line("t_final", span(runs.t_final, "s"), column),
    ]
    for name, unit in CYCLE_UNITS.items():
        lines.append(_line(name, span(getattr(runs.cycles, name), unit), column))
    for name, unit in EXIT_UNITS.items():
        values = getattr(runs, f"exit_{name}")
        if not np.isnan(np.asarray(values, dtype=float)).all():
            lines.append(_line(f"exit_{name}", span(values, unit), column))
    return "\n".join(lines)
