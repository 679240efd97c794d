"""Per-cycle closed forms: :func:`~escapement.solvers.exact.solve_exact`'s cycle table from the return map of ``v**2``,
or from the event solver where they do not apply. They agree within 1e-14 down to ``b`` of about 0.015 (below, the event
solver's rounding grows as ``eps / b``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.cycle_map import CycleMap, cycle_map
from ..model.limits import run_spec
from ..model.parameters import Parameters
from ..model.printing import compared
from ..model.status import Status
from .closed_form import Cycles, closed_form_cycles, table_rows
from .describe import CYCLE_COLUMNS, CycleTable, Exit
from .exact import solve_exact
from .kernel import PLAN
from .result import Ended, Solution
from .stream import CHUNK_BYTES_PER_CYCLE, DEFAULT_CHUNK, ChunkIterator, CycleStream, StreamSummary, check_chunk
from .stream import iter_cycles

__all__ = ["CHUNK_BYTES_PER_CYCLE", "CLOSED_FORM", "CROSS_CHECK_RTOL", "PEAK_BYTES_PER_CYCLE", "CrossCheckError",
           "CycleChunks", "CycleRun", "compare_tables", "cross_check", "iter_closed_form_cycles", "solve_cycles"]

CLOSED_FORM = "closed-form cycles"
#: the relative difference :func:`cross_check` accepts on every quantity
CROSS_CHECK_RTOL = 1e-14
#: bytes per cycle at the peak of a run whose every cycle is distinct (the transient's arcs and work arrays,
#: tracemalloc measured 357); a run that reaches the fixed point takes less (its columns, about 100)
PEAK_BYTES_PER_CYCLE = 400


class CrossCheckError(AssertionError):
    """The closed-form cycles and the event solver disagree beyond the tolerance (:func:`cross_check`)."""


@dataclass(frozen=True, repr=False)
class CycleRun(Ended):
    """A run's cycle table by the closed forms, or by the event solver where they do not apply."""

    params: Parameters
    x0: float  #: initial displacement, m
    v0: float  #: initial velocity, m/s
    n_cycles: int  #: the cycles asked for
    status: Status
    message: str
    cycles: CycleTable  #: impact time (s), velocity before impact (m/s), period (s), largest displacement (m)
    t_final: float  #: time of the impact at a1 that ends the last cycle, s
    method: str  #: ``"closed-form cycles"``, or ``"exact"`` on a fallback
    fallback: str | None  #: why the event solver made the run; None where the closed form did
    cycle_map: CycleMap
    #: largest relative difference of the map's ``v_{k+1}`` from the arcs' arrival at a1 from ``v_k`` (or NaN)
    map_residual: float = math.nan
    distinct_cycles: int = 0  #: cycles whose arcs were computed (the rest repeat the fixed point's)
    exit: Exit = Exit()
    solution: Solution | None = None  #: the event solver's run, on a fallback

    def __repr__(self) -> str:
        how = self.method if self.fallback is None else f"{self.method}, fell back: {self.fallback}"
        return (f"<CycleRun> {self.status.value} ({how}): {len(self.cycles)} of {self.n_cycles} cycles, "
                f"t_final = {self.t_final:.6g} s, fixed point {self.cycle_map.fixed_point:.6g} m/s")


def solve_cycles(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int, memory_budget: int | None = None,
                 check: bool = False, rtol: float = CROSS_CHECK_RTOL) -> CycleRun:
    """:func:`~escapement.solvers.exact.solve_exact`'s cycle table for ``n_cycles`` cycles, from the closed forms
    after the event solver's first impact at a1; where they do not apply, ``solve_exact``'s run, and
    :attr:`CycleRun.fallback` says why. With ``check`` the run is compared with ``solve_exact`` within ``rtol``."""
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, memory_budget=memory_budget)
    spec.limits.check_memory(0.0, PEAK_BYTES_PER_CYCLE, "its cycle table and the closed form's work arrays",
                             "stream the cycles in constant memory with escapement.solvers.iter_cycles")
    done = closed_form_cycles(spec)
    p, x, v, n = spec.params, spec.x0, spec.v0, spec.limits.n_cycles
    if isinstance(done, str):
        exact = solve_exact(p, x, v, n_cycles=n, record_trajectory=False, memory_budget=memory_budget)
        run = CycleRun(p, x, v, n, exact.status, exact.message, exact.cycles, exact.t_final, "exact", done,
                       cycle_map(p), exit=exact.exit, solution=exact)
    else:
        table, t_final = table_rows(done, 0, n)
        run = CycleRun(p, x, v, n, Status.COMPLETED, f"completed {n} cycles", table, t_final, CLOSED_FORM, None,
                       cycle_map(p), map_residual=done.residual, distinct_cycles=done.distinct)
    if check:
        cross_check(run, rtol)
    return run


class CycleChunks(ChunkIterator):
    """:func:`solve_cycles`'s cycle table in chunks (see :func:`iter_closed_form_cycles`)."""

    def __init__(self, done: Cycles | str, n: int, chunk: int, fallback: CycleStream | None, cmap: CycleMap) -> None:
        cycles = None if fallback is not None else done
        self._cycles, self._n, self._chunk, self._fallback, self._done = cycles, n, chunk, fallback, 0
        self.method = CLOSED_FORM if cycles else "exact"  #: which solver makes the chunks
        self.fallback = None if cycles else done  #: why the event solver makes the run; None where the closed forms do
        self.cycle_map = cmap
        self.distinct_cycles = 0 if cycles is None else cycles.distinct  #: cycles whose arcs were computed
        self.map_residual = math.nan if cycles is None else cycles.residual  #: as :attr:`CycleRun.map_residual`

    def _progress(self) -> str:
        if self._fallback is not None:
            return f"{self._fallback._progress()} by the event solver (the reason: its fallback attribute)"
        return f"chunks of {self._chunk} cycles by the closed forms, {self._done} of {self._n} handed over"

    def __next__(self) -> CycleTable:
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
        self._done = stop
        if stop == self._n:  # a cycle is the events of the automaton's cycle plan
            self._summary = StreamSummary(Status.COMPLETED, f"completed {self._n} cycles", Exit(), t_end, self._n,
                                          self._cycles.events_before + len(PLAN) * self._n)
        return table


def iter_closed_form_cycles(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int,
                            chunk: int = DEFAULT_CHUNK, memory_budget: int | None = None) -> CycleChunks:
    """:func:`solve_cycles`'s cycle table in chunks of at most ``chunk`` cycles, number for number, in memory that
    does not grow with the run; where the transient does not fit the memory budget or the closed form does not
    apply, :func:`~escapement.solvers.stream.iter_cycles`'s, and :attr:`CycleChunks.fallback` says why."""
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, memory_budget=memory_budget)
    chunk, chunk_bytes = check_chunk(chunk, spec.limits.memory_budget)
    done = closed_form_cycles(spec, most=(spec.limits.memory_budget - chunk_bytes) // PEAK_BYTES_PER_CYCLE)
    n, cmap = spec.limits.n_cycles, cycle_map(spec.params)
    stream = iter_cycles(spec.params, spec.x0, spec.v0, n_cycles=n, chunk=chunk, memory_budget=memory_budget) \
        if isinstance(done, str) else None
    return CycleChunks(done, n, chunk, stream, cmap)


def _relative(a, b) -> np.ndarray:
    """``|a - b| / |b|`` elementwise (0 where both are 0, inf where only ``b`` is; NaN stays NaN)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a == b, 0.0, np.where(b != 0.0, np.abs(a - b) / np.abs(b), np.inf))


def compare_tables(table: CycleTable, reference: CycleTable) -> dict[str, float]:
    """The largest relative difference of each column from ``reference``'s over the cycles both hold."""
    n = min(len(table), len(reference))
    return {name: float(np.max(_relative(getattr(table, name)[:n], getattr(reference, name)[:n]))) if n else 0.0
            for name in CYCLE_COLUMNS}


def cross_check(run: CycleRun, rtol: float = CROSS_CHECK_RTOL) -> dict[str, float]:
    """The largest relative difference from :func:`~escapement.solvers.exact.solve_exact`'s run of each quantity;
    :class:`CrossCheckError` names the quantity, cycle and values where one exceeds ``rtol`` or the outcomes differ."""
    exact = solve_exact(run.params, run.x0, run.v0, n_cycles=run.n_cycles, record_trajectory=False)
    if exact.status is not run.status or len(exact.cycles) != len(run.cycles):
        raise CrossCheckError(f"{run.method}: {run.status.value} after {len(run.cycles)} cycles, but solve_exact: "
                              f"{exact.status.value} after {len(exact.cycles)} cycles ({exact.message})")
    gaps = compare_tables(run.cycles, exact.cycles)
    gaps["t_final"] = float(_relative(run.t_final, exact.t_final))
    for name, gap in gaps.items():
        if not gap <= rtol:
            where, mine, theirs = "t_final", run.t_final, exact.t_final
            if name != "t_final":
                column, reference = getattr(run.cycles, name), getattr(exact.cycles, name)
                each = _relative(column, reference)
                i = int(np.argmax(np.where(np.isnan(each), np.inf, each)))
                where, mine, theirs = f"{name} of cycle {i + 1}", column[i], reference[i]
            raise CrossCheckError(f"{run.method} and solve_exact disagree on the {where}: {float(mine)!r} against "
                                  f"{float(theirs)!r}, a relative difference of {compared(gap, [rtol], 3)} "
                                  f"> rtol = {float(rtol)!r}")
    return gaps
