"""The minimal loops (benchmarks/minimal.py) give the numbers of the escapement's periodic regime.

The minimal loops are checked against what it must compute, not against itself: the return map of the symmetric
escapement written out by hand, and the cycle table of :func:`escapement.solvers.solve_exact`."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks import floor, minimal
from escapement.model import Parameters
from escapement.solvers import solve_ensemble, solve_exact

CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")


@pytest.mark.parametrize("params, x0", [(minimal.PAPER_A, 1.0), (Parameters(M=2.0, K=0.5, F=0.3, b=0.25, a1=-0.2,
                                                                          a2=0.1), 3.0)])
def test_the_minimal_loop_follows_the_return_map_of_the_symmetric_escapement(params, x0):
    """Released at rest at x0 > a3 = -a1, the mass first meets a3 with v**2 = w**2 (x0**2 - a3**2). Each half cycle
    keeps (1 - b)**2 of v**2 at its impact and gains 2 f (a2 - a1) in its zone (f = F/M), the spring's terms
    cancelling between the impact positions a1 and a3 = -a1: before the impacts at a1,
    u_{k+1} = (1 - b)**4 u_k + 2 f (a2 - a1) ((1 - b)**2 + 1), with the fixed point
    v*^2 = 2 f (a2 - a1) / (b (2 - b)). The free swing after a2 turns at x**2 = a1**2 + v(a1, after the zone)**2 / w**2:
    the amplitude."""
    n = 400
    columns = minimal.minimal_cycles(params, x0, 0.0, n)
    times, speeds, periods, amplitudes = (np.frombuffer(column) for column in columns)
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


CASES = [
    (minimal.PAPER_A, 1.0, 0.0, 10_000),  # first impact at a3
    (minimal.PAPER_A, -1.0, 0.0, 200),  # first impact at a1
    (Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0, 0.0, 10_000),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), -0.8, 0.3, 200),
]


@pytest.mark.parametrize("params, x0, v0, n", CASES)
def test_the_minimal_loop_gives_the_cycle_table_of_solve_exact_bit_for_bit(params, x0, v0, n):
    run = solve_exact(params, x0, v0, n_cycles=n, record_trajectory=False)
    assert run.success
    for name, column in zip(CYCLE_COLUMNS, minimal.minimal_cycles(params, x0, v0, n)):
        assert np.frombuffer(column).tobytes() == getattr(run.cycles, name).tobytes(), name


def test_the_numpy_loop_gives_the_cycle_table_of_solve_ensemble_to_1e14():
    work = floor.ensemble_workload(64)
    assert set(np.asarray(work["x0"]).tolist()) == {1.0, -1.0}  # both first impacts
    reference = minimal.numpy_cycles(**work, n_cycles=30)
    ensemble = solve_ensemble(**work, n_cycles=30)
    assert ensemble.success.all()
    for name in CYCLE_COLUMNS:
        got, want = getattr(reference, name), getattr(ensemble.cycles, name)
        assert got.shape == want.shape == (64, 30)
        assert np.all(np.abs(got - want) <= 1e-14 * np.abs(want)), name


def test_the_numpy_loop_takes_per_trajectory_parameters_as_the_ensemble_does():
    ps = [Parameters(M=1.0, K=1.0, F=f, b=b, a1=-0.1, a2=0.05) for f, b in ((0.5, 0.1), (1.5, 0.3))]
    columns = {k: [getattr(p, k) for p in ps] for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}
    table = minimal.numpy_cycles(**columns, x0=[3.0, -1.0], n_cycles=20)
    for i, p in enumerate(ps):
        run = solve_exact(p, [3.0, -1.0][i], n_cycles=20, record_trajectory=False)
        for name in CYCLE_COLUMNS:
            assert getattr(table, name)[i] == pytest.approx(getattr(run.cycles, name), rel=1e-14), name


def test_the_minimal_event_loop_gives_the_event_log_of_solve_exact_bit_for_bit():
    """From the first impact at a1 on, each event's time and velocity before it; and the times advance by
    exactly the cycle table's periods at every impact at a1 (a cycle is four events)."""
    for x0 in (1.0, -1.0, 3.0):
        times, speeds = (np.frombuffer(column) for column in minimal.minimal_events(minimal.PAPER_A, x0, 0.0, 300))
        run = solve_exact(minimal.PAPER_A, x0, n_cycles=300)
        first = int(np.flatnonzero(run.events.kind == 1)[0])
        assert np.array_equal(times, run.events.t[first:])
        assert np.array_equal(speeds, run.events.v_before[first:])
        assert len(times) == 4 * 300 + 1
        assert np.all(np.abs(np.diff(times[::4]) - run.cycles.period) <= 4 * np.spacing(times[4::4]))


@pytest.mark.parametrize("params, x0, v0, n", CASES)
def test_the_blocked_loop_gives_the_numbers_of_the_event_and_cycle_loops_bit_for_bit(params, x0, v0, n):
    """Its times and velocities are the event loop's, its cycle table the cycle loop's; the positions and the
    velocities after each event, which neither loop stores, are those of solve_exact's event log."""
    (t, x, v_before, v_after), cycles = minimal.minimal_blocked(params, x0, v0, n)
    times, speeds = (np.frombuffer(column) for column in minimal.minimal_events(params, x0, v0, n))
    assert t.tobytes() == times.tobytes() and v_before.tobytes() == speeds.tobytes()
    for name, got, want in zip(CYCLE_COLUMNS, cycles, minimal.minimal_cycles(params, x0, v0, n)):
        assert got.tobytes() == np.frombuffer(want).tobytes(), name
    events = solve_exact(params, x0, v0, n_cycles=n, record_trajectory=False).events
    first = int(np.flatnonzero(events.kind == 1)[0])
    assert x.tobytes() == events.x[first:].tobytes() and v_after.tobytes() == events.v_after[first:].tobytes()
