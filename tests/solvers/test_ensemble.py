import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import initial_displacement, initial_velocity, parameters

from escapement.model.parameters import ParameterError, Parameters
from escapement.model.status import Status
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact

NAMES = ("impact_time", "velocity_before_impact", "period", "amplitude")


def _compare(params_list, x0s, v0s, n_cycles):
    arrays = {k: [getattr(p, k) for p in params_list] for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}
    ens = solve_ensemble(**arrays, x0=x0s, v0=v0s, n_cycles=n_cycles)
    for i, p in enumerate(params_list):
        run = solve_exact(p, x0s[i], v0s[i], n_cycles=n_cycles, record_trajectory=False)
        assert ens.outcome(i) == run.status
        n = len(run.cycles)
        for name in NAMES:
            got, want = getattr(ens.cycles, name)[i, :n], getattr(run.cycles, name)
            assert got == pytest.approx(want, rel=1e-13, abs=1e-300), name
            assert np.isnan(getattr(ens.cycles, name)[i, n:]).all()
        assert ens.success[i] == run.success
        if np.isfinite(run.t_final):
            assert ens.t_final[i] == pytest.approx(run.t_final, rel=1e-13)
        else:
            assert ens.t_final[i] == np.inf
        for name in ("turning_point", "margin", "t_accumulation"):
            got, want = getattr(ens, f"exit_{name}")[i], getattr(run.exit, name)
            assert got == pytest.approx(want, rel=1e-12, abs=1e-15, nan_ok=True), name


@settings(max_examples=30)
@given(st.lists(st.tuples(parameters(), initial_displacement, initial_velocity), min_size=1, max_size=40))
def test_ensemble_equals_the_scalar_solver_to_1e13(cases):
    ps, x0s, v0s = zip(*cases)
    _compare(list(ps), np.array(x0s), np.array(v0s), n_cycles=6)


def test_paper_cases_over_many_cycles():
    ps = [Parameters(M=1, K=1, F=f, b=0.1, a1=-0.1, a2=0.05) for f in (1.0, 0.5)]
    _compare(ps, np.array([1.0, 3.0]), np.zeros(2), n_cycles=500)


def test_every_outcome_is_reported_with_its_exit_numbers():
    # rows: the paper's case (a); b = 1.5 (chattering); a weak force and a long zone (turned back, see
    # test_exact); released inside |a1| (stopped); an event bound of 5 (event limit)
    out = solve_ensemble(
        M=1.0, K=[1.0, 1.0, 100.0, 1.0, 1.0], F=[1.0, 1.0, 0.01, 1.0, 1.0], b=[0.1, 1.5, 0.1, 0.1, 0.1],
        a1=[-0.1, -0.1, -0.02, -0.1, -0.1], a2=[0.05, 0.05, 0.1, 0.05, 0.05], x0=[1.0, 1.0, 0.021, 0.05, 1.0],
        n_cycles=3,
    )
    assert [out.outcome(i) for i in range(5)] == [
        Status.COMPLETED, Status.CHATTERING, Status.TURNED_BACK_IN_ZONE, Status.STOPPED, Status.COMPLETED,
    ]
    assert out.status.tolist() == [0, 3, 2, 1, 0]
    assert out.success.tolist() == [True, False, False, False, True]
    # stopped: released at rest at 0.05 m, the swing's radius is 0.05 m, 0.05 m short of |a1| = a3 = 0.1 m
    assert out.exit_turning_point[3] == pytest.approx(0.05, rel=1e-15)
    assert out.exit_margin[3] == pytest.approx(0.05, rel=1e-14)
    assert out.t_final[3] == np.inf
    # turned back: from the impact at a3 = 0.02 m the zone motion about -F/K turns at -F/K - R
    v3 = -10.0 * np.sqrt(0.021**2 - 0.02**2)  # speed at a3 from release at rest at 0.021 m, w = 10
    turning = -1e-4 - np.hypot(0.02 + 1e-4, 0.9 * v3 / 10.0)
    assert out.exit_turning_point[2] == pytest.approx(turning, rel=1e-13)
    assert out.exit_margin[2] == pytest.approx(turning + 0.1, rel=1e-12)
    assert np.isfinite(out.exit_t_accumulation[1]) and np.isnan(out.exit_t_accumulation[[0, 2, 3]]).all()
    limited = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=3, max_events=5)
    assert limited.outcome(0) == Status.EVENT_LIMIT and not limited.success[0]


def test_amplitude_can_be_skipped():
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=3, amplitude=False)
    assert np.isnan(out.cycles.amplitude).all() and np.isfinite(out.cycles.velocity_before_impact).all()
    assert out.cycles.velocity_before_impact.shape == (1, 3)


def test_invalid_element_is_named():
    with pytest.raises(ParameterError, match="^row 1: b = 2.5") as err:
        solve_ensemble(1.0, 1.0, 1.0, [0.1, 2.5], -0.1, 0.05, x0=1.0, n_cycles=2)
    assert (err.value.name, err.value.row) == ("b", 1)
    with pytest.raises(ParameterError, match="^row 1: x0 = nan") as err:
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=[1.0, np.nan], n_cycles=2)
    assert err.value.name == "x0"
    with pytest.raises(ParameterError, match="^x0 = "):
        solve_ensemble(1.0, 1.0, 1.0, [0.1, 0.2], -0.1, 0.05, x0=[1.0, 2.0, 3.0], n_cycles=2)
    with pytest.raises(ParameterError, match="^n_cycles = 0"):
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=0)
