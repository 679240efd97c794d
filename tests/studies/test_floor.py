"""The speed floors' study: its reference implementations give the solvers' numbers, and its measurements
return rows of the stated form. Not timed: the sizes are tiny and no ratio is asserted."""

from __future__ import annotations

import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.studies import floor

CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "amplitude")


@pytest.mark.parametrize("params, x0, v0", [
    (floor.PAPER_A, 1.0, 0.0),  # first impact at a3
    (floor.PAPER_A, -1.0, 0.0),  # first impact at a1
    (Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0, 0.0),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), -0.8, 0.3),
])
def test_the_minimal_loop_gives_the_cycle_table_of_solve_exact_bit_for_bit(params, x0, v0):
    run = solve_exact(params, x0, v0, n_cycles=200, record_trajectory=False)
    for name, column in zip(CYCLE_COLUMNS, floor.minimal_cycles(params, x0, v0, 200)):
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


def test_the_exact_floor_gives_a_row_per_way_and_size():
    rows = floor.exact_floor(sizes=(3, 5), repeats=2)
    assert [(row["name"], row["n"]) for row in rows] == [
        (f"solve_exact {way} / minimal loop", n)
        for n in (3, 5) for way in ("storing", "storing without arcs", "streaming")]
    for row in rows:
        assert set(row) == {"name", "n", "ratio", "time_s", "reference_s", "repeats"}
        assert row["repeats"] == 2 and row["time_s"] > 0 and row["reference_s"] > 0
        assert math.isclose(row["ratio"], row["time_s"] / row["reference_s"])


def test_the_ensemble_floor_gives_a_row_for_time_and_one_for_memory():
    rows = floor.ensemble_floor(n_trajectories=20, n_cycles=3, repeats=2)
    time_row, memory_row = rows
    assert time_row["name"] == "solve_ensemble / numpy loop, 3 cycles" and time_row["n"] == 20
    assert set(time_row) == {"name", "n", "ratio", "time_s", "reference_s", "repeats"}
    assert memory_row["name"] == "solve_ensemble / numpy loop, peak memory per trajectory, 3 cycles"
    assert set(memory_row) == {"name", "n", "ratio", "bytes", "reference_bytes"}
    assert memory_row["bytes"] > 0 and memory_row["reference_bytes"] > 0
    assert math.isclose(memory_row["ratio"], memory_row["bytes"] / memory_row["reference_bytes"])


def test_peak_bytes_counts_what_a_function_allocates():
    assert floor.peak_bytes(lambda: np.ones(100_000)) >= 800_000


def test_floor_rows_are_every_row_of_both(monkeypatch):
    monkeypatch.setattr(floor, "exact_floor", lambda sizes: [{"name": "exact", "sizes": sizes}])
    monkeypatch.setattr(floor, "ensemble_floor", lambda n, c: [{"name": "ensemble", "n": n, "cycles": c}])
    assert floor.floor_rows((7,), 11, 2) == [{"name": "exact", "sizes": (7,)},
                                             {"name": "ensemble", "n": 11, "cycles": 2}]
