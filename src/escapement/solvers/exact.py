"""The exact event-driven solver: one run of the escapement, every event in closed form (:func:`solve_exact`)."""

from __future__ import annotations

import numpy as np

from ..model.events import EventLog
from ..model.limits import check_flag, run_spec
from ..model.parameters import Parameters
from .describe import ArcTable, CycleTable
from .kernel import EventRun, event_block
from .outcomes import finish
from .result import Solution

__all__ = ["ARC_BYTES", "CYCLE_BYTES", "EVENT_BYTES", "PASS_BYTES", "solve_exact"]

EVENT_BYTES = 130  #: bytes per event at the peak (tracemalloc measured 109): the loop's buffers and derived arrays
ARC_BYTES = 8  #: bytes per event of the arcs when the trajectory is kept: their start times
CYCLE_BYTES = 64  #: bytes per cycle: the cycle table's four columns and their temporaries
PASS_BYTES = 1 << 16  #: bytes whatever the run's length


def solve_exact(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                t_end: float | None = None, max_events: int | None = None, record_trajectory: bool = True,
                memory_budget: int | None = None) -> Solution:
    """Integrate the escapement model exactly from ``(x0, v0)`` at ``t = 0+``.

    The run ends at the first of ``n_cycles`` cycles, the end time ``t_end`` (an event exactly at it belongs to the
    run), ``max_events`` events and the motion leaving the escapement regime; ``status`` and ``message`` say which.
    An invalid input, or a result over ``memory_budget`` bytes, is refused before any work (ParameterError).

    Parameters
    ----------
    params : Parameters
        The model's parameters.
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run (from an impact at ``a1`` to the next); this, ``t_end`` or both.
    t_end : float, optional
        End time, s.
    max_events : int, optional
        The most events the run may hold (default: those of ``n_cycles`` cycles with a margin, or 10**7).
    record_trajectory : bool, default True
        Keep the harmonic arcs, for :meth:`Solution.sample <escapement.Solution.sample>`.
    memory_budget : int, optional
        The most bytes the result may hold (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    Solution
        How the run ended (leaving the regime is an outcome, not an error), its events, cycles and trajectory.

    Examples
    --------
    The paper's Fig. 3 (a) as the configuration runs it (fig3.cases.a), released from rest at x0 = -1 m:

    >>> from escapement import Parameters, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_exact(p, x0=-1.0, n_cycles=50)
    >>> run.status.value, len(run.cycles), round(float(run.cycles.period[-1]), 4)  # the period in s
    ('completed', 50, 6.2957)
    >>> x, v, a = run.sample([0.0, 1.0])  # m, m/s, m/s**2
    >>> round(float(x[1]), 6)
    -0.540302
    """
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events, memory_budget=memory_budget,
                    choices=True)
    record_trajectory = check_flag("record_trajectory", record_trajectory)
    contents = "its event log, cycle table and arcs" if record_trajectory else "its event log and cycle table"
    remedy = ("pass record_trajectory=False, " if record_trajectory else "") + \
        "raise memory_budget, or stream the cycles in constant memory with escapement.solvers.iter_cycles"
    spec.limits.check_memory(EVENT_BYTES + (ARC_BYTES if record_trajectory else 0), CYCLE_BYTES, contents, remedy,
                             fixed_bytes=PASS_BYTES)
    run = EventRun(spec)
    run.advance(spec.limits.max_events)
    block = event_block(run, 0, *run.take(), before=run.release)
    log = EventLog(t=block.t, kind=block.kind, x=block.x, v_before=block.v_before, v_after=block.v_after)
    trajectory = None
    if record_trajectory:  # an arc ends at each event, and one more if the run ended inside it
        n = len(block.t) + run.open_arc
        arcs = [np.concatenate(([0.0], block.t))[:n], block.arc_centre[:n], block.arc_x[:n], block.arc_v[:n]]
        at = np.array(run.wait_at, dtype=np.intp) + 1
        at = at[at < n]  # the arcs from rest after the rebounds the run went on past: rest at the impact position
        rest = (arcs[0][at], arcs[2][at], arcs[2][at], np.zeros(len(at)))  # until the rebounds accumulate
        arcs[0][at] += np.array(run.wait)[:len(at)]
        trajectory = ArcTable(*(np.insert(a, at, r) for a, r in zip(arcs, rest)), spec.params.omega,
                              float(run.outcome.t_final))
    return finish(spec, "exact", run.outcome, log, CycleTable(*block.cycles), trajectory)
