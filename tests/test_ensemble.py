import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import initial_displacement, initial_velocity, parameters

from escapement import ParameterError, Parameters, Status, solve_exact
from escapement.ensemble import solve_ensemble

NAMES = ("impact_time", "velocity_before_impact", "period", "amplitude")


def _compare(params_list, x0s, v0s, n_cycles):
    arrays = {k: [getattr(p, k) for p in params_list] for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}
    ens = solve_ensemble(**arrays, x0=x0s, v0=v0s, n_cycles=n_cycles)
    for i, p in enumerate(params_list):
        run = solve_exact(p, x0s[i], v0s[i], n_cycles=n_cycles, record_trajectory=False)
        assert ens.outcome(i) == run.status
        n = len(run.cycles)
        for name in NAMES:
            got, want = getattr(ens, name)[i, :n], getattr(run.cycles, name)
            assert got == pytest.approx(want, rel=1e-13, abs=1e-300), name
            assert np.isnan(getattr(ens, name)[i, n:]).all()


@settings(max_examples=30)
@given(st.lists(st.tuples(parameters(), initial_displacement, initial_velocity), min_size=1, max_size=40))
def test_ensemble_equals_the_scalar_solver_to_1e13(cases):
    ps, x0s, v0s = zip(*cases)
    _compare(list(ps), np.array(x0s), np.array(v0s), n_cycles=6)


def test_paper_cases_over_many_cycles():
    ps = [Parameters(M=1, K=1, F=f, b=0.1, a1=-0.1, a2=0.05) for f in (1.0, 0.5)]
    _compare(ps, np.array([1.0, 3.0]), np.zeros(2), n_cycles=500)


def test_every_outcome_is_reported():
    p = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    out = solve_ensemble(
        [1.0, 1.0, 1.0, 1.0], [1.0, 1.0, 100.0, 1.0], [1.0, 1.0, 0.01, 1.0], [0.1, 1.5, 0.1, 0.1],
        [-0.1, -0.1, -0.02, -0.1], [0.05, 0.05, 0.1, 0.05], x0=[1.0, 1.0, 0.021, 0.05], n_cycles=3,
    )
    assert [out.outcome(i) for i in range(4)] == [
        Status.COMPLETED, Status.CHATTERING, Status.TURNED_BACK_IN_ZONE, Status.STOPPED,
    ]
    assert p  # the dict documents the first row


def test_amplitude_can_be_skipped():
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=3, amplitude=False)
    assert np.isnan(out.amplitude).all() and np.isfinite(out.velocity_before_impact).all()


def test_invalid_element_is_named():
    with pytest.raises(ParameterError, match="^b = 2.5"):
        solve_ensemble(1.0, 1.0, 1.0, [0.1, 2.5], -0.1, 0.05, x0=1.0, n_cycles=2)
    with pytest.raises(ValueError, match="element 1"):
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=[1.0, np.nan], n_cycles=2)
