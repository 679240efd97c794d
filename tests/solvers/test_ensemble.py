"""The ensemble in lock-step against the scalar solver, trajectory by trajectory: the same outcomes, cycles and
exit numbers, whatever the mix of first events, endings and event bounds; the invariant of completed rows."""

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from releases import release_for_zone_turning_at
from strategies import initial_displacement, initial_velocity, parameters

import escapement.solvers.ensemble as ensemble
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact

NAMES = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
KEYS = ("M", "K", "F", "b", "a1", "a2", "a3", "a4")


def assert_rows_are_the_scalar_runs(ens, params_list, x0s, v0s, n_cycles, max_events=None, amplitude=True):
    """Each row: the scalar run's outcome, cycles (NaN after them), end time and exit numbers."""
    for i, (p, x0, v0) in enumerate(zip(params_list, x0s, v0s)):
        run = solve_exact(p, float(x0), float(v0), n_cycles=n_cycles, max_events=max_events, record_trajectory=False)
        assert ens.outcome(i) == run.status and ens.success[i] == run.success
        n = len(run.cycles)
        for name in NAMES if amplitude else NAMES[:-1]:
            got, want = getattr(ens.cycles, name)[i], getattr(run.cycles, name)
            assert got[:n] == pytest.approx(want, rel=1e-13, abs=1e-300) and np.isnan(got[n:]).all(), name
        assert ens.t_final[i] == pytest.approx(run.t_final, rel=1e-13)  # inf equals inf
        exits = (ens.exit_turning_point[i], ens.exit_margin[i], ens.exit_t_accumulation[i])
        assert exits == pytest.approx((run.exit.turning_point, run.exit.margin, run.exit.t_accumulation), rel=1e-12,
                                      abs=1e-15, nan_ok=True)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(parameters(), initial_displacement, initial_velocity), min_size=1, max_size=30),
       st.sampled_from([None, 1, 6, 57, 97, 130]), st.booleans())
def test_the_cycles_in_lock_step_give_the_scalar_solvers_numbers(cases, max_events, amplitude):
    """Over 40 cycles, with event bounds inside a cycle and between cycles, with and without the amplitude: the
    trajectories that leave the common path and come back a cycle later are followed as the scalar solver does."""
    ps, x0s, v0s = zip(*cases)
    ens = solve_ensemble(**{k: [getattr(p, k) for p in ps] for k in KEYS}, x0=np.array(x0s), v0=np.array(v0s),
                         n_cycles=40, max_events=max_events, largest_displacement=amplitude)
    assert_rows_are_the_scalar_runs(ens, ps, x0s, v0s, 40, max_events, amplitude)


def test_paper_cases_over_many_cycles():
    ps = [Parameters(M=1, K=1, F=f, b=0.1, a1=-0.1, a2=0.05) for f in (1.0, 0.5)]
    ens = solve_ensemble(**{k: [getattr(p, k) for p in ps] for k in KEYS}, x0=[1.0, 3.0], n_cycles=500)
    assert_rows_are_the_scalar_runs(ens, ps, (1.0, 3.0), (0.0, 0.0), 500)


def test_every_outcome_is_reported_with_the_scalar_runs_exit_numbers():
    """Completed, chattering (b = 1.5), turned back, stopped: the runs whose exits test_kernel.py works out by hand."""
    ps = [Parameters(M=1.0, K=K, F=F, b=b, a1=a1, a2=a2) for K, F, b, a1, a2 in (
        (1.0, 1.0, 0.1, -0.1, 0.05), (1.0, 1.0, 1.5, -0.1, 0.05), (100.0, 0.01, 0.1, -0.02, 0.1),
        (1.0, 1.0, 0.1, -0.1, 0.05))]
    out = solve_ensemble(**{k: [getattr(p, k) for p in ps] for k in KEYS}, x0=[1.0, 1.0, 0.021, 0.05], n_cycles=3)
    assert out.status.tolist() == [Status.COMPLETED.code, Status.CHATTERING.code, Status.TURNED_BACK_IN_ZONE.code,
                                   Status.STOPPED.code]
    assert_rows_are_the_scalar_runs(out, ps, (1.0, 1.0, 0.021, 0.05), (0.0,) * 4, 3)
    limited = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=3, max_events=5)
    assert limited.outcome(0) == Status.EVENT_LIMIT and not limited.success[0]


@pytest.mark.parametrize("path", ["arc_maximum", "hypot", None])
def test_a_completed_row_with_a_non_finite_number_is_a_bug_raised(monkeypatch, path):
    """An amplitude made NaN (by arc_maximum or NumPy's hypot, the top c + hypot(u0, w0)) raises; unasked, it is NaN."""
    if path == "arc_maximum":
        monkeypatch.setattr(ensemble, "arc_maximum", lambda *args: np.full(np.shape(args[1]), np.nan))
    elif path == "hypot":
        monkeypatch.setattr(np, "hypot", lambda u, w: np.full(np.shape(u), np.nan))
    if path is not None:
        with pytest.raises(FloatingPointError, match="^row 0: a completed run holds a non-finite largest_displacement"):
            solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=2)
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=2, largest_displacement=False)
    assert out.success[0] and np.isnan(out.cycles.largest_displacement).all()
    assert np.isfinite(out.cycles.velocity_before_impact).all() and out.cycles.velocity_before_impact.shape == (1, 2)


@pytest.mark.parametrize("params, impact, end", [
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.05, a2=0.1), "a1", "a2"),
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.1, a2=0.05, a3=0.05, a4=-0.1), "a3", "a4"),
])
@pytest.mark.parametrize("amplitude", [True, False])
def test_the_ensemble_follows_the_releases_around_a_turning_point_as_the_scalar_solver(params, impact, end,
                                                                                        amplitude):
    """Releases ulp by ulp around the one whose first zone arc turns exactly at the zone's end, and some well inside
    or past it, as one ensemble: each the scalar run (to rounding: NumPy's arctan2 and hypot)."""
    x0 = release_for_zone_turning_at(params, impact, mpmath.mpf(getattr(params, end)))
    releases = np.array([x0 + k * math.ulp(x0) for k in range(-60, 61)] + [0.9 * x0, 1.1 * x0, 2 * x0, x0 / 3])
    ens = solve_ensemble(*(getattr(params, k) for k in KEYS), x0=releases, n_cycles=6, largest_displacement=amplitude)
    assert_rows_are_the_scalar_runs(ens, [params] * len(releases), releases, np.zeros(len(releases)), 6,
                                    amplitude=amplitude)
    assert {ens.outcome(i) for i in range(len(releases))} >= {Status.COMPLETED, Status.TURNED_BACK_IN_ZONE}
