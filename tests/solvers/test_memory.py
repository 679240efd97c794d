"""The memory budget: a run whose result would not fit is refused before any work, with the estimate,
the budget and what to do instead; the estimates bound what the solvers really allocate."""

from __future__ import annotations

import gc
import re
import time
import tracemalloc

import numpy as np
import pytest

from escapement.model.limits import MAX_MEMORY_BUDGET, MEMORY_BUDGET, MemoryBudgetError, RunLimits
from escapement.model.parameters import ParameterError, Parameters
from escapement.solvers import exact
from escapement.solvers.driver import check_memory
from escapement.solvers.ensemble import MAX_CELLS, ensemble_bytes, solve_ensemble
from escapement.solvers.exact import solve_exact, solve_exact_stepwise
from escapement.solvers.high_precision import solve_high_precision
from escapement.solvers.naive import solve_naive
from escapement.solvers.reference import solve_reference

P = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


def _refused(run) -> tuple[MemoryBudgetError, float]:
    start = time.perf_counter()
    with pytest.raises(MemoryBudgetError) as err:
        run()
    return err.value, time.perf_counter() - start


@pytest.mark.parametrize("record", [True, False])
def test_a_billion_cycles_are_refused_within_a_second_with_the_numbers_and_the_way_out(record):
    err, seconds = _refused(lambda: solve_exact(P, 1.0, n_cycles=10**9, record_trajectory=record))
    assert seconds < 1.0
    assert isinstance(err, ParameterError) and (err.name, err.value) == ("n_cycles", 10**9)
    assert err.budget == MEMORY_BUDGET and err.estimate > 100 * MEMORY_BUDGET
    message = str(err)
    assert message.startswith("n_cycles = 1000000000 is invalid: n_cycles must be at most ")
    assert f"{err.estimate:_} bytes" in message and f"{MEMORY_BUDGET:_} bytes" in message
    assert "iter_cycles" in message and "memory_budget" in message
    # per cycle, the bound is the stored output: 4 events of t, x, v_before, v_after, kind, and a cycle row
    per_cycle = err.estimate / 10**9
    assert (4 * 33 + 32 <= per_cycle <= 300) if not record else (4 * 65 + 32 <= per_cycle <= 450)


@pytest.mark.parametrize("solver", ["reference", "high precision", "naive", "stepwise"])
def test_the_solvers_of_the_generic_loop_are_refused_alike(solver):
    run = {"reference": lambda: solve_reference(P, 1.0, n_cycles=10**9, record_trajectory=False),
           "high precision": lambda: solve_high_precision(P, 1.0, n_cycles=10**9),
           "naive": lambda: solve_naive(P, 1.0, n_cycles=10**9, step=1e-3),
           "stepwise": lambda: solve_exact_stepwise(P, 1.0, n_cycles=10**9)}[solver]
    err, seconds = _refused(run)
    assert seconds < 1.0 and (err.name, err.value) == ("n_cycles", 10**9) and err.estimate > err.budget


@pytest.mark.parametrize("record", [True, False])
def test_the_largest_run_the_error_names_fits_and_one_more_does_not(record):
    budget = 1_000_000
    err, _ = _refused(lambda: solve_exact(P, 1.0, n_cycles=10**6, record_trajectory=record, memory_budget=budget))
    most = int(re.search(r"at most ([\d_]+) ", err.requirement).group(1))
    run = solve_exact(P, 1.0, n_cycles=most, record_trajectory=record, memory_budget=budget)
    assert len(run.cycles) == most
    with pytest.raises(MemoryBudgetError):
        solve_exact(P, 1.0, n_cycles=most + 1, record_trajectory=record, memory_budget=budget)


def test_a_run_to_an_end_time_is_sized_by_max_events():
    err, _ = _refused(lambda: solve_exact(P, 1.0, t_end=1e9, max_events=10**9))
    assert (err.name, err.value) == ("max_events", 10**9)
    run = solve_exact(P, 1.0, t_end=50.0)  # the default bound, 10**7 events, fits
    assert run.success


@pytest.mark.parametrize("budget", [0, -1, 1.5, True, "2e9", 2e9, MAX_MEMORY_BUDGET + 1])
def test_a_bad_memory_budget_is_refused_naming_it(budget):
    for run in (lambda: solve_exact(P, 1.0, n_cycles=5, memory_budget=budget),
                lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, n_cycles=5, memory_budget=budget),
                lambda: RunLimits(n_cycles=5, memory_budget=budget)):
        with pytest.raises(ParameterError) as err:
            run()
        assert (err.value.name, err.value.value) == ("memory_budget", budget)
        assert not isinstance(err.value, MemoryBudgetError)


def test_a_larger_budget_lets_a_larger_run_through():
    with pytest.raises(MemoryBudgetError):
        solve_exact(P, 1.0, n_cycles=20_000, memory_budget=1_000_000)
    assert solve_exact(P, 1.0, n_cycles=20_000, memory_budget=10_000_000).success


def test_the_ensemble_budget_is_in_bytes_and_names_what_to_reduce():
    assert MAX_CELLS * 40 == MEMORY_BUDGET
    err, seconds = _refused(lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(10, 0.05), n_cycles=10**8))
    assert seconds < 1.0 and (err.name, err.value) == ("n_cycles", 10**8)
    assert "at most 4_999_999 for 10 trajectories" in err.requirement and err.estimate == ensemble_bytes(10, 10**8)
    # each trajectory's state counts, however few its cycles: 2.5e7 single cycles were let through by the
    # cell count alone, and would take some 14 GB
    many = np.full(4_000, 0.05)
    err, _ = _refused(lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, many, n_cycles=1, memory_budget=2 * 10**6))
    assert (err.name, err.value) == ("trajectories", 4000) and "at most 2_985 for n_cycles = 1" in err.requirement
    assert ensemble_bytes(25 * 10**6, 1) > 8 * MEMORY_BUDGET and ensemble_bytes(10, 10**8) == 40 * 10 * (10**8 + 1)
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(10, 0.05), n_cycles=2000, memory_budget=10**7)
    assert out.cycles.period.shape == (10, 2000)


def _peak(run) -> tuple[object, int, int]:
    """The result, the bytes it holds and the peak bytes allocated while it was made (tracemalloc)."""
    gc.collect()
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    result = run()
    held, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return result, held - base, peak - base


@pytest.mark.parametrize("record", [False, True])
def test_solve_exact_stays_within_its_estimate_without_a_second_copy(record):
    n = 20_000
    estimate = check_memory(RunLimits(n_cycles=n), exact.EVENT_BYTES + exact.ARC_BYTES * record, exact.CYCLE_BYTES,
                            "", "", fixed_bytes=exact.PASS_BYTES)
    run, held, peak = _peak(lambda: solve_exact(P, 1.0, n_cycles=n, record_trajectory=record))
    stored = sum(getattr(run.events, c).nbytes for c in ("t", "kind", "x", "v_before", "v_after")) + sum(
        getattr(run.cycles, c).nbytes for c in ("impact_time", "velocity_before_impact", "period", "amplitude"))
    if record:
        stored += sum(getattr(run.trajectory, c).nbytes for c in ("t_start", "centre", "x_start", "v_start"))
    assert stored <= held < 1.1 * stored  # the result, its buffers packed
    assert peak < 1.25 * held  # no second copy of the result at the end
    assert 0.6 * estimate < peak <= estimate


@pytest.mark.parametrize("record", [False, True])
def test_the_generic_loop_stays_within_its_estimate(record):
    n = 8_000
    stepper_bytes = 34 if record else 0
    estimate = check_memory(RunLimits(n_cycles=n), 40 + stepper_bytes, 40, "", "")
    _, held, peak = _peak(lambda: solve_exact_stepwise(P, 1.0, n_cycles=n, record_trajectory=record))
    assert peak < 1.25 * held and 0.6 * estimate < peak <= estimate


def test_the_high_precision_solver_stays_within_its_estimate():
    limits = RunLimits(n_cycles=100)
    _, _, peak = _peak(lambda: solve_high_precision(P, 1.0, n_cycles=100, dps=50))
    with pytest.raises(MemoryBudgetError) as err:
        solve_high_precision(P, 1.0, n_cycles=10**7, dps=50)
    per_cycle = err.value.estimate / 10**7  # the estimate is linear in the cycles
    # 100 cycles take at most events_for(100) = 4 * 104 events: within 104 cycles of the linear estimate
    assert 0.6 * per_cycle * limits.n_cycles < peak <= per_cycle * (limits.n_cycles + 4)


@pytest.mark.parametrize("n, n_cycles", [(300, 1000), (20_000, 1), (2000, 60)])
def test_the_ensemble_stays_within_its_estimate(n, n_cycles):
    _, _, peak = _peak(lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(n, 0.05), n_cycles=n_cycles))
    assert peak <= ensemble_bytes(n, n_cycles)
