"""The speed floors' measurements (benchmarks/floor.py) return rows of the stated form. Not timed: the sizes are
tiny and no ratio is asserted. The minimal loops themselves are tested in test_minimal.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmarks import floor

CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "amplitude")


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
        (f"solve_exact {way} / minimal {loop} loop", n) for n in (3, 5)
        for loop, ways in (("event", ("storing", "storing without arcs")),
                           ("cycle", ("storing", "storing without arcs", "streaming"))) for way in ways]
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
        ("solve_exact storing / minimal event loop", 4),
        ("solve_exact storing without arcs / minimal event loop", 4),
        ("solve_exact storing / minimal cycle loop", 4),
        ("solve_exact storing without arcs / minimal cycle loop", 4),
        ("solve_exact streaming / minimal cycle loop", 4),
        ("solve_ensemble / numpy loop, 2 cycles", 6),
        ("solve_ensemble / numpy loop, peak memory per trajectory, 2 cycles", 6),
        ("solve_exact streamed / closed-form cycles streamed", 50),
        ("closed-form cycles streamed, peak memory against 50 cycles", 200),
    ]
    assert rows[-1]["ratio"] == pytest.approx(rows[-1]["bytes"] / rows[-1]["reference_bytes"])
    _assert_ratios(rows[:-1])


def test_peak_bytes_counts_what_a_function_allocates():
    assert floor.peak_bytes(lambda: np.ones(100_000)) >= 800_000
