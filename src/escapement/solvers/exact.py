"""The exact event-driven solver: one run of the escapement, every event in closed form.

:func:`solve_exact` checks its inputs, refuses a run too large for its memory budget, runs the event
loop of :mod:`escapement.solvers.kernel` and derives the event log, the cycle table and the table of
arcs from what the loop stored, on arrays.
"""

from __future__ import annotations

import numpy as np

from ..model.events import EventLog
from ..model.limits import check_flag, run_spec
from ..model.parameters import Parameters
from .describe import ArcTable, CycleTable
from .kernel import Block, EventRun, cycle_rows, event_block
from .outcomes import finish
from .result import Solution

__all__ = ["ARC_BYTES", "CYCLE_BYTES", "EVENT_BYTES", "PASS_BYTES", "solve_exact"]

#: bytes per event at the peak of :func:`solve_exact`: the loop's three columns (growing buffers, up to 1/8
#: over-allocated; the arrays are views of them) and the arrays derived from them (kind, position, velocity
#: after, duration, the arcs' starts, centres and largest x, and their temporaries); measured with tracemalloc
#: at 109 bytes an event, the cycle table's share included
EVENT_BYTES = 130
#: bytes per event of the arcs when the trajectory is kept: their start times (the rest are the derived columns)
ARC_BYTES = 8
#: bytes per cycle: impact time, velocity, period and largest displacement, and their temporaries
CYCLE_BYTES = 64
#: bytes whatever the run's length
PASS_BYTES = 1 << 16
_REMEDY = "raise memory_budget, or stream the cycles in constant memory with escapement.solvers.iter_cycles"


def solve_exact(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                t_end: float | None = None, max_events: int | None = None, record_trajectory: bool = True,
                memory_budget: int | None = None) -> Solution:
    """Integrate the escapement model exactly from ``(x0, v0)`` at ``t = 0+``.

    The run ends at the first of: ``n_cycles`` complete cycles, the end time ``t_end``, ``max_events``
    events, or the motion leaving the escapement regime; the returned
    :class:`~escapement.solvers.result.Solution` says which, in ``status`` and ``message``.
    Before any work the size of the result is estimated from the limits and a run above
    ``memory_budget`` bytes is refused; :func:`escapement.solvers.stream.iter_cycles` gives the cycles of
    any run in constant memory.

    On which side each boundary falls (:meth:`EventRun.advance <escapement.solvers.kernel.EventRun.advance>`):

    * ``t_end``: an event whose time (as stored, the compensated sum of the arcs' durations) equals ``t_end``
      belongs to the run, as one before it; one an ulp after it does not, and the run completes at
      ``t_final = t_end``. A turn back inside an impulse zone exactly at ``t_end`` is that exit
      (``turned_back_in_zone``); one an ulp after it is not, and the run completes at ``t_end``.
    * ``n_cycles``: the run's last event is the ``(n_cycles + 1)``-th impact at a1, which ends the last cycle;
      ``t_final`` is its time.
    * ``max_events``: the run holds at most ``max_events`` events. If the last allowed event ends the last
      cycle the run has completed; otherwise it ends there with ``event_limit``, even where the next event would
      come after ``t_end`` (the bound is reached before the end time is).

    Parameters
    ----------
    params : Parameters
        The model's parameters.
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run (cycle ``k`` runs from the ``k``-th impact at ``a1`` to the next); at
        least one of ``n_cycles`` and ``t_end`` is given.
    t_end : float, optional
        End time, s; an event exactly at ``t_end`` is kept.
    max_events : int, optional
        The most events the run may hold (default: those of ``n_cycles`` cycles with a margin, or
        10**7 for a run to ``t_end`` alone).
    record_trajectory : bool, default True
        Keep the harmonic arcs, for :meth:`Solution.sample <escapement.Solution.sample>`.
    memory_budget : int, optional
        The most bytes the result may hold (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    Solution
        The run: ``status`` and ``message`` (how it ended), ``events``, ``cycles`` (the Poincare
        map: impact time in s, velocity before impact in m/s, period in s, largest displacement in m),
        ``trajectory`` and ``t_final`` (s). Leaving the escapement regime is an outcome, not an error.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters` (a
        :class:`~escapement.model.arguments.ParameterTypeError`, which is a :class:`ParameterError` too).
    ParameterError
        If ``x0``, ``v0`` or a limit is invalid (the message names it); a
        :class:`~escapement.model.limits.MemoryBudgetError` if the run would exceed ``memory_budget``.

    Examples
    --------
    The paper's Fig. 3 (a) as the configuration runs it (fig3.cases.a), released from rest at x0 = -1 m:

    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=-1.0, n_cycles=50)
    >>> run.status, len(run.cycles)
    (<Status.COMPLETED: 'completed'>, 50)
    >>> round(float(run.cycles.period[-1]), 4)  # s
    6.2957
    >>> x, v, a = run.sample([0.0, 1.0])  # m, m/s, m/s**2
    >>> round(float(x[1]), 6)
    -0.540302

    A release too close to the centre never reaches an impact position:

    >>> solve_exact(p, x0=-0.01, n_cycles=5).status
    <Status.STOPPED: 'stopped'>
    """
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events,
                    memory_budget=memory_budget)
    record_trajectory = check_flag("record_trajectory", record_trajectory)
    contents = "its event log, cycle table and arcs" if record_trajectory else "its event log and cycle table"
    remedy = ("pass record_trajectory=False, " if record_trajectory else "") + _REMEDY
    spec.limits.check_memory(EVENT_BYTES + (ARC_BYTES if record_trajectory else 0), CYCLE_BYTES, contents, remedy,
                             fixed_bytes=PASS_BYTES)
    run = EventRun(spec)
    run.advance(spec.limits.max_events)
    block = event_block(run, 0, *run.take(), before=run.release)
    cycles, _ = cycle_rows(block)
    log = EventLog(t=block.t, kind=block.kind, x=block.x, v_before=block.v_before, v_after=block.v_after)
    trajectory = _arcs(spec.params, block, run.open_arc, float(run.outcome.t_final)) if record_trajectory else None
    return finish(spec, "exact", run.outcome, log, CycleTable(*cycles), trajectory)


def _arcs(params: Parameters, block: Block, open_arc: bool, t_final: float) -> ArcTable:
    """The arcs: one ending at each event, and the one after the last event if the run ended inside it."""
    n = len(block.t) + open_arc
    t_start = np.concatenate(([0.0], block.t))[:n]
    return ArcTable(t_start, block.arc_centre[:n], block.arc_x[:n], block.arc_v[:n],
                    params.omega, t_final)
