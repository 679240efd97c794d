"""The exact solver's cycles in chunks: the same numbers as solve_exact, the same ending (their memory:
test_memory.py)."""

from __future__ import annotations

import numpy as np
import pytest

from escapement.model.limits import MemoryBudgetError
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers import iter_cycles, solve_exact

PAPER_A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
PAPER_B = Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05)
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")


def _joined(chunks, name: str) -> bytes:
    return np.concatenate([getattr(c, name) for c in chunks]).tobytes() if chunks else b""


@pytest.mark.parametrize("chunk", [1, 7, 1024, 1_000_000])  # 1024 cycles: a pass of the loop holds 4096 events
@pytest.mark.parametrize("params, x0", [(PAPER_A, 1.0), (PAPER_B, 3.0), (ASYMMETRIC, -0.8)])
def test_the_chunks_put_together_are_the_cycles_of_solve_exact_bit_for_bit(params, x0, chunk):
    whole = solve_exact(params, x0, n_cycles=3_000, record_trajectory=False)
    stream = iter_cycles(params, x0, n_cycles=3_000, chunk=chunk)
    chunks = list(stream)
    assert [len(c) for c in chunks] == [min(chunk, 3_000 - i) for i in range(0, 3_000, chunk)]
    for name in COLUMNS:
        assert _joined(chunks, name) == getattr(whole.cycles, name).tobytes(), name
    s = stream.summary
    assert (s.status, s.message, s.t_final, s.n_cycles, s.n_events) == (
        whole.status, whole.message, whole.t_final, len(whole.cycles), len(whole.events))
    assert s.success


@pytest.mark.parametrize("params, x0, limits, status", [
    (PAPER_A, 0.05, dict(n_cycles=10), Status.STOPPED),  # below a1 and a3: no impact
    (Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0), 1.0, dict(n_cycles=100),
     Status.STOPPED),  # no force: the swings decay below a3
    (Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.1, a2=0.5), 1.0, dict(n_cycles=20), Status.TURNED_BACK_IN_ZONE),
    (Parameters(M=1.0, K=1.0, F=1.0, b=1.5, a1=-0.1, a2=0.05), 1.0, dict(n_cycles=5), Status.CHATTERING),
    (PAPER_B, 3.0, dict(t_end=87.0), Status.COMPLETED),
    (PAPER_A, 1.0, dict(n_cycles=50, max_events=33), Status.EVENT_LIMIT),
])
def test_a_stream_ends_as_solve_exact_does(params, x0, limits, status):
    whole = solve_exact(params, x0, record_trajectory=False, **limits)
    stream = iter_cycles(params, x0, chunk=3, **limits)
    chunks = list(stream)
    s = stream.summary
    assert s.status == whole.status == status
    assert (s.message, s.t_final, s.n_cycles, s.n_events) == (whole.message, whole.t_final, len(whole.cycles),
                                                               len(whole.events))
    assert np.array_equal([s.exit.turning_point, s.exit.margin, s.exit.t_accumulation],
                          [whole.exit.turning_point, whole.exit.margin, whole.exit.t_accumulation], equal_nan=True)
    for name in COLUMNS:
        assert _joined(chunks, name) == getattr(whole.cycles, name).tobytes(), name


def test_the_summary_comes_once_the_stream_is_exhausted():
    stream = iter_cycles(PAPER_A, 1.0, n_cycles=10, chunk=4)
    assert len(next(stream)) == 4
    with pytest.raises(RuntimeError, match="not exhausted"):
        stream.summary  # noqa: B018
    assert [len(c) for c in stream] == [4, 2]
    assert stream.summary.n_cycles == 10 and stream.summary.status == Status.COMPLETED
    with pytest.raises(StopIteration):
        next(stream)


def test_a_run_of_a_billion_cycles_is_streamed_without_refusal():
    stream = iter_cycles(PAPER_A, 1.0, n_cycles=10**9, chunk=1000)
    first = next(stream)
    assert len(first) == 1000
    with pytest.raises(MemoryBudgetError):
        solve_exact(PAPER_A, 1.0, n_cycles=10**9, record_trajectory=False)
