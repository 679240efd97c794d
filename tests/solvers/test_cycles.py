"""The per-cycle closed forms (escapement.solvers.cycles) against the event solver, number by number."""

import dataclasses
import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper import corrected
from escapement.solvers import cycles as cyc
from escapement.solvers.cycles import (
    CLOSED_FORM,
    CrossCheckError,
    compare_tables,
    cross_check,
    cycle_map,
    solve_cycles,
)
from escapement.solvers.exact import solve_exact

MODEL = dict(M=1.0, K=1.0, b=0.1, a1=-0.1, a2=0.05, a3=0.1, a4=-0.05)  # Fig. 3
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
#: the configuration's asymmetric geometries (checks.asymmetric.positions)
ASYMMETRIC = [(-0.1, 0.05, 0.2, -0.02), (-0.15, 0.0, 0.08, -0.1), (-0.1, 0.05, 0.3, 0.0)]


def params(**changes) -> Parameters:
    return Parameters(**{**MODEL, "F": 1.0, **changes})


def assert_closed_form_agrees(p: Parameters, x0: float, n: int):
    run = solve_cycles(p, x0, n_cycles=n)
    assert run.method == CLOSED_FORM and run.fallback is None, run.fallback
    assert run.status is Status.COMPLETED and run.message == f"completed {n} cycles" and len(run.cycles) == n
    gaps = cross_check(run, rtol=1e-14)  # raises beyond 1e-14 relative, on every quantity of every cycle
    assert set(gaps) == {*COLUMNS, "t_final"} and max(gaps.values()) <= 1e-14
    assert run.map_residual <= 1e-14
    return run


def assert_same_as_exact(run, p: Parameters, x0: float, n: int):
    exact = solve_exact(p, x0, n_cycles=n, record_trajectory=False)
    assert run.method == "exact" and run.fallback
    assert (run.status, run.message, run.t_final, run.exit) == (exact.status, exact.message, exact.t_final, exact.exit)
    for name in COLUMNS:
        assert np.array_equal(getattr(run.cycles, name), getattr(exact.cycles, name))
    assert run.solution is not None and run.solution.method == "exact"


@pytest.mark.parametrize("n", [50, 1000])
@pytest.mark.parametrize("F, x0", [(1.0, 1.0), (1.0, -1.0), (0.5, 3.0), (0.5, -3.0)])
def test_fig3_cases_agree_with_the_event_solver(F, x0, n):
    assert_closed_form_agrees(params(F=F), x0, n)


@pytest.mark.parametrize("positions", ASYMMETRIC)
@pytest.mark.parametrize("F", [0.5, 1.0, 3.0])
def test_asymmetric_zones_agree_with_the_event_solver(F, positions):
    a1, a2, a3, a4 = positions
    p = params(F=F, a1=a1, a2=a2, a3=a3, a4=a4)
    assert not p.symmetric
    for x0 in (1.0, -1.0):
        assert_closed_form_agrees(p, x0, 300)


@pytest.mark.parametrize("b", [0.05, 1.0])
def test_impact_coefficients_within_the_regime_agree(b):
    for x0 in (1.0, -1.0):
        run = assert_closed_form_agrees(params(b=b), x0, 1000)
    if b == 1.0:  # mu = 0: every cycle after the first is the fixed point's
        assert run.cycle_map.mu == 0.0 and run.distinct_cycles == 2


@pytest.mark.parametrize("b", [1.5, 1.9])
def test_impacts_that_reverse_the_velocity_fall_back_to_the_event_solver(b):
    p = params(b=b)
    for x0 in (1.0, -1.0):
        run = solve_cycles(p, x0, n_cycles=50)
        assert_same_as_exact(run, p, x0, 50)
        assert run.status is Status.CHATTERING and "chatters" in run.fallback and "b = " in run.fallback


@pytest.mark.parametrize("x0, status", [(0.01, Status.STOPPED), (0.05, Status.STOPPED)])
def test_a_run_that_never_reaches_a1_falls_back(x0, status):
    p = params()
    run = solve_cycles(p, x0, n_cycles=20)
    assert_same_as_exact(run, p, x0, 20)
    assert run.status is status and "first cycle" in run.fallback


def test_a_run_that_turns_back_in_a_zone_falls_back():
    p = params(F=0.01, b=1.0, a1=-0.1, a2=0.15, a3=0.1, a4=-0.15)
    run = solve_cycles(p, -1.0, n_cycles=20)
    assert_same_as_exact(run, p, -1.0, 20)
    assert run.status is Status.TURNED_BACK_IN_ZONE


@pytest.mark.parametrize("x0", [1.0, 2.0, -1.0])
def test_a_run_that_stops_after_some_cycles_falls_back_from_the_closed_form(x0):
    # c < 0 (a3**2 < a1**2 and no force): v**2 falls by mu and c each cycle until a swing misses a1
    p = params(F=0.0, a1=-0.5, a2=0.05, a3=0.05, a4=-0.05)
    assert cycle_map(p).c < 0.0
    run = solve_cycles(p, x0, n_cycles=200)
    assert_same_as_exact(run, p, x0, 200)
    assert run.status is Status.STOPPED and 0 < len(run.cycles) < 200
    assert "the free swing a4 -> a1" in run.fallback and "cannot reach its end" in run.fallback


def test_a_grazing_cycle_falls_back_though_the_event_solver_completes():
    # without force the velocity decays to 0: the swing from a4 arrives at a1 ever closer to its turning point
    p = params(F=0.0)
    run = solve_cycles(p, 1.0, n_cycles=300)
    assert_same_as_exact(run, p, 1.0, 300)
    assert run.status is Status.COMPLETED and "grazes its end" in run.fallback


def test_the_fixed_point_is_the_corrected_papers():
    for p in (params(), params(F=0.5), params(b=0.05), params(F=3.0, a1=-0.1, a2=0.05, a3=0.3, a4=0.0)):
        m = cycle_map(p)
        assert m.mu == pytest.approx((1 - p.b) ** 4, rel=1e-15)
        assert m.c == pytest.approx(corrected.map_constant(p), rel=1e-14)
        assert m.fixed_point == pytest.approx(corrected.fixed_point(p), rel=1e-14)
        assert m.fixed_point_sq == pytest.approx(m.c / (1 - m.mu), rel=1e-14)
        run = solve_cycles(p, 1.0, n_cycles=400)
        assert run.cycles.velocity_before_impact[-1] == math.sqrt(m.fixed_point_sq)  # converged: the float v*
    # the symmetric case in its own closed form: v***2 = 2 f (a2 - a1) / (b (2 - b))
    assert cycle_map(params()).fixed_point_sq == pytest.approx(2 * 0.15 / 0.19, rel=1e-15)


def test_the_velocities_are_the_map_at_every_cycle():
    p = params(F=0.5)
    run = solve_cycles(p, -3.0, n_cycles=200)
    m = cycle_map(p)
    v = run.cycles.velocity_before_impact
    expected = np.sqrt(m.velocity_sq(v[0], np.arange(1, 201)))
    assert np.array_equal(v[1:], expected[1:])
    # the map itself: v_{k+1}**2 = mu v_k**2 + c
    assert v[1:] ** 2 == pytest.approx(m.mu * v[:-1] ** 2 + m.c, rel=1e-14)


def test_long_runs_compute_the_distinct_cycles_only_and_repeat_the_fixed_point():
    p = params()
    run = solve_cycles(p, 1.0, n_cycles=100_000)
    k = run.distinct_cycles
    assert 50 < k < 200  # (0.6561)**k below an ulp
    c = run.cycles
    for name in ("velocity_before_impact", "period", "largest_displacement"):
        column = getattr(c, name)
        assert np.all(column[k - 1:] == column[-1])
    assert np.all(np.diff(c.impact_time) > 0)
    # impact times: t_k = t_1 + sum of the periods before, to rounding
    assert c.impact_time[-1] == pytest.approx(math.fsum([c.impact_time[0], *c.period[:-1]]), rel=2e-16, abs=0)
    assert run.t_final == pytest.approx(math.fsum([c.impact_time[0], *c.period]), rel=2e-16, abs=0)


def test_a_long_run_agrees_with_the_streamed_event_solver():
    from escapement.solvers.stream import iter_cycles

    p = params()
    run = solve_cycles(p, 1.0, n_cycles=200_000)
    done = 0
    for chunk in iter_cycles(p, 1.0, n_cycles=200_000, chunk=50_000):
        part = {name: getattr(run.cycles, name)[done:done + len(chunk)] for name in COLUMNS}
        gaps = compare_tables(type(run.cycles)(**part), chunk)
        assert max(gaps.values()) <= 1e-14, gaps
        done += len(chunk)
    assert done == 200_000


def test_cross_check_raises_on_a_disagreement_and_names_it():
    run = solve_cycles(params(), 1.0, n_cycles=20)
    period = run.cycles.period.copy()
    period[6] *= 1 + 1e-13
    bad = dataclasses.replace(run, cycles=dataclasses.replace(run.cycles, period=period))
    with pytest.raises(CrossCheckError, match=r"period of cycle 7: .* > rtol = 1e-14"):
        cross_check(bad)
    assert cross_check(bad, rtol=1e-12)["period"] == pytest.approx(1e-13, rel=1e-2)
    with pytest.raises(CrossCheckError, match="solve_exact: completed after 20 cycles"):
        cross_check(dataclasses.replace(bad, cycles=dataclasses.replace(run.cycles, period=period[:5])))


def test_the_first_cycle_is_the_event_solvers():
    run = solve_cycles(params(), 1.0, n_cycles=5)
    exact = solve_exact(params(), 1.0, n_cycles=5, record_trajectory=False)
    assert run.cycles.impact_time[0] == exact.cycles.impact_time[0]
    assert run.cycles.velocity_before_impact[0] == exact.cycles.velocity_before_impact[0]


def _streamed(chunks):
    tables = list(chunks)
    return ({name: np.concatenate([np.empty(0)] + [getattr(t, name) for t in tables]) for name in COLUMNS},
            [len(t) for t in tables])


@pytest.mark.parametrize("chunk", [1, 7, 100, 10_000])
@pytest.mark.parametrize("p, x0", [(params(), -1.0), (params(F=0.5), 3.0), (params(a3=0.2, a4=-0.02), 1.0)])
def test_streamed_chunks_are_solve_cycles_number_for_number(p, x0, chunk):
    n = 700
    stored = solve_cycles(p, x0, n_cycles=n)
    chunks = cyc.iter_closed_form_cycles(p, x0, n_cycles=n, chunk=chunk)
    columns, sizes = _streamed(chunks)
    assert chunks.method == CLOSED_FORM and chunks.fallback is None
    assert sizes == [min(chunk, n - i) for i in range(0, n, chunk)]
    for name in COLUMNS:
        assert np.array_equal(columns[name], getattr(stored.cycles, name)), name
    summary = chunks.summary
    assert summary.status is Status.COMPLETED and summary.n_cycles == n and summary.t_final == stored.t_final
    exact = solve_exact(p, x0, n_cycles=n, record_trajectory=False)  # the event count from the event solver
    assert summary.n_events == len(exact.events) and summary.message == exact.message


@pytest.mark.parametrize("p, x0, why", [
    (params(b=1.5), 1.0, "reverses the velocity"),  # chatters
    (params(), 0.05, "did not complete"),  # never reaches a1
    # a transient of 9_527 cycles; the budget holds a chunk (1_000 x 128 bytes) and 2_180 x 400 bytes besides
    (params(b=1e-3), 1.0, "more than the 2_180 cycles"),
])
def test_streamed_runs_the_closed_form_cannot_make_are_the_event_solvers(p, x0, why):
    n = 10_000
    chunks = cyc.iter_closed_form_cycles(p, x0, n_cycles=n, chunk=1_000, memory_budget=10**6)
    columns, _ = _streamed(chunks)
    assert chunks.method == "exact" and why in chunks.fallback
    exact = solve_exact(p, x0, n_cycles=n, record_trajectory=False)
    for name in COLUMNS:
        assert np.array_equal(columns[name], getattr(exact.cycles, name)), name
    assert chunks.summary.status is exact.status and chunks.summary.t_final == exact.t_final


def test_a_stream_is_not_summarised_before_it_ends():
    chunks = cyc.iter_closed_form_cycles(params(), 1.0, n_cycles=100, chunk=10)
    next(chunks)
    with pytest.raises(RuntimeError, match="not exhausted"):
        chunks.summary


def test_a_streamed_run_takes_the_memory_of_a_chunk_whatever_its_length():
    from benchmarks.floor import peak_bytes

    def drained(n):
        return lambda: [None for _ in cyc.iter_closed_form_cycles(params(), 1.0, n_cycles=n, chunk=1_000)]

    short, long = peak_bytes(drained(10_000)), peak_bytes(drained(1_000_000))
    assert long <= 1.5 * short, (short, long)  # a hundred times the cycles, not the memory
    stored = peak_bytes(lambda: solve_cycles(params(), 1.0, n_cycles=1_000_000))
    assert stored >= 20 * long, (stored, long)  # what the stored table takes


def test_a_streamed_chunk_owns_its_arrays():
    chunks = cyc.iter_closed_form_cycles(params(), 1.0, n_cycles=600, chunk=100)  # a transient of ~250 cycles
    first = next(chunks)
    expected = solve_cycles(params(), 1.0, n_cycles=600).cycles
    for name in COLUMNS:
        getattr(first, name)[:] = 0.0
    rest = list(chunks)
    for name in COLUMNS:
        assert np.array_equal(np.concatenate([getattr(c, name) for c in rest]), getattr(expected, name)[100:]), name
