"""Speed floors: the solvers against the least code that computes the same numbers, timed side by side.

Two reference implementations, each the floor its solver is measured against and a second path to its
numbers (the tests compare them):

* :func:`minimal_cycles`, a minimal closed-form loop for one trajectory, written out by hand: the same
  closed forms as :func:`escapement.model.kinematics.crossing` (the same operations in the same order), the
  same compensated time sum and the paper's impact law ``v+ = (1 - b) v-``, one regular cycle after
  another; no exits, no event log, no checks. It gives the cycle table of
  :func:`escapement.solvers.solve_exact` bit for bit.
* :func:`numpy_cycles`, the same loop vectorised with NumPy over many trajectories at once, the floor of
  :func:`escapement.solvers.solve_ensemble`; the same operations on arrays, so the same numbers
  in practice (the tests ask for 1e-14, relative).

Both assume the regime holds (the paper's cases: ``a1 < 0``, ``a4 <= a2``, ``a4 <= a3``, ``b < 1``, a
release that reaches an impact): outside it their numbers mean nothing.

:func:`exact_floor` and :func:`ensemble_floor` measure the ratios, in one process, the runs of each pair
interleaved and repeated (medians); they return rows of dicts (``name``, ``ratio``, the times or bytes),
ready for a CSV; :func:`floor_rows` gives every row of the speed table's floors (rule run_speed). Wall
times depend on the machine and its load; the ratios much less. The solvers are reached through their
public names only (:mod:`escapement.solvers`).
"""

from __future__ import annotations

import gc
import math
import statistics
import time
import tracemalloc
from array import array
from collections.abc import Callable, Mapping
from typing import NamedTuple

import numpy as np

from escapement.model import Parameters
from escapement.solvers import iter_closed_form_cycles, iter_cycles, solve_ensemble, solve_exact

__all__ = [
    "PAPER_A", "Cycles", "ensemble_floor", "ensemble_workload", "exact_floor", "floor_rows",
    "minimal_cycles", "numpy_cycles", "peak_bytes", "side_by_side", "stream_floor",
]

TWO_PI = 2.0 * math.pi
#: the paper's Fig. 3 case (a): the workload of the scalar floor, released at rest at 1 m
PAPER_A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


class Cycles(NamedTuple):
    """The cycle table of :func:`numpy_cycles` (s, m/s, s, m): a row per trajectory, a column per cycle."""

    impact_time: np.ndarray
    velocity_before_impact: np.ndarray
    period: np.ndarray
    amplitude: np.ndarray


def minimal_cycles(p: Parameters, x0: float, v0: float, n_cycles: int) -> tuple[array, array, array, array]:
    """Impact times at a1 (s), velocities before them (m/s), periods (s) and amplitudes (m) of ``n_cycles``
    cycles from ``(x0, v0)``, by the minimal closed-form loop.

    The first arc from the release, free (to a1 moving right or a3 moving left, whichever comes first), the
    arcs to the first impact at a1, then per cycle the zone (a1, a2), the free swing over the top to a3, the
    zone (a4, a3) and the free swing to a1. The amplitude is the top of the free swing, the only arc of a
    regular cycle that passes the top of its circle, ``hypot(a2, v / omega)``, or the largest surface
    position if that is larger.
    """
    w = p.omega
    w2 = w * w
    c = p.zone_offset
    r = 1.0 - p.b
    a1, a2, a3, a4 = p.a1, p.a2, p.a3, p.a4
    sqrt, atan2, hypot = math.sqrt, math.atan2, math.hypot
    t_sum = t_err = x0 * 0
    best = None
    for target, d in ((a1, 1), (a3, -1)):  # the first arc, free: a1 moving right or a3 moving left
        v_sq = v0 * v0 + w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0))
        if v_sq > 0.0:
            v1 = d * sqrt(v_sq)
            u0, q, w0, w1 = x0 - 0.0, target - 0.0, v0 / w, v1 / w
            angle = atan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
            angle = angle + TWO_PI * (angle <= 0.0)
            if best is None or angle / w < best[0]:
                best = (angle / w, v1, target)
    dt, v, x = best
    new = t_sum + dt
    t_err += (t_sum - new) + dt if abs(t_sum) >= abs(dt) else (dt - new) + t_sum
    t_sum = new

    def stage(x_from, target, centre):
        return w2 * ((x_from - target) * (x_from + target - 2.0 * centre)), x_from - centre, target - centre

    k1, u1, q1 = stage(a1, a2, c)
    k2, u2, q2 = stage(a2, a3, 0.0)
    k3, u3, q3 = stage(a3, a4, -c)
    k4, u4, q4 = stage(a4, a1, 0.0)
    if x == a3:  # the impact at a3, the zone to a4, the free swing to a1
        v = r * v
        v1 = -sqrt(v * v + k3)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q3 - u3 * w1, u3 * q3 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        v = v1
        v1 = sqrt(v * v + k4)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q4 - u4 * w1, u4 * q4 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        v = v1
    times, speeds, periods, amplitudes = array("d"), array("d"), array("d"), array("d")
    floor = max(a2, a3)
    for _ in range(n_cycles):
        times.append(t_sum + t_err)
        speeds.append(v)
        v = r * v
        # (a1, a2) in the zone
        v1 = sqrt(v * v + k1)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q1 - u1 * w1, u1 * q1 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed = 0.0 + dt
        v = v1
        # a2 to a3, free, over the top
        v1 = -sqrt(v * v + k2)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q2 - u2 * w1, u2 * q2 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        top = 0.0 + hypot(u2, w0)
        v = r * v1
        # (a4, a3) in the zone
        v1 = -sqrt(v * v + k3)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q3 - u3 * w1, u3 * q3 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        v = v1
        # a4 to a1, free
        v1 = sqrt(v * v + k4)
        w0, w1 = v / w, v1 / w
        angle = atan2(w0 * q4 - u4 * w1, u4 * q4 + w0 * w1)
        dt = (angle + TWO_PI * (angle <= 0.0)) / w
        new = t_sum + dt
        t_err += (t_sum - new) + dt if t_sum >= dt else (dt - new) + t_sum
        t_sum = new
        elapsed += dt
        v = v1
        periods.append(elapsed)
        amplitudes.append(top if top > floor else floor)
    return times, speeds, periods, amplitudes


def _numpy_arc(v, k, u, q, omega, direction: float):
    """One arc of every trajectory: ``crossing()`` on arrays with the arc's surface terms ``k, u, q``;
    the velocity on arrival and the time."""
    v1 = np.sqrt(v * v + k)
    if direction < 0:
        np.negative(v1, out=v1)
    w0 = v / omega
    w1 = v1 / omega
    angle = np.arctan2(w0 * q - u * w1, u * q + w0 * w1)
    angle[angle <= 0.0] += TWO_PI
    angle /= omega
    return v1, angle


def _numpy_add(t_sum, t_err, dt):
    """Neumaier's compensated sum, in place (``t_sum >= 0``, ``dt > 0``: ``|t_sum| >= |dt|`` is ``t_sum >= dt``)."""
    new = t_sum + dt
    t_err += np.where(t_sum >= dt, (t_sum - new) + dt, (dt - new) + t_sum)
    t_sum[:] = new


def numpy_cycles(M, K, F, b, a1, a2, a3=None, a4=None, x0=1.0, v0=0.0, *, n_cycles: int) -> Cycles:
    """:func:`minimal_cycles` vectorised over trajectories: the cycle table, each column of shape
    ``(N, n_cycles)``, of every trajectory (the inputs broadcast to ``(N,)``, as for
    :func:`escapement.solvers.solve_ensemble`; ``a3``, ``a4`` default to ``-a1``, ``-a2``).

    The first arc picks, per trajectory, the first of a1 moving right and a3 moving left; the trajectories
    that hit a3 first then take the zone to a4 and the swing to a1; from there every cycle is four arcs of
    every trajectory at once.
    """
    a3 = -np.asarray(a1, dtype=float) if a3 is None else a3
    a4 = -np.asarray(a2, dtype=float) if a4 is None else a4
    M, K, F, b, a1, a2, a3, a4, x0, v0 = (np.array(a, dtype=float).ravel() for a in np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (M, K, F, b, a1, a2, a3, a4, x0, v0))))
    n = len(M)
    omega = np.sqrt(K / M)
    w2 = omega * omega
    c = F / K
    r = 1.0 - b
    # the first arc, free (centre 0): to a1 moving right or to a3 moving left, whichever comes first
    dt = np.full(n, np.inf)
    v = np.zeros(n)
    for target, direction in ((a1, 1.0), (a3, -1.0)):
        v_sq = v0 * v0 + w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0))
        with np.errstate(invalid="ignore"):
            v1, tau = _numpy_arc(v0, w2 * ((x0 - target) * (x0 + target - 2.0 * 0.0)), x0 - 0.0, target - 0.0,
                                 omega, direction)
        take = (v_sq > 0.0) & (tau < dt)
        dt = np.where(take, tau, dt)
        v = np.where(take, v1, v)
    at_a3 = v < 0.0
    t_sum, t_err = np.zeros(n), np.zeros(n)
    _numpy_add(t_sum, t_err, dt)

    def stage(x_from, target, centre):
        return w2 * ((x_from - target) * (x_from + target - 2.0 * centre)), x_from - centre, target - centre

    k1, u1, q1 = stage(a1, a2, c)
    k2, u2, q2 = stage(a2, a3, 0.0)
    k3, u3, q3 = stage(a3, a4, -c)
    k4, u4, q4 = stage(a4, a1, 0.0)
    if at_a3.any():  # the impact at a3, the zone to a4, the free swing to a1
        i = np.flatnonzero(at_a3)
        ts, te = t_sum[i], t_err[i]
        v3, dt = _numpy_arc(r[i] * v[i], k3[i], u3[i], q3[i], omega[i], -1.0)
        _numpy_add(ts, te, dt)
        v1, dt = _numpy_arc(v3, k4[i], u4[i], q4[i], omega[i], 1.0)
        _numpy_add(ts, te, dt)
        t_sum[i], t_err[i], v[i] = ts, te, v1
    times, speeds, periods, amplitudes = (np.empty((n, n_cycles)) for _ in range(4))
    floor = np.maximum(a2, a3)
    for cycle in range(n_cycles):
        times[:, cycle] = t_sum + t_err
        speeds[:, cycle] = v
        v1, dt = _numpy_arc(r * v, k1, u1, q1, omega, 1.0)  # (a1, a2) in the zone
        _numpy_add(t_sum, t_err, dt)
        elapsed = 0.0 + dt
        top = 0.0 + np.hypot(u2, v1 / omega)
        v1, dt = _numpy_arc(v1, k2, u2, q2, omega, -1.0)  # a2 to a3, free, over the top
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        v1, dt = _numpy_arc(r * v1, k3, u3, q3, omega, -1.0)  # (a4, a3) in the zone
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        v, dt = _numpy_arc(v1, k4, u4, q4, omega, 1.0)  # a4 to a1, free
        _numpy_add(t_sum, t_err, dt)
        elapsed += dt
        periods[:, cycle] = elapsed
        amplitudes[:, cycle] = np.where(top > floor, top, floor)
    return Cycles(impact_time=times, velocity_before_impact=speeds, period=periods, amplitude=amplitudes)


# --- measuring -------------------------------------------------------------------------------------------------


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


def exact_floor(sizes=(1_000, 100_000), repeats: dict | int | None = None, params: Parameters = PAPER_A,
                x0: float = 1.0) -> list[dict]:
    """:func:`escapement.solvers.solve_exact` against :func:`minimal_cycles` on the periodic regime,
    ``n`` cycles for each of ``sizes``: storing the full result (the default, with the arcs), storing without
    the arcs (``record_trajectory=False``), and streaming the cycles (:func:`escapement.solvers.iter_cycles`).
    One row per way and size: ``name``, ``n``, ``ratio`` (median time over the minimal loop's), ``time_s``,
    ``reference_s``, ``repeats``. ``repeats`` (a dict by size, or one number for all) defaults to about
    a second of the minimal loop per size: at least 7 runs, at most 300."""
    rows = []
    for n in sizes:
        count = repeats.get(n) if isinstance(repeats, dict) else repeats
        if count is None:
            start = time.perf_counter()
            minimal_cycles(params, x0, 0.0, n)
            count = max(7, min(300, int(1.0 / max(time.perf_counter() - start, 1e-6))))
        times = side_by_side({
            "minimal": lambda n=n: minimal_cycles(params, x0, 0.0, n),
            "storing": lambda n=n: solve_exact(params, x0, n_cycles=n),
            "storing without arcs": lambda n=n: solve_exact(params, x0, n_cycles=n, record_trajectory=False),
            "streaming": lambda n=n: _drained(iter_cycles(params, x0, n_cycles=n)),
        }, count)
        for way in ("storing", "storing without arcs", "streaming"):
            rows.append(_row(f"solve_exact {way} / minimal loop", n, times[way], times["minimal"]))
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
    memory = {"exact": peak_bytes(exact(small)), "closed": peak_bytes(closed(small)), "large": peak_bytes(closed(large))}
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
