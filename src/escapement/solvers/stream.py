"""The exact solver's cycles in chunks, in constant memory (:func:`iter_cycles`), ``solve_exact``'s number for
number."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..model.limits import check_budget, check_count, run_spec
from ..model.parameters import Parameters
from ..model.status import Status
from .describe import CycleTable, Exit
from .kernel import BLOCK_EVENTS, EventRun, event_block
from .result import Ended

__all__ = ["CHUNK_BYTES_PER_CYCLE", "DEFAULT_CHUNK", "MAX_CHUNK", "ChunkIterator", "CycleStream", "StreamSummary",
           "check_chunk", "iter_cycles"]

DEFAULT_CHUNK = 100_000
MAX_CHUNK = 10_000_000
#: bytes a cycle of a chunk takes: its four floats, and the parts gathered before they are joined (the closed
#: forms' chunks take as much: their rows and the impact times' work arrays)
CHUNK_BYTES_PER_CYCLE = 128


@dataclass(frozen=True)
class StreamSummary(Ended):
    """How a streamed run ended: the fields of a Solution that do not grow with the run."""

    status: Status
    message: str
    exit: Exit
    t_final: float
    n_cycles: int  #: complete cycles handed over, all chunks together
    n_events: int  #: events of the run


class ChunkIterator(Iterator[CycleTable]):
    """A run's cycle table chunk by chunk; once exhausted, :attr:`summary` says how it ended."""

    _summary: StreamSummary | None = None

    def __repr__(self) -> str:
        ended = "" if self._summary is None else f"; ended {self._summary.status.value}"
        return f"<{type(self).__name__}> {self._progress()}{ended}"

    @property
    def summary(self) -> StreamSummary:
        """How the run ended; available once the stream is exhausted."""
        if self._summary is None:
            raise RuntimeError("the stream is not exhausted yet: iterate over it to the end first")
        return self._summary


class CycleStream(ChunkIterator):
    """The per-cycle table of one run of the event loop, chunk by chunk (see :func:`iter_cycles`)."""

    def __init__(self, run: EventRun, chunk: int) -> None:
        self._run, self._chunk = run, chunk
        self._cycles = 0  # complete cycles handed over
        self._carry: tuple | None = None  # the events from the impact at a1 that begins the cycle under way
        self._ready: list[tuple[np.ndarray, ...]] = []  # cycles derived, not yet handed over

    def _progress(self) -> str:
        return f"chunks of {self._chunk} cycles, {self._cycles} handed over"

    def __next__(self) -> CycleTable:
        run = self._run
        while sum(len(part[0]) for part in self._ready) < self._chunk and run.outcome is None:
            run.advance(BLOCK_EVENTS)
            self._derive(run.take())
        if not self._ready:
            if self._summary is None:
                outcome = run.outcome
                self._summary = StreamSummary(outcome.status, outcome.message, outcome.exit,
                                              float(outcome.t_final), self._cycles, run.events)
            raise StopIteration
        columns = [np.concatenate(parts) for parts in zip(*self._ready)]
        rest = [column[self._chunk:] for column in columns]
        self._ready = [tuple(rest)] if len(rest[0]) else []
        head = CycleTable(*(column[:self._chunk] for column in columns))
        self._cycles += len(head)
        return head

    def _derive(self, stored: tuple[np.ndarray, np.ndarray, np.ndarray]) -> None:
        """The cycles a block completes, after the events of the cycle under way carried from the last block."""
        start, before, carried = self._carry or (0, self._run.release, None)
        columns = tuple(np.concatenate(pair) for pair in zip(carried, stored)) if carried else stored
        block = event_block(self._run, start, *columns, before=before)
        if len(block.cycles[0]):
            self._ready.append(block.cycles)
        if block.begins:  # the state after the event before the impact at a1 that begins the cycle under way
            before = (int(block.kind[block.begins - 1]), block.arc_x[block.begins], block.arc_v[block.begins])
        self._carry = (start + block.begins, before, tuple(column[block.begins:].copy() for column in columns))


def iter_cycles(params: Parameters, x0: float, v0: float = 0.0, *, n_cycles: int | None = None,
                t_end: float | None = None, max_events: int | None = None, chunk: int = DEFAULT_CHUNK,
                memory_budget: int | None = None) -> CycleStream:
    """:func:`~escapement.solvers.exact.solve_exact`'s cycle table for the same arguments, in chunks of at most
    ``chunk`` cycles, in memory that does not grow with the run; :attr:`CycleStream.summary` says how it ended.

    Parameters
    ----------
    params : Parameters
        The model's parameters.
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int, optional
        Complete cycles to run; this, ``t_end`` or both.
    t_end : float, optional
        End time, s.
    max_events : int, optional
        Bound on the number of events.
    chunk : int, default 100_000
        The most cycles a chunk holds, at most :data:`MAX_CHUNK`.
    memory_budget : int, optional
        The most bytes a chunk may take, :data:`CHUNK_BYTES_PER_CYCLE` a cycle (default 2 GB).

    Returns
    -------
    CycleStream
        An iterator of :class:`~escapement.solvers.result.CycleTable` chunks; the run goes on as it is iterated.

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
    spec = run_spec(params, x0, v0, n_cycles=n_cycles, t_end=t_end, max_events=max_events, memory_budget=memory_budget,
                    choices=True)
    chunk, _ = check_chunk(chunk, spec.limits.memory_budget)
    return CycleStream(EventRun(spec), chunk)


def check_chunk(chunk: int, memory_budget: int) -> tuple[int, int]:
    """``chunk`` checked, and the bytes a chunk of it takes, within ``memory_budget``."""
    chunk = check_count("chunk", chunk, MAX_CHUNK)
    return chunk, check_budget(memory_budget, f"chunks of {CHUNK_BYTES_PER_CYCLE} bytes a cycle",
                               [("chunk", chunk, lambda n: n * CHUNK_BYTES_PER_CYCLE)])
