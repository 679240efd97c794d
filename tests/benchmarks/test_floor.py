"""The speed floors' measurements (benchmarks/floor.py) on an injected clock: each timed run takes a duration
the test sets, so every median, time and ratio of a row is known by hand. The memory rows likewise take their
peak bytes from the test; :func:`floor.peak_bytes` itself is checked on an allocation of known size. No wall
time is asserted. The minimal loops themselves are tested in test_minimal.py."""

from __future__ import annotations

import gc
import tracemalloc
from types import SimpleNamespace

import numpy as np
import pytest

from benchmarks import floor
from escapement.model import Parameters


class DurationClock:
    """A clock read twice per timed run (start, end): each end reading comes the next of ``durations`` after
    the start. Durations are binary fractions, so that every difference and ratio is exact."""

    def __init__(self, durations) -> None:
        self.durations, self.now, self.readings = list(durations), 0.0, 0

    def __call__(self) -> float:
        self.readings += 1
        if self.readings % 2 == 0:
            self.now += self.durations.pop(0)
        return self.now


def _use(monkeypatch, clock) -> None:
    monkeypatch.setattr(floor, "time", SimpleNamespace(perf_counter=clock))


def _interleaved(*per_function):
    """The durations read in side_by_side's order: one run of each function per round."""
    return [d for round_ in zip(*per_function) for d in round_]


def test_side_by_side_interleaves_the_runs_and_times_each_with_the_collector_off(monkeypatch):
    clock = DurationClock(_interleaved([0.5, 0.25, 2.0], [1.0, 1.0, 1.0]))
    _use(monkeypatch, clock)
    calls = []
    times = floor.side_by_side({"a": lambda: calls.append(("a", gc.isenabled())),
                                "b": lambda: calls.append(("b", gc.isenabled()))}, 3)
    assert calls == [("a", False), ("b", False)] * 3  # interleaved, the garbage collector off while timed
    assert gc.isenabled()  # and on again afterwards
    assert times == {"a": [0.5, 0.25, 2.0], "b": [1.0, 1.0, 1.0]}
    assert clock.durations == [] and clock.readings == 12


WAYS = (("storing", 6), ("storing without arcs", 3), ("streaming", 1.5))  # the solver's ways and their medians


@pytest.mark.parametrize("fastest", list(floor.EXACT_FLOORS))
def test_the_exact_floor_sets_each_way_against_the_fastest_loop_by_median_then_the_event_by_event_loops(
        monkeypatch, fastest):
    # the loops' medians are 1 (the fastest's), 2 and 4; the smallest run (0.25) and the smallest mean (1.42) are
    # another loop's than the smallest median
    others = iter(([0.25, 2, 2], [4, 4, 4]))
    per_loop = {loop: [1, 8, 0.5] if loop == fastest else next(others) for loop in floor.EXACT_FLOORS}
    medians = dict(zip((fastest, *(loop for loop in per_loop if loop != fastest)), (1, 2, 4)))
    storing, no_arcs, streaming = [8, 4, 6], [3, 5, 3], [1.5, 0.5, 2]  # medians 6, 3 and 1.5
    _use(monkeypatch, DurationClock(_interleaved(*per_loop.values(), storing, no_arcs, streaming)))
    rows = floor.exact_floor(sizes=(3,), repeats=3)
    notes = {loop: note for loop, (_, note) in floor.EXACT_FLOORS.items()}
    expected = [(f"solve_exact {way} / fastest minimal loop", time, 1, f"the {fastest}: {notes[fastest]}")
                for way, time in WAYS]
    expected += [(f"solve_exact {way} / {loop}", time, medians[loop], notes[loop])
                 for loop, ways in (("minimal event loop", WAYS[:2]), ("minimal cycle loop", WAYS))
                 for way, time in ways]
    assert rows == [{"name": name, "n": 3, "ratio": time / reference, "time_s": time, "reference_s": reference,
                     "repeats": 3, "note": note} for name, time, reference, note in expected]
    assert [row["ratio"] for row in rows[:3]] == [6, 3, 1.5]  # the quotients over the floor, worked out


def test_the_exact_floor_gives_a_row_per_way_and_size():
    rows = floor.exact_floor(sizes=(3, 5), repeats=2)
    ways = ("storing", "storing without arcs", "streaming")
    assert [(row["name"], row["n"]) for row in rows] == [
        (f"solve_exact {way} / {loop}", n) for n in (3, 5)
        for loop, kept in (("fastest minimal loop", ways), ("minimal event loop", ways[:2]),
                           ("minimal cycle loop", ways)) for way in kept]
    assert all(row["repeats"] == 2 and row["time_s"] > 0 and row["reference_s"] > 0 for row in rows)


def _scripted_peaks(monkeypatch, peaks):
    """peak_bytes giving the test's numbers, in the order of the calls (each function still runs once)."""
    remaining = list(peaks)

    def peak(function):
        function()
        return remaining.pop(0)

    monkeypatch.setattr(floor, "peak_bytes", peak)
    return remaining


def test_the_ensemble_floor_gives_a_row_for_time_and_one_per_trajectory_for_memory(monkeypatch):
    _use(monkeypatch, DurationClock(_interleaved([1, 2, 1], [3, 2, 5])))  # numpy, then the ensemble: medians 1, 3
    left = _scripted_peaks(monkeypatch, [4000, 8000])  # numpy, then the ensemble: 200 and 400 bytes a trajectory
    time_row, memory_row = floor.ensemble_floor(n_trajectories=20, n_cycles=3, repeats=3)
    assert time_row == {"name": "solve_ensemble / numpy loop, 3 cycles", "n": 20, "ratio": 3.0, "time_s": 3,
                        "reference_s": 1, "repeats": 3}
    assert memory_row == {"name": "solve_ensemble / numpy loop, peak memory per trajectory, 3 cycles", "n": 20,
                          "ratio": 2.0, "bytes": 400.0, "reference_bytes": 200.0}
    assert left == []


def test_the_stream_floor_times_the_smaller_size_and_compares_the_larger_s_memory(monkeypatch):
    # exact and closed-form streams side by side (medians 4 and 1), then the larger run once (16)
    _use(monkeypatch, DurationClock([*_interleaved([4, 6, 2], [1, 2, 1]), 16]))
    _scripted_peaks(monkeypatch, [300, 100, 150])  # exact and closed form at 50 cycles, closed form at 200
    streamed, memory = floor.stream_floor(sizes=(200, 50), repeats=3)
    assert streamed == {"name": "solve_exact streamed / closed-form cycles streamed", "n": 50, "ratio": 4.0,
                        "time_s": 4, "reference_s": 1, "repeats": 3, "bytes": 300, "reference_bytes": 100}
    assert memory == {"name": "closed-form cycles streamed, peak memory against 50 cycles", "n": 200, "ratio": 1.5,
                      "time_s": 16, "reference_s": 1, "repeats": 1, "bytes": 150, "reference_bytes": 100}


def test_the_floor_rows_are_those_of_the_three_floors_on_the_configured_sizes(monkeypatch):
    """Each floor (its rows checked above) takes its sizes from the configuration, the scalar ones the scene."""
    monkeypatch.setattr(floor, "exact_floor", lambda sizes, params, x0: [("exact", sizes, params, x0)])
    monkeypatch.setattr(floor, "ensemble_floor", lambda n, cycles: [("ensemble", n, cycles)])
    monkeypatch.setattr(floor, "stream_floor", lambda sizes, params, x0: [("stream", sizes, params, x0)])
    settings = {"exact_cycles": [4, 9], "ensemble_trajectories": 6, "ensemble_cycles": 2, "stream_cycles": [50, 200]}
    p = Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05)
    assert floor.floor_rows(settings, params=p, x0=-3.0) == [("exact", (4, 9), p, -3.0), ("ensemble", 6, 2),
                                                              ("stream", (50, 200), p, -3.0)]


def test_peak_bytes_counts_what_a_function_allocates():
    # 100_000 float64 are 800_000 bytes of data, and an array's header is a few hundred bytes at most
    assert 800_000 <= floor.peak_bytes(lambda: np.ones(100_000)) < 801_000
    kept = []
    assert floor.peak_bytes(lambda: kept.append(0)) < 1_000  # nothing of size allocated
    with pytest.raises(ZeroDivisionError):
        floor.peak_bytes(lambda: 1 / 0)
    assert not tracemalloc.is_tracing()  # stopped even when the function raises
