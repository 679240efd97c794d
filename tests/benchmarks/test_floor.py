"""The speed floors (benchmarks/floor.py): their loops give the numbers of the escapement's periodic regime, and
their measurements return rows of the stated form. Not timed: the sizes are tiny and no ratio is asserted.

The minimal loop is checked against what it must compute, not against itself: the return map of the symmetric
escapement written out by hand, and the cycle table of :func:`escapement.solvers.solve_exact`."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmarks import floor
from escapement.model import Parameters
from escapement.solvers import solve_ensemble, solve_exact

CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "amplitude")


@pytest.mark.parametrize("params, x0", [(floor.PAPER_A, 1.0), (Parameters(M=2.0, K=0.5, F=0.3, b=0.25, a1=-0.2,
                                                                          a2=0.1), 3.0)])
def test_the_minimal_loop_follows_the_return_map_of_the_symmetric_escapement(params, x0):
    """Released at rest at x0 > a3 = -a1, the mass first meets a3 with v**2 = w**2 (x0**2 - a3**2). Each half cycle
    keeps (1 - b)**2 of v**2 at its impact and gains 2 f (a2 - a1) in its zone (f = F/M), the spring's terms
    cancelling between the impact positions a1 and a3 = -a1: before the impacts at a1,
    u_{k+1} = (1 - b)**4 u_k + 2 f (a2 - a1) ((1 - b)**2 + 1), with the fixed point
    v*^2 = 2 f (a2 - a1) / (b (2 - b)). The free swing after a2 turns at x**2 = a1**2 + v(a1, after the zone)**2 / w**2:
    the amplitude."""
    n = 400
    times, speeds, periods, amplitudes = (np.frombuffer(column) for column in floor.minimal_cycles(params, x0, 0.0, n))
    w2, f, r2 = params.K / params.M, params.F / params.M, (1.0 - params.b) ** 2
    gain = 2.0 * f * (params.a2 - params.a1)
    u = [r2 * w2 * (x0**2 - params.a1**2) + gain]
    for _ in range(n - 1):
        u.append(r2 * r2 * u[-1] + gain * (r2 + 1.0))
    u = np.array(u)
    assert speeds**2 == pytest.approx(u, rel=1e-12)
    assert (speeds > 0).all()
    assert speeds[-1] ** 2 == pytest.approx(gain / (params.b * (2.0 - params.b)), rel=1e-12)
    assert amplitudes**2 == pytest.approx(params.a1**2 + (r2 * u + gain) / w2, rel=1e-12)
    assert np.diff(times) == pytest.approx(periods[:-1], rel=1e-12)


@pytest.mark.parametrize("params, x0, v0, n", [
    (floor.PAPER_A, 1.0, 0.0, 10_000),  # first impact at a3
    (floor.PAPER_A, -1.0, 0.0, 200),  # first impact at a1
    (Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0, 0.0, 10_000),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), -0.8, 0.3, 200),
])
def test_the_minimal_loop_gives_the_cycle_table_of_solve_exact_bit_for_bit(params, x0, v0, n):
    run = solve_exact(params, x0, v0, n_cycles=n, record_trajectory=False)
    assert run.success
    for name, column in zip(CYCLE_COLUMNS, floor.minimal_cycles(params, x0, v0, n)):
        assert np.frombuffer(column).tobytes() == getattr(run.cycles, name).tobytes(), name


def test_the_numpy_loop_gives_the_cycle_table_of_solve_ensemble_to_1e14():
    work = floor.ensemble_workload(64)
    assert set(np.asarray(work["x0"]).tolist()) == {1.0, -1.0}  # both first impacts
    reference = floor.numpy_cycles(**work, n_cycles=30)
    ensemble = solve_ensemble(**work, n_cycles=30)
    assert ensemble.success.all()
    for name in CYCLE_COLUMNS:
        got, want = getattr(reference, name), getattr(ensemble.cycles, name)
        assert got.shape == want.shape == (64, 30)
        assert np.all(np.abs(got - want) <= 1e-14 * np.abs(want)), name


def test_the_numpy_loop_takes_per_trajectory_parameters_as_the_ensemble_does():
    ps = [Parameters(M=1.0, K=1.0, F=f, b=b, a1=-0.1, a2=0.05) for f, b in ((0.5, 0.1), (1.5, 0.3))]
    columns = {k: [getattr(p, k) for p in ps] for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}
    table = floor.numpy_cycles(**columns, x0=[3.0, -1.0], n_cycles=20)
    for i, p in enumerate(ps):
        run = solve_exact(p, [3.0, -1.0][i], n_cycles=20, record_trajectory=False)
        for name in CYCLE_COLUMNS:
            assert getattr(table, name)[i] == pytest.approx(getattr(run.cycles, name), rel=1e-14), name


def test_side_by_side_runs_every_function_the_same_number_of_times():
    calls = []
    times = floor.side_by_side({"a": lambda: calls.append("a"), "b": lambda: calls.append("b")}, 3)
    assert calls == ["a", "b"] * 3  # interleaved
    assert {name: len(t) for name, t in times.items()} == {"a": 3, "b": 3}
    assert all(t >= 0.0 for ts in times.values() for t in ts)


def _assert_ratios(rows):
    for row in rows:
        if "bytes" in row and "peak memory" in row["name"]:
            assert row["bytes"] > 0 and row["reference_bytes"] > 0
            assert math.isclose(row["ratio"], row["bytes"] / row["reference_bytes"])
        else:
            assert row["time_s"] > 0 and row["reference_s"] > 0
            assert math.isclose(row["ratio"], row["time_s"] / row["reference_s"])


def test_the_exact_floor_gives_a_row_per_way_and_size():
    rows = floor.exact_floor(sizes=(3, 5), repeats=2)
    assert [(row["name"], row["n"]) for row in rows] == [
        (f"solve_exact {way} / minimal loop", n)
        for n in (3, 5) for way in ("storing", "storing without arcs", "streaming")]
    assert all(set(row) == {"name", "n", "ratio", "time_s", "reference_s", "repeats"} for row in rows)
    assert all(row["repeats"] == 2 for row in rows)
    _assert_ratios(rows)


def test_the_ensemble_floor_gives_a_row_for_time_and_one_for_memory():
    rows = floor.ensemble_floor(n_trajectories=20, n_cycles=3, repeats=2)
    time_row, memory_row = rows
    assert time_row["name"] == "solve_ensemble / numpy loop, 3 cycles" and time_row["n"] == 20
    assert set(time_row) == {"name", "n", "ratio", "time_s", "reference_s", "repeats"}
    assert memory_row["name"] == "solve_ensemble / numpy loop, peak memory per trajectory, 3 cycles"
    assert set(memory_row) == {"name", "n", "ratio", "bytes", "reference_bytes"}
    _assert_ratios(rows)


def test_the_floor_rows_are_those_of_the_three_floors_on_the_configured_sizes():
    settings = {"exact_cycles": [4], "ensemble_trajectories": 6, "ensemble_cycles": 2, "stream_cycles": [50, 200]}
    rows = floor.floor_rows(settings)
    assert [(row["name"], row["n"]) for row in rows] == [
        ("solve_exact storing / minimal loop", 4),
        ("solve_exact storing without arcs / minimal loop", 4),
        ("solve_exact streaming / minimal loop", 4),
        ("solve_ensemble / numpy loop, 2 cycles", 6),
        ("solve_ensemble / numpy loop, peak memory per trajectory, 2 cycles", 6),
        ("solve_exact streamed / closed-form cycles streamed", 50),
        ("closed-form cycles streamed, peak memory against 50 cycles", 200),
    ]
    assert rows[-1]["ratio"] == pytest.approx(rows[-1]["bytes"] / rows[-1]["reference_bytes"])
    _assert_ratios(rows[:-1])


def test_peak_bytes_counts_what_a_function_allocates():
    assert floor.peak_bytes(lambda: np.ones(100_000)) >= 800_000
