"""The exact solver's specialised loop against the generic solver loop with one stepper call and one
``arc_maximum`` per event (``solve_exact_stepwise``): every number must be the same, bit for bit. The
minimal closed-form loop, a third path to the cycle table, is tested with the speed floors
(tests/benchmarks/test_floor.py)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import initial_displacement, initial_velocity, parameters

import escapement.solvers.exact as exact
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.exact import solve_exact, solve_exact_stepwise

CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "amplitude")
EVENT_COLUMNS = ("t", "kind", "x", "v_before", "v_after")
ARC_COLUMNS = ("t_start", "centre", "x_start", "v_start")


def _bits(a) -> bytes:
    """The bytes of an array: equal bits, -0.0 and NaN included."""
    a = np.ascontiguousarray(a)
    return a.dtype.str.encode() + a.tobytes()


def assert_same_run(fast, slow) -> None:
    """Two solutions of one run hold the same numbers, bit for bit, and end alike."""
    assert (fast.status, fast.message) == (slow.status, slow.message)
    assert _bits([fast.t_final, *vars(fast.exit).values()]) == _bits([slow.t_final, *vars(slow.exit).values()])
    for name in EVENT_COLUMNS:
        assert _bits(getattr(fast.events, name)) == _bits(getattr(slow.events, name)), f"events.{name}"
    for name in CYCLE_COLUMNS:
        assert _bits(getattr(fast.cycles, name)) == _bits(getattr(slow.cycles, name)), f"cycles.{name}"
    assert (fast.trajectory is None) == (slow.trajectory is None)
    if fast.trajectory is not None:
        for name in ARC_COLUMNS:
            assert _bits(getattr(fast.trajectory, name)) == _bits(getattr(slow.trajectory, name)), f"arcs.{name}"
        assert _bits([fast.trajectory.t_final, fast.trajectory.omega]) == _bits([slow.trajectory.t_final,
                                                                                 slow.trajectory.omega])


@pytest.mark.parametrize("record", [True, False])
@pytest.mark.parametrize("params, x0, v0", [
    (Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), 1.0, 0.0),
    (Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0, 0.0),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), -0.8, 0.3),
    (Parameters(M=1.0, K=1.0, F=1.0, b=0.2, a1=-0.1, a2=0.3, a3=0.1, a4=-0.2), 1.0, 0.0),  # a2 > a3
])
def test_the_specialised_loop_gives_the_numbers_of_the_generic_loop(params, x0, v0, record):
    assert_same_run(solve_exact(params, x0, v0, n_cycles=3000, record_trajectory=record),
                    solve_exact_stepwise(params, x0, v0, n_cycles=3000, record_trajectory=record))


@pytest.mark.parametrize("b", [1.0, 1.5, 1.99])
@pytest.mark.parametrize("x0", [1.0, -1.0, 3.0])
def test_b_of_one_and_above_take_the_generic_path_to_the_same_numbers(b, x0):
    # b = 1 leaves the mass at rest after each impact (the amplitude's shortcut never holds); b > 1 rebounds
    p = Parameters(M=1.0, K=1.0, F=0.5, b=b, a1=-0.1, a2=0.05)
    assert_same_run(solve_exact(p, x0, n_cycles=200), solve_exact_stepwise(p, x0, n_cycles=200))


@settings(max_examples=200, deadline=None)
@given(p=parameters(), x0=initial_displacement, v0=initial_velocity,
       b=st.one_of(st.none(), st.floats(0.02, 1.98)), limit=st.sampled_from(["cycles", "time", "events"]),
       record=st.booleans())
def test_random_runs_give_the_numbers_of_the_generic_loop(p, x0, v0, b, limit, record):
    if b is not None:
        p = Parameters(**{**p.as_dict(), "b": b})
    limits = {"cycles": dict(n_cycles=40), "time": dict(t_end=60.0), "events": dict(n_cycles=40, max_events=97)}[limit]
    assert_same_run(solve_exact(p, x0, v0, record_trajectory=record, **limits),
                    solve_exact_stepwise(p, x0, v0, record_trajectory=record, **limits))


def _release_for_zone_turning_at(p: Parameters, impact: str, turn: mpmath.mpf) -> float:
    """From rest at x0 (50 digits): the free arc reaches the impact position with v**2 = w**2 (x0**2 - a**2),
    the impact keeps (1 - b) of it, and the zone arc about c through (a, v+) turns at ``turn``:
    (v+ / w)**2 = (turn - c)**2 - (a - c)**2."""
    with mpmath.workdps(50):
        a = mpmath.mpf(getattr(p, impact))
        c = mpmath.mpf(p.F) / mpmath.mpf(p.K) * (1 if impact == "a1" else -1)
        w_after_sq = (turn - c) ** 2 - (a - c) ** 2
        return float(-mpmath.sqrt(a**2 + w_after_sq / (1 - mpmath.mpf(p.b)) ** 2) if impact == "a1"
                     else mpmath.sqrt(a**2 + w_after_sq / (1 - mpmath.mpf(p.b)) ** 2))


@pytest.mark.parametrize("params, impact, end", [
    # the zone (a1, a2) about F/K = 0.02 m, narrower than a2's distance from its centre: it turns near a2
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.05, a2=0.1), "a1", "a2"),
    # the zone (a4, a3) about -F/K, turning near a4
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.1, a2=0.05, a3=0.05, a4=-0.1), "a3", "a4"),
])
def test_arcs_that_reach_their_end_at_a_turning_point_give_the_numbers_of_the_generic_loop(monkeypatch, params,
                                                                                            impact, end):
    """Releases ulp by ulp around the one whose first zone arc turns exactly at the zone's end: some turn
    back, some arrive with a velocity within 1e-6 of the circle's scale (the amplitude's shortcut gives way
    to arc_maximum); every one gives the generic loop's numbers."""
    calls = []
    original = exact.arc_maximum
    monkeypatch.setattr(exact, "arc_maximum", lambda *args: calls.append(args) or original(*args))
    x0 = _release_for_zone_turning_at(params, impact, mpmath.mpf(getattr(params, end)))
    outcomes, fallbacks = set(), 0
    for k in range(-60, 61):
        release = x0 + k * math.ulp(x0)
        calls.clear()
        fast = solve_exact(params, release, n_cycles=3)
        # the loop's own calls start at the impact position (the stepper's first arc starts at the release)
        fallbacks += any(args[1] == getattr(params, impact) for args in calls)
        assert_same_run(fast, solve_exact_stepwise(params, release, n_cycles=3))
        outcomes.add(fast.status)
    assert Status.TURNED_BACK_IN_ZONE in outcomes and Status.COMPLETED in outcomes
    assert fallbacks, "no arc arrived close enough to its turning point to leave the shortcut"


@pytest.mark.parametrize("params, impact, end", [
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.05, a2=0.1), "a1", "a2"),
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.1, a2=0.05, a3=0.05, a4=-0.1), "a3", "a4"),
])
@pytest.mark.parametrize("amplitude", [True, False])
def test_the_ensemble_follows_the_releases_around_a_turning_point_as_the_scalar_solver(params, impact, end,
                                                                                        amplitude):
    """The releases of the test above as one ensemble, mixed with releases whose first zone arc turns well
    inside or well past the zone's end: in the ensemble's cycles in lock-step some trajectories turn back,
    some leave for the per-event passes (an arc that arrives near its turning point) and come back a cycle
    later than the others; each gives the scalar solver's numbers (to rounding: NumPy's arctan2 and hypot)."""
    from escapement.solvers.ensemble import solve_ensemble

    x0 = _release_for_zone_turning_at(params, impact, mpmath.mpf(getattr(params, end)))
    releases = np.array([x0 + k * math.ulp(x0) for k in range(-60, 61)] + [0.9 * x0, 1.1 * x0, 2 * x0, x0 / 3])
    ens = solve_ensemble(*(getattr(params, k) for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")), x0=releases,
                         n_cycles=6, amplitude=amplitude)
    for i, release in enumerate(releases):
        run = solve_exact(params, float(release), n_cycles=6, record_trajectory=False)
        assert ens.outcome(i) == run.status
        n = len(run.cycles)
        for name in CYCLE_COLUMNS if amplitude else CYCLE_COLUMNS[:-1]:
            got = getattr(ens.cycles, name)[i]
            assert got[:n] == pytest.approx(getattr(run.cycles, name), rel=1e-13, abs=1e-300), name
            assert np.isnan(got[n:]).all()
        assert ens.t_final[i] == pytest.approx(run.t_final, rel=1e-13)
    assert {Status(s) for s in map(lambda i: ens.outcome(i), range(len(releases)))} >= {Status.COMPLETED,
                                                                                         Status.TURNED_BACK_IN_ZONE}
