"""The per-cycle closed forms (cycles, and closed_form, its engine) against the event solver, number by number: the
first impact, the distinct cycles, where the closed form gives way, the compensated impact times, the transient's
memory; and both solvers' cycles in chunks (their endings: test_kernel.py, their memory: test_memory.py)."""

import dataclasses
import math

import numpy as np
import pytest

from benchmarks.floor import peak_bytes
from escapement.model.limits import MemoryBudgetError
from escapement.model.cycle_map import cycle_map
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper import corrected
from escapement.solvers import closed_form as cf
from escapement.solvers import cycles as cyc
from escapement.solvers.cycles import CLOSED_FORM, CrossCheckError, compare_tables, cross_check, solve_cycles
from escapement.solvers.exact import solve_exact
from escapement.solvers.stream import iter_cycles

MODEL = dict(M=1.0, K=1.0, b=0.1, a1=-0.1, a2=0.05, a3=0.1, a4=-0.05)  # Fig. 3
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)


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


#: Fig. 3's cases, the configuration's asymmetric geometries (checks.asymmetric.positions) and impact coefficients
#: across the regime, each released on both sides
AGREEING = [(params(F=F), x0, n) for F, x0 in ((1.0, 1.0), (0.5, 3.0)) for n in (50, 1000)] + [
    (params(F=F, **dict(zip(("a1", "a2", "a3", "a4"), positions))), 1.0, 300) for F in (0.5, 1.0, 3.0)
    for positions in ((-0.1, 0.05, 0.2, -0.02), (-0.15, 0.0, 0.08, -0.1), (-0.1, 0.05, 0.3, 0.0))] + [
    (params(b=b), 1.0, 1000) for b in (0.05, 1.0)]


@pytest.mark.parametrize("p, x0, n", AGREEING)
def test_the_closed_form_agrees_with_the_event_solver(p, x0, n):
    for release in (x0, -x0):
        run = assert_closed_form_agrees(p, release, n)
    if p.b == 1.0:  # mu = 0: every cycle after the first is the fixed point's
        assert run.cycle_map.mu == 0.0 and run.distinct_cycles == 2


@pytest.mark.parametrize("p, x0, n, status, why", [
    (params(b=1.5), 1.0, 50, Status.CHATTERING, "b = 1.5: the impact reverses the velocity (the run chatters)"),
    (params(b=1.9), -1.0, 50, Status.CHATTERING, "b = 1.9: the impact reverses the velocity (the run chatters)"),
    (params(), 0.01, 20, Status.STOPPED, "the event solver's first cycle from the release did not complete"),
    (params(), 0.05, 20, Status.STOPPED, "first cycle"),
    (params(F=0.01, b=1.0, a1=-0.1, a2=0.15, a3=0.1, a4=-0.15), -1.0, 20, Status.TURNED_BACK_IN_ZONE, "first cycle"),
    # without force the velocity decays to 0: the swing from a4 arrives at a1 ever closer to its turning point
    (params(F=0.0), 1.0, 300, Status.COMPLETED, "the free swing a4 -> a1 of cycle"),
])
def test_a_run_the_closed_form_cannot_make_is_the_event_solvers_and_says_why(p, x0, n, status, why):
    run = solve_cycles(p, x0, n_cycles=n)
    assert_same_as_exact(run, p, x0, n)
    assert run.status is status and why in run.fallback
    assert ("grazes its end" in run.fallback) == (status is Status.COMPLETED)


@pytest.mark.parametrize("x0", [1.0, 2.0, -1.0])
def test_a_run_that_stops_after_some_cycles_falls_back_from_the_closed_form(x0):
    # c < 0 (a3**2 < a1**2 and no force): v**2 falls by mu and c each cycle until a swing misses a1
    p = params(F=0.0, a1=-0.5, a2=0.05, a3=0.05, a4=-0.05)
    assert cycle_map(p).c < 0.0
    run = solve_cycles(p, x0, n_cycles=200)
    assert_same_as_exact(run, p, x0, 200)
    assert run.status is Status.STOPPED and 0 < len(run.cycles) < 200
    assert "the free swing a4 -> a1" in run.fallback and "cannot reach its end" in run.fallback


def test_the_velocities_are_the_map_at_every_cycle_and_its_fixed_point_the_corrected_papers():
    for p in (params(), params(F=0.5), params(b=0.05), params(F=3.0, a1=-0.1, a2=0.05, a3=0.3, a4=0.0)):
        m = cycle_map(p)
        assert m.mu == pytest.approx((1 - p.b) ** 4, rel=1e-15)
        assert m.c == pytest.approx(corrected.map_constant(p), rel=1e-14)
        assert m.fixed_point == pytest.approx(corrected.fixed_point(p), rel=1e-14)
        assert m.fixed_point_sq == pytest.approx(m.c / (1 - m.mu), rel=1e-14)
        v = solve_cycles(p, -3.0, n_cycles=400).cycles.velocity_before_impact
        assert np.array_equal(v[1:], np.sqrt(m.velocity_sq(v[0], np.arange(1, 401)))[1:])
        assert v[1:] ** 2 == pytest.approx(m.mu * v[:-1] ** 2 + m.c, rel=1e-14)  # v_{k+1}**2 = mu v_k**2 + c
        assert v[-1] == math.sqrt(m.fixed_point_sq)  # converged: the float v*
    # the symmetric case in its own closed form: v***2 = 2 f (a2 - a1) / (b (2 - b))
    assert cycle_map(params()).fixed_point_sq == pytest.approx(2 * 0.15 / 0.19, rel=1e-15)


def test_long_runs_compute_the_distinct_cycles_only_and_repeat_the_fixed_point():
    run = solve_cycles(params(), 1.0, n_cycles=100_000)
    k, c = run.distinct_cycles, run.cycles
    assert 50 < k < 200  # (0.6561)**k below an ulp
    for name in ("velocity_before_impact", "period", "largest_displacement"):
        assert np.all(getattr(c, name)[k - 1:] == getattr(c, name)[-1])
    assert np.all(np.diff(c.impact_time) > 0)
    # impact times: t_k = t_1 + the periods before, to rounding
    assert c.impact_time[-1] == pytest.approx(math.fsum([c.impact_time[0], *c.period[:-1]]), rel=2e-16, abs=0)
    assert run.t_final == pytest.approx(math.fsum([c.impact_time[0], *c.period]), rel=2e-16, abs=0)


def test_a_long_run_agrees_with_the_streamed_event_solver():
    run, done = solve_cycles(params(), 1.0, n_cycles=60_000), 0
    for chunk in iter_cycles(params(), 1.0, n_cycles=60_000, chunk=20_000):
        part = {name: getattr(run.cycles, name)[done:done + len(chunk)] for name in COLUMNS}
        assert max(compare_tables(type(run.cycles)(**part), chunk).values()) <= 1e-14
        done += len(chunk)
    assert done == 60_000


def test_cross_check_raises_on_a_disagreement_and_names_it(monkeypatch):
    run = solve_cycles(params(), 1.0, n_cycles=20)
    period = run.cycles.period.copy()
    period[6] *= 1 + 1e-13
    bad = dataclasses.replace(run, cycles=dataclasses.replace(run.cycles, period=period))
    with pytest.raises(CrossCheckError, match=r"period of cycle 7: .* > rtol = 1e-14"):
        cross_check(bad)
    assert cross_check(bad, rtol=1e-12)["period"] == pytest.approx(1e-13, rel=1e-2)
    with pytest.raises(CrossCheckError, match="solve_exact: completed after 20 cycles"):
        cross_check(dataclasses.replace(bad, cycles=dataclasses.replace(run.cycles, period=period[:5])))
    assert solve_cycles(params(), 1.0, n_cycles=30, check=True).method == CLOSED_FORM  # check runs the cross check
    monkeypatch.setattr(cf, "two_sum", lambda a, b: (a + b + 1e-9, 0.0 * a))  # impact times off by 1e-9 s
    with pytest.raises(CrossCheckError, match="impact_time"):
        solve_cycles(params(), 1.0, n_cycles=30, check=True)


# --- the engine -----------------------------------------------------------------------------------------------


def test_the_first_impact_is_the_event_solvers_and_the_rows_of_a_window_those_of_the_whole_run():
    """Time, velocity and events up to the first impact at a1 are the event loop's, and the table's first row; each
    row from its own cycle number: any window is the whole table's numbers, its end the next one's start."""
    p = params(F=0.5)
    exact = solve_exact(p, 3.0, n_cycles=5, record_trajectory=False)
    t1, v1, events = cf.first_impact(p, 3.0, 0.0)
    i = int(np.flatnonzero(exact.events.kind == 1)[0])
    assert (t1, v1, events) == (exact.events.t[i], exact.events.v_before[i], i + 1)
    assert events == 3  # from rest at x0 = 3: a3, a4, then a1
    assert "reverses the velocity" in cf.first_impact(params(b=1.5), 1.0, 0.0)
    assert "did not complete" in cf.first_impact(p, 0.05, 0.0)
    c = cf.distinct_cycles(p, cf.prepared(p), t1, v1, 1000)
    whole, end = cf.table_rows(c, 0, 1000)
    for start, stop in ((0, 1), (5, 17), (c.distinct - 3, c.distinct + 40), (999, 1000)):
        part, t_end = cf.table_rows(c, start, stop)
        for name in COLUMNS:
            assert np.array_equal(getattr(part, name), getattr(whole, name)[start:stop]), (name, start)
        assert t_end == (whole.impact_time[stop] if stop < 1000 else end)
    run = solve_cycles(p, 3.0, n_cycles=1000)
    assert end == run.t_final and (run.cycles.impact_time[0], run.cycles.velocity_before_impact[0]) == (t1, v1)


def _fractions_of_the_largest_speed(b: float, x0: float) -> list[float]:
    """Per cycle, the least ``v**2`` an arc arrives with over its largest (``E = v**2 + w**2 x**2``, w = 1): without
    force each arc keeps ``E``, arriving at ``p`` with ``E - p**2``; an impact multiplies ``v**2`` by ``(1 - b)**2``."""
    r2, a, a2, fractions = (1 - b) ** 2, 0.1, 0.05, []
    v_sq = r2 * (x0 * x0 - a * a)  # from rest at x0, after the first impact, at a3; the zone and swing keep E
    while not fractions or fractions[-1] > 1e-4:
        after_a1 = r2 * v_sq + a * a  # E after the impact at a1: the arcs to a2 and to a3
        after_a3 = r2 * (after_a1 - a * a) + a * a  # E after the impact at a3: the arcs to a4 and to a1
        fractions.append(min(1 - a2 * a2 / after_a1, 1 - a * a / after_a1, 1 - a2 * a2 / after_a3,
                             1 - a * a / after_a3))
        v_sq = after_a3 - a * a
    return fractions


def test_the_closed_form_gives_way_where_an_arc_grazes_its_end_at_a_thousandth_of_its_speed_squared():
    """The swing decays without force until the swing to a1 grazes it: the last cycle whose arcs all arrive above 1e-3
    of their largest v**2 is the closed form's (with b = 0.01 the fraction falls by 4 % a cycle), the next is not."""
    p = params(F=0.0, b=0.01)
    fractions = _fractions_of_the_largest_speed(0.01, 1.0)
    n = next(k for k, f in enumerate(fractions) if f <= 1e-3)  # cycles 1 .. n arrive above the threshold
    assert 1e-3 < fractions[n - 1] < 1.05e-3 and 0.95e-3 < fractions[n]
    assert solve_cycles(p, 1.0, n_cycles=n).method == CLOSED_FORM
    run = solve_cycles(p, 1.0, n_cycles=n + 1)
    assert_same_as_exact(run, p, 1.0, n + 1)
    assert f"the free swing a4 -> a1 of cycle {n + 1} grazes its end" in run.fallback


def test_the_prefix_sums_are_compensated():
    rng = np.random.default_rng(7)
    d = rng.standard_normal(5000) * np.exp(-np.arange(5000) / 300.0) * 1e-3
    d[::7] *= 1e6
    hi, lo = cf._prefix_sums(d)
    assert np.array_equal(hi[1:], np.cumsum(d))  # cumsum adds one by one (what TwoSum corrects)
    for i in (1, 10, 777, 5000):
        assert hi[i] + lo[i] == math.fsum(d[:i])


# --- in chunks ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("chunk", [1, 7, 1024, 1_000_000])  # 1024 cycles: a block of the loop holds 4096 events
@pytest.mark.parametrize("p, x0", [(params(), 1.0), (params(F=0.5), 3.0), (ASYMMETRIC, -0.8)])
def test_the_event_solver_s_chunks_put_together_are_its_cycles_bit_for_bit(p, x0, chunk):
    whole = solve_exact(p, x0, n_cycles=3_000, record_trajectory=False)
    stream = iter_cycles(p, x0, n_cycles=3_000, chunk=chunk)
    chunks = list(stream)
    assert [len(c) for c in chunks] == [min(chunk, 3_000 - i) for i in range(0, 3_000, chunk)]
    for name in COLUMNS:
        assert np.concatenate([getattr(c, name) for c in chunks]).tobytes() == getattr(whole.cycles, name).tobytes()
    s = stream.summary
    assert (s.status, s.message, s.t_final, s.n_cycles, s.n_events) == (
        whole.status, whole.message, whole.t_final, len(whole.cycles), len(whole.events))
    assert s.success


def test_the_summary_comes_once_the_stream_is_exhausted():
    stream = iter_cycles(params(), 1.0, n_cycles=10, chunk=4)
    assert len(next(stream)) == 4
    with pytest.raises(RuntimeError, match="not exhausted"):
        stream.summary  # noqa: B018
    assert [len(c) for c in stream] == [4, 2]
    assert stream.summary.n_cycles == 10 and stream.summary.status == Status.COMPLETED
    with pytest.raises(StopIteration):
        next(stream)


def test_a_run_of_a_billion_cycles_is_streamed_without_refusal():
    assert len(next(iter_cycles(params(), 1.0, n_cycles=10**9, chunk=1000))) == 1000
    with pytest.raises(MemoryBudgetError):
        solve_exact(params(), 1.0, n_cycles=10**9, record_trajectory=False)


def _streamed(chunks):
    tables = list(chunks)
    columns = {name: np.concatenate([np.empty(0), *(getattr(t, name) for t in tables)]) for name in COLUMNS}
    return columns, [len(t) for t in tables]


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


def test_a_chunk_owns_its_arrays_and_the_stream_is_summarised_once_it_ends():
    chunks = cyc.iter_closed_form_cycles(params(), 1.0, n_cycles=600, chunk=100)  # a transient of ~250 cycles
    first = next(chunks)
    with pytest.raises(RuntimeError, match="not exhausted"):
        chunks.summary  # noqa: B018
    for name in COLUMNS:
        getattr(first, name)[:] = 0.0
    rest, expected = list(chunks), solve_cycles(params(), 1.0, n_cycles=600).cycles
    for name in COLUMNS:
        assert np.array_equal(np.concatenate([getattr(c, name) for c in rest]), getattr(expected, name)[100:]), name


def test_a_streamed_run_takes_the_memory_of_a_chunk_whatever_its_length():
    def drained(n):
        return lambda: [None for _ in cyc.iter_closed_form_cycles(params(), 1.0, n_cycles=n, chunk=1_000)]

    short, long = peak_bytes(drained(10_000)), peak_bytes(drained(100_000))
    assert long <= 1.5 * short, (short, long)  # ten times the cycles, not the memory
    stored = peak_bytes(lambda: solve_cycles(params(), 1.0, n_cycles=100_000))
    assert stored >= 20 * long, (stored, long)  # what the stored table takes


@pytest.mark.parametrize("b", [1e-3, 1e-4])
def test_the_transient_stays_within_the_memory_budget(b):
    p = params(b=b)
    count = cf._transient(cycle_map(p), cf.first_impact(p, 1.0, 0.0)[1], 10**8)  # every cycle distinct
    chunk = 1_000
    budget = chunk * cyc.CHUNK_BYTES_PER_CYCLE + count * cyc.PEAK_BYTES_PER_CYCLE  # just enough for the guard

    def run():
        return cyc.iter_closed_form_cycles(p, 1.0, n_cycles=count + 10 * chunk, chunk=chunk, memory_budget=budget)

    assert run().method == CLOSED_FORM
    streamed = peak_bytes(lambda: [None for _ in run()])
    assert streamed <= budget, (streamed, budget)
    stored = peak_bytes(lambda: solve_cycles(p, 1.0, n_cycles=count, memory_budget=count * cyc.PEAK_BYTES_PER_CYCLE))
    assert stored <= count * cyc.PEAK_BYTES_PER_CYCLE, (stored, count)
