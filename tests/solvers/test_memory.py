"""The memory budget: a run whose result would not fit is refused before any work, with the estimate, the budget
and what to do instead; the most the refusal names fits and one more does not; and each solver's estimate bounds
its peak (tracemalloc) without being more than twice that. Measured (the paper's case (a), NumPy 2, CPython 3.11):
solve_exact 110 bytes an event at its peak, the result holding 42 (73 with the arcs); iter_cycles about 90 a cycle
of a chunk and 0.5 MB for a block; solve_cycles 283 a cycle where each is distinct; solve_ensemble 40 a cell and
700 a trajectory; the integrators' loop 48 to 81 an event, the reference's dense output 6_400 an event.
"""

from __future__ import annotations

import gc
import re
import tracemalloc
from unittest import mock

import numpy as np
import pytest

from escapement.integrators import driver
from escapement.integrators.high_precision import solve_high_precision
from escapement.integrators.naive import solve_naive
from escapement.integrators.reference import solve_reference
from escapement.model.limits import MEMORY_BUDGET, MemoryBudgetError, RunLimits
from escapement.model.parameters import ParameterError, Parameters
from escapement.solvers import cycles as cyc
from escapement.solvers import exact, stream
from escapement.solvers.ensemble import ensemble_bytes, solve_ensemble
from escapement.solvers.exact import solve_exact

P = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


def _refused(run) -> MemoryBudgetError:
    with pytest.raises(MemoryBudgetError) as err:
        run()
    return err.value


@pytest.mark.parametrize("solver", ["exact", "exact without its trajectory", "reference", "high precision", "naive"])
def test_a_billion_cycles_are_refused_before_any_work_with_the_numbers_and_the_way_out(solver):
    run = {"exact": lambda: solve_exact(P, 1.0, n_cycles=10**9),
           "exact without its trajectory": lambda: solve_exact(P, 1.0, n_cycles=10**9, record_trajectory=False),
           "reference": lambda: solve_reference(P, 1.0, n_cycles=10**9, record_trajectory=False),
           "high precision": lambda: solve_high_precision(P, 1.0, n_cycles=10**9),
           "naive": lambda: solve_naive(P, 1.0, n_cycles=10**9, step=1e-3)}[solver]
    with mock.patch.object(exact, "EventRun", wraps=exact.EventRun) as loop, mock.patch.object(driver, "finish") as end:
        err = _refused(run)
    assert not loop.called and not end.called and err.estimate > err.budget
    assert isinstance(err, ParameterError) and (err.name, err.value) == ("n_cycles", 10**9)
    if solver.startswith("exact"):
        assert err.budget == MEMORY_BUDGET and err.estimate > 100 * MEMORY_BUDGET
        assert str(err).startswith("n_cycles = 1000000000 is invalid: n_cycles must be at most ")
        assert f"{err.estimate:_} bytes" in str(err) and f"{MEMORY_BUDGET:_} bytes (2 GB)" in str(err)
        assert "iter_cycles" in str(err) and "memory_budget" in str(err)
        assert ("record_trajectory=False" in str(err)) == (solver == "exact")


#: runs whose refusal names a count: the run for a value of it, the budget, the count's name
RUNS = [
    (lambda n, budget: solve_exact(P, 1.0, n_cycles=n, memory_budget=budget), 1_000_000, "n_cycles"),
    (lambda n, budget: solve_exact(P, 1.0, n_cycles=n, record_trajectory=False, memory_budget=budget), 1_000_000,
     "n_cycles"),
    (lambda n, budget: solve_exact(P, 1.0, t_end=1e9, max_events=n, memory_budget=budget), 1_000_000, "max_events"),
    (lambda n, budget: cyc.solve_cycles(P, 1.0, n_cycles=n, memory_budget=budget), 100_000, "n_cycles"),
    (lambda n, budget: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, [0.05] * 3, n_cycles=n, memory_budget=budget),
     100_000, "n_cycles"),
    (lambda n, budget: solve_ensemble(1.0, 1.0, np.full(n, 1.0), 0.1, -0.1, 0.05, n_cycles=10, memory_budget=budget),
     1_000_000, "trajectories"),
    (lambda n, budget: stream.iter_cycles(P, 1.0, n_cycles=5, chunk=n, memory_budget=budget), 1_000_000, "chunk"),
]


@pytest.mark.parametrize("run, budget, name", RUNS, ids=[f"{i}-{name}" for i, (_, _, name) in enumerate(RUNS)])
def test_the_largest_run_the_error_names_fits_and_one_more_does_not(run, budget, name):
    err = _refused(lambda: run(10**6, budget))
    most = int(re.search(r"at most ([\d_]+) for the run", err.requirement).group(1))
    assert err.name == name and 1 <= most < 10**6
    run(most, budget)
    with pytest.raises(MemoryBudgetError):
        run(most + 1, budget)


@pytest.mark.parametrize("run", [
    lambda budget: solve_exact(P, 1.0, n_cycles=1, memory_budget=budget),
    lambda budget: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, n_cycles=1, memory_budget=budget),
])
def test_a_budget_too_small_for_the_smallest_run_is_named_as_the_budget(run):
    err = _refused(lambda: run(10))
    least = int(re.search(r"must be at least ([\d_]+) bytes", str(err)).group(1))
    assert (err.name, err.value) == ("memory_budget", 10) and str(err).startswith("memory_budget = 10 is invalid")
    run(least)
    with pytest.raises(MemoryBudgetError):
        run(least - 1)


# --- the estimates against the measured peaks ---------------------------------------------------------


def _peak(run) -> tuple[object, int, int]:
    """The result, the bytes it holds and the peak bytes allocated while it was made (tracemalloc)."""
    gc.collect()
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    result = run()
    held, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return result, held - base, peak - base


def _estimate_of(run, n_cycles: int) -> float:
    """A solver's estimate for ``n_cycles`` cycles, linear, from its refusals of two runs too large to fit."""
    large, larger = (_refused(lambda cycles=cycles: run(cycles)).estimate for cycles in (5 * 10**8, 10**9))
    per_cycle = (larger - large) / (10**9 - 5 * 10**8)
    return larger - per_cycle * (10**9 - n_cycles)


def _bounds(estimate: float, peak: int) -> None:
    assert peak <= estimate <= 2.0 * peak, (estimate, peak, estimate / peak)  # at most twice the measured peak


@pytest.mark.parametrize("record", [False, True])
def test_solve_exact_stays_within_its_estimate_and_holds_its_columns_alone(record):
    """10_000 cycles: the columns, linear in the cycles, outweigh the rest from about a thousand cycles on."""
    run, held, peak = _peak(lambda: solve_exact(P, 1.0, n_cycles=10_000, record_trajectory=record))
    stored = sum(getattr(run.events, c).nbytes for c in ("t", "kind", "x", "v_before", "v_after")) + sum(
        a.nbytes for a in vars(run.cycles).values())
    if record:
        stored += sum(getattr(run.trajectory, c).nbytes for c in ("t_start", "centre", "x_start", "v_start"))
    assert stored <= held < 1.1 * stored  # the result holds its columns and nothing more
    _bounds(_estimate_of(lambda n: solve_exact(P, 1.0, n_cycles=n, record_trajectory=record), 10_000), peak)


def test_a_run_to_an_end_time_stays_within_the_estimate_of_its_event_bound():
    events = len(solve_exact(P, 1.0, t_end=40_000.0, record_trajectory=False).events)
    run, _, peak = _peak(lambda: solve_exact(P, 1.0, t_end=40_000.0, max_events=events + 1))
    assert run.success and len(run.events) == events
    estimate = RunLimits(t_end=40_000.0, max_events=events + 1).check_memory(
        exact.EVENT_BYTES + exact.ARC_BYTES, exact.CYCLE_BYTES, "", "", fixed_bytes=exact.PASS_BYTES)
    _bounds(estimate, peak)


def test_a_streamed_run_takes_the_memory_of_a_chunk_whatever_its_length():
    """A chunk's budget bounds the stream's peak (the chunk built, the one held, a block of the loop, the chunk large
    enough for its cycles to outweigh the block); five times the cycles take no more memory."""
    _, _, peak = _peak(lambda: [None for _ in stream.iter_cycles(P, 1.0, n_cycles=10_500, chunk=10_000)])
    _bounds(10_000 * stream.CHUNK_BYTES_PER_CYCLE, peak)
    short, long = (_peak(lambda n=n: [None for _ in stream.iter_cycles(P, 1.0, n_cycles=n, chunk=500)])[2]
                   for n in (1_500, 7_500))
    assert long <= 1.5 * short, (short, long)


def test_the_closed_forms_stay_within_their_estimates():
    """Where every cycle is distinct (b = 1e-3: a transient of some 9_500 cycles) and in a streamed chunk."""
    p = Parameters(M=1.0, K=1.0, F=1.0, b=1e-3, a1=-0.1, a2=0.05)
    run, _, peak = _peak(lambda: cyc.solve_cycles(p, 1.0, n_cycles=9_000))
    assert run.method == cyc.CLOSED_FORM and run.distinct_cycles == 9_000
    _bounds(9_000 * cyc.PEAK_BYTES_PER_CYCLE, peak)
    _, _, peak = _peak(lambda: [None for _ in cyc.iter_closed_form_cycles(P, 1.0, n_cycles=30_000, chunk=10_000)])
    _bounds(10_000 * cyc.CHUNK_BYTES_PER_CYCLE, peak)


#: long and narrow, large, wide and short: the cells (48 bytes) outweigh a trajectory's state (1000) from some
#: hundred cycles on
@pytest.mark.parametrize("n, n_cycles", [(10, 500), (100, 300), (20_000, 1)])
def test_the_ensemble_stays_within_its_estimate(n, n_cycles):
    _, _, peak = _peak(lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(n, 0.05), n_cycles=n_cycles))
    _bounds(ensemble_bytes(n, n_cycles), peak)


@pytest.mark.parametrize("solver", ["high precision", "naive", "reference", "reference without its trajectory"])
def test_the_integrators_stay_within_their_estimates(solver):
    """Enough cycles for the events to outweigh the loop's fixed part (the reference's dense output: 7 kB an event)."""
    run = {"high precision": lambda n: solve_high_precision(P, 1.0, n_cycles=n, dps=30),
           "naive": lambda n: solve_naive(P, 1.0, n_cycles=n, step=0.1),
           "reference": lambda n: solve_reference(P, 1.0, n_cycles=n),
           "reference without its trajectory": lambda n: solve_reference(P, 1.0, n_cycles=n, record_trajectory=False),
           }[solver]
    n = {"high precision": 50, "naive": 200}.get(solver, 15)
    run(5)  # SciPy's caches, filled once per process
    _, _, peak = _peak(lambda: run(n))
    _bounds(_estimate_of(run, n + 4), peak)  # n cycles take at most events_for(n): the events of n + 4 cycles
