"""Per-cycle closed forms: a run's cycle table from the return map of ``v**2``, without walking its events.

:func:`solve_cycles` gives the cycle table of :func:`~escapement.solvers.exact.solve_exact` from the closed
forms of each cycle (:mod:`escapement.solvers.closed_form`, the map of :mod:`escapement.model.cycle_map`);
:func:`iter_closed_form_cycles` the same table in chunks, in constant memory however many cycles. Where the
closed form does not apply, the event solver makes the run, and the result says why. :func:`cross_check`
compares a run with ``solve_exact`` on every quantity; they agree within 1e-14 down to ``b`` of about 0.015
(below, the event solver's own rounding, damped only by ``mu = (1 - b)**4``, grows like ``eps / b``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.cycle_map import CycleMap, cycle_map
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state, check_parameters
from ..model.status import Status
from .closed_form import GRAZING_SPEED_SQ, Cycles, distinct_cycles, first_impact, prepared, table_rows
from ..model.printing import compared
from .exact import solve_exact
from .kernel import PLAN
from .outcomes import check_memory
from .result import CycleTable, Exit, Solution
from .stream import DEFAULT_CHUNK, ChunkIterator, CycleStream, StreamSummary, check_chunk, iter_cycles

__all__ = [
    "CHUNK_BYTES_PER_CYCLE",
    "CLOSED_FORM",
    "CROSS_CHECK_RTOL",
    "GRAZING_SPEED_SQ",
    "CrossCheckError",
    "CycleChunks",
    "CycleMap",
    "CycleRun",
    "compare_tables",
    "cross_check",
    "cycle_map",
    "iter_closed_form_cycles",
    "solve_cycles",
]

#: the method's name (in :attr:`CycleRun.method` and the benchmark's rows)
CLOSED_FORM = "closed-form cycles"
#: the relative difference :func:`cross_check` accepts on every quantity
CROSS_CHECK_RTOL = 1e-14
#: bytes per cycle at the peak of a run whose every cycle is distinct (the transient's arcs and work arrays, 357
#: measured with tracemalloc); a run that reaches the fixed point takes less (its columns and the impact times'
#: work arrays, about 100)
PEAK_BYTES_PER_CYCLE = 400
#: bytes per cycle of a streamed chunk: its rows and the impact times' work arrays (about 96 measured)
CHUNK_BYTES_PER_CYCLE = 128
#: the columns of a cycle table, in order
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")

class CrossCheckError(AssertionError):
    """The closed-form cycles and the event solver disagree beyond the tolerance (:func:`cross_check`)."""


@dataclass(frozen=True, repr=False)
class CycleRun:
    """A run's cycle table from :func:`solve_cycles`: from the closed forms, or from the event solver where
    they do not apply (:attr:`fallback` says why; :attr:`solution` is then ``solve_exact``'s whole run)."""

    params: Parameters
    x0: float  #: initial displacement, m
    v0: float  #: initial velocity, m/s
    n_cycles: int  #: the cycles asked for
    status: Status
    message: str
    cycles: CycleTable  #: impact time (s), velocity before impact (m/s), period (s), largest displacement (m)
    t_final: float  #: time of the impact at a1 that ends the last cycle (the event solver's t_final), s
    method: str  #: ``"closed-form cycles"``, or ``"exact"`` on a fallback
    fallback: str | None  #: why the event solver made the whole run; None where the closed form did
    cycle_map: CycleMap
    #: largest relative difference between the closed form's ``v_{k+1}`` and the arcs' arrival at a1 from
    #: ``v_k`` (the map against the energy of the arcs; NaN on a fallback)
    map_residual: float = math.nan
    distinct_cycles: int = 0  #: cycles whose arcs were computed (the rest repeat the fixed point's)
    exit: Exit = Exit()
    solution: Solution | None = None  #: the event solver's run, on a fallback

    @property
    def fell_back(self) -> bool:
        """True where the event solver made the whole run."""
        return self.fallback is not None

    @property
    def success(self) -> bool:
        """True when the requested cycles were reached."""
        return self.status.success

    def __repr__(self) -> str:
        how = self.method if self.fallback is None else f"{self.method}, fell back: {self.fallback}"
        return (f"<CycleRun> {self.status.value} ({how}): {len(self.cycles)} of {self.n_cycles} cycles, "
                f"t_final = {self.t_final:.6g} s, fixed point {self.cycle_map.fixed_point:.6g} m/s")


def solve_cycles(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int,
    memory_budget: int | None = None,
    check: bool = False,
    rtol: float = CROSS_CHECK_RTOL,
) -> CycleRun:
    """The cycle table of :func:`~escapement.solvers.exact.solve_exact` for ``n_cycles`` cycles from the
    closed forms of each cycle, in a few vectorised NumPy calls (see the module's docstring).

    The first partial cycle (from the release to the first impact at a1) is the event solver's; every cycle
    from there follows from the return map ``v_{k+1}**2 = mu v_k**2 + c``. Where the closed form does not
    apply (``b > 1``, a run that stops, turns back or chatters, a grazing arc) the event solver makes the
    whole run, ``solve_exact(params, x0, v0, n_cycles=n_cycles, record_trajectory=False)``, whose numbers
    the result then holds exactly; :attr:`CycleRun.fallback` says why.

    Parameters
    ----------
    params : Parameters
        The model's parameters.
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles (cycle ``k`` runs from the ``k``-th impact at a1 to the next).
    memory_budget : int, optional
        The most bytes the result and its work arrays may take (default
        :data:`~escapement.model.limits.MEMORY_BUDGET`), :data:`PEAK_BYTES_PER_CYCLE` a cycle.
    check : bool, default False
        Compare with ``solve_exact`` on every quantity (:func:`cross_check`); raise :class:`CrossCheckError`
        beyond ``rtol``.
    rtol : float, default 1e-14
        The relative difference the check accepts.

    Returns
    -------
    CycleRun
        ``status``, ``message``, ``cycles`` (impact time in s, velocity before impact in m/s, period in s,
        amplitude in m), ``t_final`` (s), ``method``, ``fallback`` and the map's constants.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0``, ``n_cycles`` or ``memory_budget`` is invalid, or
        (:class:`~escapement.model.limits.MemoryBudgetError`) the run would exceed ``memory_budget``.
    CrossCheckError
        With ``check``, if a quantity differs from ``solve_exact``'s by more than ``rtol`` (relative).

    Examples
    --------
    >>> from escapement import Parameters
    >>> from escapement.solvers.cycles import solve_cycles
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_cycles(p, x0=1.0, n_cycles=50, check=True)
    >>> run.method, run.status.value, len(run.cycles)
    ('closed-form cycles', 'completed', 50)
    >>> round(float(run.cycles.period[-1]), 4)  # s
    6.2957
    >>> chattering = solve_cycles(Parameters(M=1.0, K=1.0, F=1.0, b=1.5, a1=-0.1, a2=0.05), x0=1.0, n_cycles=5)
    >>> chattering.method, chattering.status.value, chattering.fell_back
    ('exact', 'chattering', True)
    """
    params = check_parameters(params)
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, memory_budget=memory_budget)
    n = limits.n_cycles
    check_memory(limits, 0.0, PEAK_BYTES_PER_CYCLE, "its cycle table and the closed form's work arrays",
                 "stream the cycles in constant memory with escapement.solvers.iter_cycles")
    prep = prepared(params)
    cmap = prep.cycle_map
    first = first_impact(params, x, v)
    reason = first if isinstance(first, str) else None
    if reason is None:
        with np.errstate(all="ignore"):
            done = distinct_cycles(params, prep, first[0], first[1], n)
        reason = done if isinstance(done, str) else None
    if reason is not None:
        exact = solve_exact(params, x, v, n_cycles=n, record_trajectory=False, memory_budget=memory_budget)
        run = CycleRun(params, x, v, n, exact.status, exact.message, exact.cycles, exact.t_final, "exact", reason,
                       cmap, exit=exact.exit, solution=exact)
    else:
        table, t_final = table_rows(done, 0, n)
        run = CycleRun(params, x, v, n, Status.COMPLETED, f"completed {n} cycles", table, t_final, CLOSED_FORM,
                       None, cmap, map_residual=done.residual, distinct_cycles=done.distinct)
    if check:
        cross_check(run, rtol)
    return run


class CycleChunks(ChunkIterator):
    """:func:`solve_cycles`'s cycle table in chunks (see :func:`iter_closed_form_cycles`); once it is
    exhausted, :attr:`summary` says how the run ended."""

    def __init__(self, cycles: Cycles | None, events_before: int, n: int, chunk: int,
                 fallback: CycleStream | None, reason: str | None, cmap: CycleMap) -> None:
        self._cycles, self._events_before, self._n, self._chunk = cycles, events_before, n, chunk
        self._fallback, self._done = fallback, 0
        self.method = "exact" if fallback is not None else CLOSED_FORM  #: which solver makes the chunks
        self.fallback = reason  #: why the event solver makes the run; None where the closed forms do
        self.cycle_map = cmap
        self.distinct_cycles = 0 if cycles is None else cycles.distinct  #: cycles whose arcs were computed
        self.map_residual = math.nan if cycles is None else cycles.residual  #: as :attr:`CycleRun.map_residual`

    def _progress(self) -> str:
        if self._fallback is not None:
            return f"{self._fallback._progress()} by the event solver (the reason: its fallback attribute)"
        return f"chunks of {self._chunk} cycles by the closed forms, {self._done} of {self._n} handed over"

    def __next__(self) -> CycleTable:
        """The next chunk of the per-cycle table; :class:`StopIteration` once the run has ended."""
        if self._fallback is not None:
            try:
                return next(self._fallback)
            except StopIteration:
                self._summary = self._fallback.summary
                raise
        if self._done >= self._n:
            raise StopIteration
        stop = min(self._done + self._chunk, self._n)
        with np.errstate(all="ignore"):
            table, t_end = table_rows(self._cycles, self._done, stop)
        # a chunk owns its arrays, as the event solver's do: a window inside the transient is a view of it
        table = CycleTable(impact_time=table.impact_time, **{
            name: getattr(table, name).copy() for name in COLUMNS if name != "impact_time"})
        self._done = stop
        if stop == self._n:  # a cycle is the events of the automaton's cycle plan
            self._summary = StreamSummary(Status.COMPLETED, f"completed {self._n} cycles", Exit(), t_end, self._n,
                                          self._events_before + len(PLAN) * self._n)
        return table


def iter_closed_form_cycles(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int,
    chunk: int = DEFAULT_CHUNK,
    memory_budget: int | None = None,
) -> CycleChunks:
    """The cycle table of :func:`solve_cycles` for the same arguments, in chunks of at most ``chunk`` cycles,
    in memory that does not grow with the run: the distinct cycles are computed once, and each chunk's
    rows from them (every row from its own cycle number alone, so the chunks put together are
    ``solve_cycles``'s table number for number). The distinct cycles are those of the transient (about
    ``45 / -log10(mu)``, whatever the run's length); where they would not fit the memory budget, or the
    closed form does not apply, the event solver streams the run
    (:func:`~escapement.solvers.stream.iter_cycles`) and :attr:`CycleChunks.fallback` says why.

    Parameters
    ----------
    params : Parameters
        The model's parameters.
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles (cycle ``k`` runs from the ``k``-th impact at a1 to the next).
    chunk : int, default 100_000
        The most cycles a chunk holds.
    memory_budget : int, optional
        The most bytes a chunk (:data:`CHUNK_BYTES_PER_CYCLE` a cycle) and the transient's distinct cycles
        (:data:`PEAK_BYTES_PER_CYCLE` a cycle while they are computed) may take together (default
        :data:`~escapement.model.limits.MEMORY_BUDGET`).

    Returns
    -------
    CycleChunks
        An iterator of :class:`~escapement.solvers.result.CycleTable` chunks (impact time in s, velocity
        before impact in m/s, period in s, largest displacement in m); its ``summary`` (status, message, end time)
        once exhausted, ``method`` and ``fallback``.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0``, ``n_cycles``, ``chunk`` or ``memory_budget`` is invalid, or
        (:class:`~escapement.model.limits.MemoryBudgetError`) a chunk would exceed ``memory_budget``.

    Examples
    --------
    >>> import numpy as np
    >>> from escapement import Parameters
    >>> from escapement.solvers.cycles import iter_closed_form_cycles, solve_cycles
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> chunks = iter_closed_form_cycles(p, x0=1.0, n_cycles=250, chunk=100)
    >>> times = [c.impact_time for c in chunks]  # s
    >>> [len(t) for t in times], chunks.method, chunks.summary.status.value
    ([100, 100, 50], 'closed-form cycles', 'completed')
    >>> bool(np.array_equal(np.concatenate(times), solve_cycles(p, x0=1.0, n_cycles=250).cycles.impact_time))
    True
    """
    params = check_parameters(params)
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, memory_budget=memory_budget)
    n = limits.n_cycles
    chunk, estimate = check_chunk(chunk, CHUNK_BYTES_PER_CYCLE, limits.memory_budget)
    prep = prepared(params)
    cmap = prep.cycle_map
    first = first_impact(params, x, v)
    reason = first if isinstance(first, str) else None
    if reason is None:
        with np.errstate(all="ignore"):
            done = distinct_cycles(params, prep, first[0], first[1], n,
                                    most=(limits.memory_budget - estimate) // PEAK_BYTES_PER_CYCLE)
        reason = done if isinstance(done, str) else None
    if reason is not None:
        stream = iter_cycles(params, x, v, n_cycles=n, chunk=chunk, memory_budget=memory_budget)
        return CycleChunks(None, 0, n, chunk, stream, reason, cmap)
    return CycleChunks(done, first[2], n, chunk, None, None, cmap)


def _relative(a, b) -> np.ndarray:
    """``|a - b| / |b|`` elementwise (0 where both are 0, inf where only ``b`` is; NaN stays NaN)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        gap = np.abs(a - b)
        return np.where(a == b, 0.0, np.where(b != 0.0, gap / np.abs(b), np.inf))


def compare_tables(table: CycleTable, reference: CycleTable) -> dict[str, float]:
    """The largest relative difference of each column of ``table`` from ``reference`` over the cycles both
    hold (NaN where a value is NaN; 0.0 for no common cycle)."""
    n = min(len(table), len(reference))
    out = {}
    for name in COLUMNS:
        gaps = _relative(getattr(table, name)[:n], getattr(reference, name)[:n])
        out[name] = float(np.max(gaps)) if n else 0.0
    return out


def cross_check(run: CycleRun, rtol: float = CROSS_CHECK_RTOL) -> dict[str, float]:
    """Compare ``run`` with :func:`~escapement.solvers.exact.solve_exact` for the same arguments: the same
    outcome and number of cycles, and every quantity of every cycle (and ``t_final``) within ``rtol``
    (relative). Returns the largest relative difference of each; raises :class:`CrossCheckError` naming the
    quantity, the cycle and both values otherwise."""
    exact = solve_exact(run.params, run.x0, run.v0, n_cycles=run.n_cycles, record_trajectory=False)
    if exact.status is not run.status or len(exact.cycles) != len(run.cycles):
        raise CrossCheckError(f"{run.method}: {run.status.value} after {len(run.cycles)} cycles, but solve_exact: "
                              f"{exact.status.value} after {len(exact.cycles)} cycles ({exact.message})")
    gaps = compare_tables(run.cycles, exact.cycles)
    gaps["t_final"] = float(_relative(run.t_final, exact.t_final))
    for name, gap in gaps.items():
        if not gap <= rtol:
            if name == "t_final":
                where, mine, theirs = "t_final", run.t_final, exact.t_final
            else:
                column, reference = getattr(run.cycles, name), getattr(exact.cycles, name)
                each = _relative(column, reference)
                i = int(np.argmax(np.where(np.isnan(each), np.inf, each)))
                where, mine, theirs = f"{name} of cycle {i + 1}", column[i], reference[i]
            raise CrossCheckError(f"{run.method} and solve_exact disagree on the {where}: {float(mine)!r} against "
                                  f"{float(theirs)!r}, a relative difference of {compared(gap, [rtol], 3)} "
                                  f"> rtol = {float(rtol)!r}")
    return gaps
