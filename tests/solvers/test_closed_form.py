"""The engine of the per-cycle closed forms (escapement.solvers.closed_form): the first impact from the event
loop, the distinct cycles, their grazing margin, the compensated impact times and the transient's memory."""

import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.solvers import closed_form as cf
from escapement.solvers import cycles as cyc
from escapement.solvers.cycles import CLOSED_FORM, CrossCheckError, solve_cycles
from escapement.solvers.exact import solve_exact

MODEL = dict(M=1.0, K=1.0, b=0.1, a1=-0.1, a2=0.05, a3=0.1, a4=-0.05)  # Fig. 3
COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")


def params(**changes) -> Parameters:
    return Parameters(**{**MODEL, "F": 1.0, **changes})


def assert_same_as_exact(run, p: Parameters, x0: float, n: int):
    exact = solve_exact(p, x0, n_cycles=n, record_trajectory=False)
    assert run.method == "exact" and run.fallback
    assert (run.status, run.message, run.t_final, run.exit) == (exact.status, exact.message, exact.t_final, exact.exit)
    for name in COLUMNS:
        assert np.array_equal(getattr(run.cycles, name), getattr(exact.cycles, name))


def test_the_first_impact_is_the_event_solvers():
    """Time and velocity before the first impact at a1, and the events up to it, from the event loop."""
    p = params()
    exact = solve_exact(p, 1.0, n_cycles=1, record_trajectory=False)
    t1, v1, events = cf.first_impact(p, 1.0, 0.0)
    i = int(np.flatnonzero(exact.events.kind == 1)[0])
    assert (t1, v1, events) == (exact.events.t[i], exact.events.v_before[i], i + 1)
    assert events == 3  # from rest at x0 = 1: a3, a4, then a1
    assert "reverses the velocity" in cf.first_impact(params(b=1.5), 1.0, 0.0)
    assert "did not complete" in cf.first_impact(p, 0.05, 0.0)


def test_the_rows_of_a_window_are_those_of_the_whole_run():
    """table_rows makes each row from its own cycle number: any window of cycles is the same numbers as the
    whole table's, and the end time of a window is the next window's first impact time."""
    p = params(F=0.5)
    t1, v1, _ = cf.first_impact(p, 3.0, 0.0)
    c = cf.distinct_cycles(p, cf.prepared(p), t1, v1, 1000)
    whole, end = cf.table_rows(c, 0, 1000)
    for start, stop in ((0, 1), (5, 17), (c.distinct - 3, c.distinct + 40), (999, 1000)):
        part, t_end = cf.table_rows(c, start, stop)
        for name in COLUMNS:
            assert np.array_equal(getattr(part, name), getattr(whole, name)[start:stop]), (name, start)
        assert t_end == (whole.impact_time[stop] if stop < 1000 else end)
    assert end == solve_cycles(p, 3.0, n_cycles=1000).t_final


def _fractions_of_the_largest_speed(b: float, x0: float) -> list[float]:
    """Per cycle, the least ``v**2`` an arc arrives with, as a fraction of its largest (its energy
    ``E = v**2 + w**2 x**2``, w = 1): the paper's geometry without force, so that every centre is 0 and each arc
    keeps ``E``, arriving at ``p`` with ``E - p**2``; each impact multiplies ``v**2`` by ``(1 - b)**2``."""
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
    """Without force the swing decays (v**2 by (1 - b)**4 a cycle) until the free swing arrives at a1 grazing it:
    the last cycle whose arcs all arrive with more than 1e-3 of their largest v**2 is the closed form's, the next
    the event solver's. With b = 0.01 the fraction falls by 4 % a cycle: a threshold 1.05 times larger or smaller
    moves the cycle where the closed form gives way."""
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


def test_check_mode_runs_the_cross_check(monkeypatch):
    run = solve_cycles(params(), 1.0, n_cycles=30, check=True)
    assert run.method == CLOSED_FORM
    monkeypatch.setattr(cf, "two_sum", lambda a, b: (a + b + 1e-9, 0.0 * a))  # impact times off by 1e-9 s
    with pytest.raises(CrossCheckError, match="impact_time"):
        solve_cycles(params(), 1.0, n_cycles=30, check=True)


@pytest.mark.parametrize("b", [1e-3, 1e-4])
def test_the_transient_stays_within_the_memory_budget(b):
    from benchmarks.floor import peak_bytes

    p = params(b=b)
    count = cf._transient(cf.cycle_map(p), cf.first_impact(p, 1.0, 0.0)[1], 10**8)  # every cycle distinct
    chunk = 1_000
    budget = chunk * cyc.CHUNK_BYTES_PER_CYCLE + count * cyc.PEAK_BYTES_PER_CYCLE  # just enough for the guard
    chunks = cyc.iter_closed_form_cycles(p, 1.0, n_cycles=count + 10 * chunk, chunk=chunk, memory_budget=budget)
    assert chunks.method == CLOSED_FORM
    streamed = peak_bytes(lambda: [None for _ in cyc.iter_closed_form_cycles(p, 1.0, n_cycles=count + 10 * chunk,
                                                                               chunk=chunk, memory_budget=budget)])
    assert streamed <= budget, (streamed, budget)
    stored = peak_bytes(lambda: solve_cycles(p, 1.0, n_cycles=count, memory_budget=count * cyc.PEAK_BYTES_PER_CYCLE))
    assert stored <= count * cyc.PEAK_BYTES_PER_CYCLE, (stored, count)
