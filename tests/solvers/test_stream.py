"""The exact solver's cycles in chunks: the same numbers as solve_exact, the same ending, constant memory."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from escapement.model.limits import MemoryBudgetError
from escapement.model.parameters import ParameterError, Parameters
from escapement.model.status import Status
from escapement.solvers import iter_cycles, solve_exact
from escapement.solvers.stream import CHUNK_BYTES_PER_CYCLE, MAX_CHUNK

PAPER_A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
PAPER_B = Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05)
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")


def _joined(chunks, name: str) -> bytes:
    return np.concatenate([getattr(c, name) for c in chunks]).tobytes() if chunks else b""


@pytest.mark.parametrize("chunk", [1, 7, 4096, 10_000, 1_000_000])
@pytest.mark.parametrize("params, x0", [(PAPER_A, 1.0), (PAPER_B, 3.0), (ASYMMETRIC, -0.8)])
def test_the_chunks_put_together_are_the_cycles_of_solve_exact_bit_for_bit(params, x0, chunk):
    whole = solve_exact(params, x0, n_cycles=10_000, record_trajectory=False)
    stream = iter_cycles(params, x0, n_cycles=10_000, chunk=chunk)
    chunks = list(stream)
    assert [len(c) for c in chunks] == [min(chunk, 10_000 - i) for i in range(0, 10_000, chunk)]
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


@pytest.mark.parametrize("chunk", [0, -1, 1.5, True, "100", MAX_CHUNK + 1])
def test_a_bad_chunk_is_refused_naming_it(chunk):
    with pytest.raises(ParameterError) as err:
        iter_cycles(PAPER_A, 1.0, n_cycles=10, chunk=chunk)
    assert (err.value.name, err.value.value) == ("chunk", chunk)


def test_a_chunk_over_the_memory_budget_is_refused():
    with pytest.raises(MemoryBudgetError) as err:
        iter_cycles(PAPER_A, 1.0, n_cycles=10, chunk=1000, memory_budget=1000 * CHUNK_BYTES_PER_CYCLE - 1)
    assert err.value.name == "chunk" and err.value.estimate == 1000 * CHUNK_BYTES_PER_CYCLE
    assert f"at most {999:_}" in err.value.requirement


def test_a_run_of_a_billion_cycles_is_streamed_without_refusal():
    stream = iter_cycles(PAPER_A, 1.0, n_cycles=10**9, chunk=1000)
    first = next(stream)
    assert len(first) == 1000
    with pytest.raises(MemoryBudgetError):
        solve_exact(PAPER_A, 1.0, n_cycles=10**9, record_trajectory=False)


_STREAM_RUN = """
import resource, sys
from escapement.model.parameters import Parameters
from escapement.solvers import iter_cycles
p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
largest = max(float(chunk.largest_displacement.max()) for chunk in iter_cycles(p, 1.0, n_cycles=int(sys.argv[1])))
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, largest)
"""


def _peak_rss_kb(n_cycles: int) -> int:
    """Peak resident memory (kB) of a process that streams ``n_cycles`` cycles and reduces each chunk."""
    out = subprocess.run([sys.executable, "-c", _STREAM_RUN, str(n_cycles)], capture_output=True, text=True,
                         check=True, timeout=300)
    rss, largest = out.stdout.split()
    assert float(largest) > 0.1
    return int(rss)


def test_the_memory_of_a_stream_does_not_grow_with_its_length():
    # 500_000 cycles more would hold 16 MB more of cycle table alone, and 88 MB more in solve_exact: either is
    # above the 10 MB allowed for the noise of the resident memory
    short, long = _peak_rss_kb(100_000), _peak_rss_kb(600_000)
    assert long - short < 10_000, (short, long)
