"""Speed floors: the solvers against the least code that computes the same numbers, timed side by side.

:func:`exact_floor`, :func:`ensemble_floor` and :func:`stream_floor` measure the ratios against the floors
of :mod:`benchmarks.minimal`, in one process, the runs of each pair interleaved and repeated (medians); they
return rows of dicts (``name``, ``ratio``, the times or bytes), ready for a CSV; :func:`floor_rows` gives
every row of the speed table's floors (rule run_speed). Wall times depend on the machine and its load; the
ratios much less. The solvers are reached through their public names only (:mod:`escapement.solvers`).
"""

from __future__ import annotations

import gc
import statistics
import time
import tracemalloc
from collections.abc import Callable, Mapping

import numpy as np

from escapement.model import Parameters
from escapement.solvers import iter_closed_form_cycles, iter_cycles, solve_ensemble, solve_exact

from .minimal import PAPER_A, minimal_blocked, minimal_cycles, minimal_events, numpy_cycles

__all__ = ["EXACT_FLOORS", "ensemble_floor", "ensemble_workload", "exact_floor", "floor_rows", "peak_bytes",
           "side_by_side", "stream_floor"]


def side_by_side(functions: dict[str, Callable[[], object]], repeats: int) -> dict[str, list[float]]:
    """Wall times (s) of each function, ``repeats`` times, the functions interleaved (one run of each per
    round), so that the load of a shared machine falls on all alike. As :mod:`timeit` does, the garbage
    collector is off while a run is timed (its pauses would fall on whichever run crosses its threshold);
    it collects once before the rounds."""
    times: dict[str, list[float]] = {name: [] for name in functions}
    gc.collect()
    for _ in range(repeats):
        for name, function in functions.items():
            enabled = gc.isenabled()
            gc.disable()
            try:
                start = time.perf_counter()
                function()
                times[name].append(time.perf_counter() - start)
            finally:
                if enabled:
                    gc.enable()
    return times


def _row(name: str, n: int, times: list[float], reference: list[float], **extra) -> dict:
    median, base = statistics.median(times), statistics.median(reference)
    return {"name": name, "n": n, "ratio": median / base, "time_s": median, "reference_s": base,
            "repeats": len(times), **extra}


def _drained(stream) -> None:
    for _ in stream:
        pass


#: the minimal loops of the exact solver, by the name its rows give them, and what each is in a row's note
EXACT_FLOORS = {
    "minimal blocked loop": (minimal_blocked, "the velocity by a loop, then the arcs and times on arrays"),
    "minimal event loop": (minimal_events, "event by event, the event log"),
    "minimal cycle loop": (minimal_cycles, "event by event, each cycle unrolled, the cycle table"),
}


def exact_floor(sizes=(1_000, 100_000), repeats: dict | int | None = None, params: Parameters = PAPER_A,
                x0: float = 1.0) -> list[dict]:
    """:func:`escapement.solvers.solve_exact` against the minimal loops (:data:`EXACT_FLOORS`) on the periodic
    regime, ``n`` cycles for each of ``sizes``, three ways: storing the full result (the default, with the arcs),
    storing without the arcs (``record_trajectory=False``) and streaming the cycles
    (:func:`escapement.solvers.iter_cycles`). Per size, each way against the fastest minimal loop (the floor: its
    note names it), then against the event-by-event loops as before the kernel worked in blocks (storing against
    :func:`minimal_events`, every way against :func:`minimal_cycles`). A row has ``name``, ``n``, ``ratio``
    (median time over the loop's), ``time_s``, ``reference_s``, ``repeats`` and ``note``. ``repeats`` (a dict by
    size, or one number for all) defaults to about a second of the cycle loop per size: at least 7 runs, at most
    300."""
    rows = []
    for n in sizes:
        count = repeats.get(n) if isinstance(repeats, dict) else repeats
        if count is None:
            start = time.perf_counter()
            minimal_cycles(params, x0, 0.0, n)
            count = max(7, min(300, int(1.0 / max(time.perf_counter() - start, 1e-6))))
        times = side_by_side({
            **{name: lambda n=n, loop=loop: loop(params, x0, 0.0, n) for name, (loop, _) in EXACT_FLOORS.items()},
            "storing": lambda n=n: solve_exact(params, x0, n_cycles=n),
            "storing without arcs": lambda n=n: solve_exact(params, x0, n_cycles=n, record_trajectory=False),
            "streaming": lambda n=n: _drained(iter_cycles(params, x0, n_cycles=n)),
        }, count)
        fastest = min(EXACT_FLOORS, key=lambda name: statistics.median(times[name]))
        ways = ("storing", "storing without arcs", "streaming")
        rows += [_row(f"solve_exact {way} / fastest minimal loop", n, times[way], times[fastest],
                      note=f"the {fastest}: {EXACT_FLOORS[fastest][1]}") for way in ways]
        rows += [_row(f"solve_exact {way} / {loop}", n, times[way], times[loop], note=EXACT_FLOORS[loop][1])
                 for loop, kept in (("minimal event loop", ways[:2]), ("minimal cycle loop", ways)) for way in kept]
    return rows


def ensemble_workload(n_trajectories: int) -> dict:
    """The ensemble's workload: the paper's case (a) with the force spread over [0.5, 1.5] N and the release
    alternating between 1 m and -1 m (so that the first impact is at a3 for half the trajectories, at a1 for
    the others); keyword arguments of :func:`escapement.solvers.solve_ensemble` and
    :func:`numpy_cycles` but ``n_cycles``."""
    return dict(M=1.0, K=1.0, F=np.linspace(0.5, 1.5, n_trajectories), b=0.1, a1=-0.1, a2=0.05,
                x0=np.where(np.arange(n_trajectories) % 2 == 0, 1.0, -1.0), v0=0.0)


def peak_bytes(function: Callable[[], object]) -> int:
    """The peak bytes ``function`` allocates (tracemalloc), above what was allocated before it."""
    gc.collect()
    tracemalloc.start()
    try:
        base = tracemalloc.get_traced_memory()[0]
        function()
        return tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()


def ensemble_floor(n_trajectories: int = 10_000, n_cycles: int = 50, repeats: int = 7) -> list[dict]:
    """:func:`escapement.solvers.solve_ensemble` against :func:`numpy_cycles` on
    :func:`ensemble_workload`: a row for the time (``ratio``, ``time_s``, ``reference_s``, ``repeats``) and
    one for the peak memory per trajectory (``ratio``, ``bytes``, ``reference_bytes``, per trajectory), each
    with ``name`` and ``n`` (the trajectories); ``n_cycles`` cycles each."""
    work = ensemble_workload(n_trajectories)
    functions = {"numpy": lambda: numpy_cycles(**work, n_cycles=n_cycles),
                 "ensemble": lambda: solve_ensemble(**work, n_cycles=n_cycles)}
    times = side_by_side(functions, repeats)
    memory = {name: peak_bytes(function) / n_trajectories for name, function in functions.items()}
    return [
        _row(f"solve_ensemble / numpy loop, {n_cycles} cycles", n_trajectories, times["ensemble"], times["numpy"]),
        {"name": f"solve_ensemble / numpy loop, peak memory per trajectory, {n_cycles} cycles", "n": n_trajectories,
         "ratio": memory["ensemble"] / memory["numpy"], "bytes": memory["ensemble"],
         "reference_bytes": memory["numpy"]},
    ]


def stream_floor(sizes=(1_000_000, 100_000_000), repeats: int = 3, params: Parameters = PAPER_A,
                 x0: float = 1.0) -> list[dict]:
    """Long runs in constant memory. The event solver's stream (:func:`escapement.solvers.iter_cycles`)
    against the closed forms' (:func:`escapement.solvers.iter_closed_form_cycles`) over the smaller of
    ``sizes`` (time, side by side, and peak memory), and the closed forms' stream over the larger against the
    smaller: its ``ratio`` is the peak memory's, ``time_s`` the larger run's wall time (one run) and
    ``reference_s`` the smaller's (the median of the side-by-side runs).
    Each row has ``name``, ``n``, ``ratio``, ``time_s``, ``reference_s``, ``bytes`` and ``reference_bytes``."""
    small, large = sorted(sizes)

    def closed(n):
        return lambda: _drained(iter_closed_form_cycles(params, x0, n_cycles=n))

    def exact(n):
        return lambda: _drained(iter_cycles(params, x0, n_cycles=n))

    times = side_by_side({"exact": exact(small), "closed": closed(small)}, repeats)
    memory = {
        "exact": peak_bytes(exact(small)), "closed": peak_bytes(closed(small)), "large": peak_bytes(closed(large)),
    }
    large_time = side_by_side({"large": closed(large)}, 1)["large"][0]
    return [
        _row("solve_exact streamed / closed-form cycles streamed", small, times["exact"], times["closed"],
             bytes=memory["exact"], reference_bytes=memory["closed"]),
        {"name": f"closed-form cycles streamed, peak memory against {small:_} cycles", "n": large,
         "ratio": memory["large"] / memory["closed"], "time_s": large_time,
         "reference_s": statistics.median(times["closed"]), "repeats": 1, "bytes": memory["large"],
         "reference_bytes": memory["closed"]},
    ]


def floor_rows(settings: Mapping, params: Parameters = PAPER_A, x0: float = 1.0) -> list[dict]:
    """Every row of the speed table's floors: :func:`exact_floor` on ``settings["exact_cycles"]``,
    :func:`ensemble_floor` on ``settings["ensemble_trajectories"]`` and ``settings["ensemble_cycles"]``,
    :func:`stream_floor` on ``settings["stream_cycles"]`` (the configuration's ``speed.floor``); the scalar
    floors from ``x0`` (m) with ``params``."""
    return [
        *exact_floor(tuple(settings["exact_cycles"]), params=params, x0=x0),
        *ensemble_floor(settings["ensemble_trajectories"], settings["ensemble_cycles"]),
        *stream_floor(tuple(settings["stream_cycles"]), params=params, x0=x0),
    ]
