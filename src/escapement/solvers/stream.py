"""The exact solver's cycles in chunks, in constant memory.

:func:`iter_cycles` runs the event loop of :func:`escapement.solvers.exact.solve_exact`
(:class:`~escapement.solvers.kernel.EventRun`) in passes of :data:`PASS_EVENTS` events, derives each
pass's cycles as ``solve_exact`` does, and hands the per-cycle table over in chunks of at most ``chunk``
cycles: the loop's state and the events of the cycle under way carry over from pass to pass, so the
chunks put together are, number for number, the ``cycles`` of ``solve_exact`` for the same run.
Memory holds one pass and one chunk at a time, whatever the number of cycles::

    stream = iter_cycles(params, 1.0, n_cycles=10**8)
    for chunk in stream:  # CycleTable, at most 100_000 cycles each
        ...
    stream.summary.status, stream.summary.message  # how the run ended, as solve_exact says it
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..model.limits import check_budget, check_count, run_spec
from ..model.parameters import Parameters
from ..model.status import Status
from .describe import CycleTable, Exit
from .kernel import Block, EventRun, cycle_rows, event_block
from .result import Ended

__all__ = ["CHUNK_BYTES_PER_CYCLE", "DEFAULT_CHUNK", "MAX_CHUNK", "PASS_EVENTS", "ChunkIterator", "CycleStream",
           "StreamSummary", "check_chunk", "iter_cycles"]

#: cycles per chunk unless the caller says otherwise
DEFAULT_CHUNK = 100_000
#: the most cycles a chunk may hold
MAX_CHUNK = 10_000_000
#: bytes a cycle of a chunk takes: its four floats, and the parts of a chunk gathered before they are joined (the
#: closed forms' chunks take as much: their rows and the impact times' work arrays)
CHUNK_BYTES_PER_CYCLE = 128
#: events per pass of the loop (about 0.5 MB of derived arrays each)
PASS_EVENTS = 1 << 12


@dataclass(frozen=True)
class StreamSummary(Ended):
    """How a streamed run ended: the fields of :class:`~escapement.solvers.result.Solution` that do not
    grow with the run."""

    status: Status
    message: str
    exit: Exit
    t_final: float
    n_cycles: int  #: complete cycles handed over, all chunks together
    n_events: int  #: events of the run


class ChunkIterator(Iterator[CycleTable]):
    """A run's per-cycle table, chunk by chunk; once it is exhausted, :attr:`summary` says how the run ended
    (the base of :class:`CycleStream` and of the closed forms' :class:`~escapement.solvers.cycles.CycleChunks`)."""

    _summary: StreamSummary | None = None

    def __iter__(self) -> ChunkIterator:
        """The iterator itself."""
        return self

    def _progress(self) -> str:
        """What has been handed over so far (each kind of stream says it its own way)."""
        raise NotImplementedError

    def __repr__(self) -> str:
        """One line: the chunk size, the cycles handed over and, once exhausted, how the run ended."""
        ended = "" if self._summary is None else f"; ended {self._summary.status.value}"
        return f"<{type(self).__name__}> {self._progress()}{ended}"

    @property
    def summary(self) -> StreamSummary:
        """How the run ended; available once the stream is exhausted."""
        if self._summary is None:
            raise RuntimeError("the stream is not exhausted yet: iterate over it to the end first")
        return self._summary


class CycleStream(ChunkIterator):
    """An iterator over the per-cycle table of one run, chunk by chunk (see :func:`iter_cycles`); once it
    is exhausted, :attr:`summary` says how the run ended."""

    def __init__(self, run: EventRun, chunk: int) -> None:
        self._run = run
        self._chunk = chunk
        self._cycles = 0  # complete cycles handed over
        self._carry: tuple | None = None  # the events from the impact at a1 that begins the cycle under way
        self._ready: list[tuple[np.ndarray, ...]] = []  # cycles derived, not yet handed over
        self._pending = 0

    def _progress(self) -> str:
        return f"chunks of {self._chunk} cycles, {self._cycles} handed over"

    def __next__(self) -> CycleTable:
        """The next chunk of the per-cycle table; :class:`StopIteration` once the run has ended."""
        run = self._run
        while self._pending < self._chunk and run.outcome is None:
            run.advance(PASS_EVENTS)
            self._derive(run.take())
        if not self._pending:
            if self._summary is None:
                outcome = run.outcome
                self._summary = StreamSummary(outcome.status, outcome.message, outcome.exit,
                                              float(outcome.t_final), self._cycles, run.events)
            raise StopIteration
        columns = [np.concatenate(parts) for parts in zip(*self._ready)]
        head = [column[:self._chunk] for column in columns]
        rest = [column[self._chunk:] for column in columns]
        self._ready = [tuple(rest)] if len(rest[0]) else []
        self._pending = len(rest[0])
        self._cycles += len(head[0])
        return CycleTable(*head)

    def _derive(self, stored: tuple[np.ndarray, np.ndarray, np.ndarray]) -> None:
        """The cycles that the events of a pass complete, the events carried over from the last pass first;
        the events from the impact at a1 that begins the cycle under way are carried to the next."""
        run = self._run
        start, before, carried = self._carry or (0, run.release, None)
        columns = stored if carried is None else tuple(np.concatenate(pair) for pair in zip(carried, stored))
        block: Block = event_block(run, start, *columns, before=before)
        cycles, begins = cycle_rows(block)
        if len(cycles[0]):
            self._ready.append(cycles)
            self._pending += len(cycles[0])
        if begins:  # the state after the event before that impact at a1
            before = (int(block.kind[begins - 1]), block.arc_x[begins], block.arc_v[begins])
        self._carry = (start + begins, before, tuple(column[begins:].copy() for column in columns))


def iter_cycles(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                t_end: float | None = None, max_events: int | None = None, chunk: int = DEFAULT_CHUNK,
                memory_budget: int | None = None) -> CycleStream:
    """The per-cycle table of :func:`~escapement.solvers.exact.solve_exact` for the same arguments, in
    chunks of at most ``chunk`` cycles (:class:`~escapement.solvers.result.CycleTable` each), in memory
    that does not grow with the run: no event log, no trajectory, one chunk at a time.

    The limits are those of ``solve_exact``; regime exits end the stream, and its :attr:`CycleStream.summary`
    says how the run ended (status, message, exit, end time). ``chunk`` is at most :data:`MAX_CHUNK`, and a
    chunk's :data:`CHUNK_BYTES_PER_CYCLE` bytes a cycle at most ``memory_budget``.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run; at least one of ``n_cycles`` and ``t_end`` is given.
    t_end : float, optional
        End time, s.
    max_events : int, optional
        Bound on the number of events.
    chunk : int, default 100_000
        The most cycles a chunk holds.
    memory_budget : int, optional
        The most bytes a chunk may take (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    CycleStream
        An iterator of :class:`~escapement.solvers.result.CycleTable` chunks (impact time in s,
        velocity before impact in m/s, period in s, largest displacement in m); the run goes on as it is iterated.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0``, a limit or ``chunk`` is invalid, or
        (:class:`~escapement.model.limits.MemoryBudgetError`) a chunk would exceed ``memory_budget``.

    Examples
    --------
    >>> import numpy as np
    >>> from escapement import Parameters, iter_cycles, solve_exact
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> stream = iter_cycles(p, x0=1.0, n_cycles=250, chunk=100)
    >>> periods = [chunk.period for chunk in stream]  # s
    >>> [len(c) for c in periods], stream.summary.status.value
    ([100, 100, 50], 'completed')
    >>> bool(np.array_equal(np.concatenate(periods), solve_exact(p, x0=1.0, n_cycles=250).cycles.period))
    True
    """
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events,
                    memory_budget=memory_budget)
    chunk, _ = check_chunk(chunk, spec.limits.memory_budget)
    return CycleStream(EventRun(spec), chunk)


def check_chunk(chunk: int, memory_budget: int) -> tuple[int, int]:
    """``chunk`` checked (an integer in [1, :data:`MAX_CHUNK`]) and the bytes a chunk of it takes
    (:data:`CHUNK_BYTES_PER_CYCLE` a cycle), within ``memory_budget``
    (:func:`~escapement.model.limits.check_budget`)."""
    chunk = check_count("chunk", chunk, MAX_CHUNK)
    return chunk, check_budget(memory_budget, f"chunks of {CHUNK_BYTES_PER_CYCLE} bytes a cycle",
                               [("chunk", chunk, lambda n: n * CHUNK_BYTES_PER_CYCLE)])
