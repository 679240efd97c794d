import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from releases import release_for_zone_turning_at
from strategies import initial_displacement, initial_velocity, parameters

from escapement.model.parameters import ParameterError, Parameters
from escapement.model.status import Status
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision
from escapement.integrators.naive import solve_naive
from escapement.integrators.reference import solve_reference

NAMES = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
CYCLE_COLUMNS = NAMES


def _compare(params_list, x0s, v0s, n_cycles, max_events=None, amplitude=True):
    arrays = {k: [getattr(p, k) for p in params_list] for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}
    ens = solve_ensemble(**arrays, x0=x0s, v0=v0s, n_cycles=n_cycles, max_events=max_events, largest_displacement=amplitude)
    for i, p in enumerate(params_list):
        run = solve_exact(p, x0s[i], v0s[i], n_cycles=n_cycles, max_events=max_events, record_trajectory=False)
        assert ens.outcome(i) == run.status
        n = len(run.cycles)
        for name in NAMES if amplitude else NAMES[:-1]:
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


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(parameters(), initial_displacement, initial_velocity), min_size=1, max_size=30),
       st.sampled_from([None, 1, 6, 57, 97, 130]), st.booleans())
def test_the_cycles_in_lock_step_give_the_scalar_solvers_numbers(cases, max_events, amplitude):
    """Over 40 cycles, with event bounds that end runs inside a cycle and between cycles, with and without
    the amplitude: the trajectories that leave the lock-step cycles (an ending, an arc off the common path)
    and come back at a later cycle than the others are followed as the scalar solver follows them."""
    ps, x0s, v0s = zip(*cases)
    _compare(list(ps), np.array(x0s), np.array(v0s), n_cycles=40, max_events=max_events, amplitude=amplitude)


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
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=3, largest_displacement=False)
    assert np.isnan(out.cycles.largest_displacement).all() and np.isfinite(out.cycles.velocity_before_impact).all()
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


# --- one validation: the ensemble refuses what Parameters and RunLimits refuse, naming the row ----------

GOOD = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=0.0)


@pytest.mark.parametrize(
    "name, bad, requirement",
    [
        ("b", True, "a real number"),
        ("b", "1.0", "a real number"),
        ("M", "1.0", "a real number"),
        ("M", 1e-320, "in [1e-50, 1e+50] (kg)"),  # subnormal: blamed on M, not on K/M
        ("K", 1e60, "in [1e-50, 1e+50] (N/m)"),
        ("F", 5e-324, "0 or of magnitude in [1e-50, 1e+50] (N)"),
        ("b", 1e-13, "1 - b"),
        ("a2", 1e200, "0 or of magnitude in [1e-50, 1e+50] (m)"),
        ("x0", 1e200, "0 or of magnitude in [1e-50, 1e+50] (m)"),
        ("x0", True, "a real number"),
        ("v0", -1e-320, "0 or of magnitude in [1e-50, 1e+50] (m/s)"),
        ("v0", "0", "a real number"),
    ],
)
def test_a_bad_row_is_named_by_its_index_and_parameter(name, bad, requirement):
    columns = {k: [v, v, v] for k, v in GOOD.items()}
    columns[name][2] = bad
    with pytest.raises(ParameterError) as err:
        solve_ensemble(**columns, n_cycles=2)
    assert (err.value.name, err.value.row) == (name, 2)
    assert str(err.value).startswith(f"row 2: {name} = {bad!r} is invalid: {name} must be ")
    assert requirement in err.value.requirement
    # the same value alone is refused by the scalar rules with the same requirement
    with pytest.raises(ParameterError) as scalar:
        if name in ("x0", "v0"):
            solve_exact(Parameters(**{k: v for k, v in GOOD.items() if k not in ("x0", "v0")}),
                        **{**{"x0": 1.0, "v0": 0.0}, name: bad}, n_cycles=2)
        else:
            Parameters(**{k: v for k, v in {**GOOD, name: bad}.items() if k not in ("x0", "v0")})
    assert (scalar.value.name, scalar.value.requirement, scalar.value.row) == (name, err.value.requirement, None)


@pytest.mark.parametrize(
    "counts, name",
    [
        (dict(n_cycles=0), "n_cycles"),
        (dict(n_cycles=-1), "n_cycles"),
        (dict(n_cycles=1.5), "n_cycles"),
        (dict(n_cycles=True), "n_cycles"),
        (dict(n_cycles=np.True_), "n_cycles"),
        (dict(n_cycles="3"), "n_cycles"),
        (dict(n_cycles=10**9 + 1), "n_cycles"),
        (dict(n_cycles=3, max_events=0), "max_events"),
        (dict(n_cycles=3, max_events=-1), "max_events"),
        (dict(n_cycles=3, max_events=2.0), "max_events"),
        (dict(n_cycles=3, max_events=False), "max_events"),
        (dict(n_cycles=3, max_events=5 * 10**9 + 1), "max_events"),
    ],
)
def test_a_bad_count_is_refused_alike_by_the_ensemble_and_every_scalar_solver(counts, name):
    p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    solvers = {
        "ensemble": lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, **counts),
        "exact": lambda: solve_exact(p, 1.0, **counts),
        "reference": lambda: solve_reference(p, 1.0, **counts),
        "high precision": lambda: solve_high_precision(p, 1.0, **counts),
        "naive": lambda: solve_naive(p, 1.0, step=1e-3, **counts),
    }
    if "max_events" in counts:
        del solvers["naive"]  # it takes no event bound
    messages = set()
    for solver, run in solvers.items():
        with pytest.raises(ParameterError) as err:
            run()
        assert err.value.name == name and err.value.row is None, solver
        assert "a positive integer, at most" in err.value.requirement, solver
        messages.add(str(err.value))
    assert len(messages) == 1 and next(iter(messages)).startswith(f"{name} = {counts[name]!r} is invalid")


def test_the_cycle_tables_have_a_stated_size_limit():
    with pytest.raises(ParameterError) as err:
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(1000, 0.05), x0=1.0, n_cycles=50_000)
    assert err.value.name == "n_cycles" and "at most 49_999 for 1_000 trajectories" in err.value.requirement
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, np.full(1000, 0.05), x0=1.0, n_cycles=2)
    assert out.cycles.period.shape == (1000, 2)


def test_amplitude_must_be_a_bool():
    with pytest.raises(ParameterError, match="^largest_displacement = 'no' is invalid: largest_displacement must be True or False"):
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=2, largest_displacement="no")


@pytest.mark.parametrize("path", ["arc_maximum", "hypot"])
def test_a_completed_row_with_a_non_finite_number_is_a_bug_raised(monkeypatch, path):
    """The invariant: completed rows hold only finite numbers; if the arithmetic ever produced
    one, the run raises instead of reporting it as completed. The amplitude made NaN: the ensemble's
    arc_maximum replaced, or NumPy's hypot (the top of an arc's circle, c + hypot(u0, w0)) made NaN."""
    import escapement.solvers.ensemble as ensemble

    if path == "arc_maximum":
        monkeypatch.setattr(ensemble, "arc_maximum", lambda *args: np.full(np.shape(args[1]), np.nan))
    else:
        monkeypatch.setattr(np, "hypot", lambda u, w: np.full(np.shape(u), np.nan))
    with pytest.raises(FloatingPointError, match="^row 0: a completed run holds a non-finite largest_displacement"):
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=2)
    out = solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, x0=1.0, n_cycles=2, largest_displacement=False)  # not computed: NaN
    assert out.success[0] and np.isnan(out.cycles.largest_displacement).all()


@pytest.mark.parametrize("dps", [0, -5, 16, 1.5, True, "50", 1001])
def test_the_digits_of_the_high_precision_solver_are_a_count_too(dps):
    p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    with pytest.raises(ParameterError) as err:
        solve_high_precision(p, 1.0, n_cycles=2, dps=dps)
    assert err.value.name == "dps" and err.value.requirement == "an integer >= 17, at most 1_000"
    assert solve_high_precision(p, 1.0, n_cycles=2, dps=17).success



@pytest.mark.parametrize("params, impact, end", [
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.05, a2=0.1), "a1", "a2"),
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.1, a2=0.05, a3=0.05, a4=-0.1), "a3", "a4"),
])
@pytest.mark.parametrize("amplitude", [True, False])
def test_the_ensemble_follows_the_releases_around_a_turning_point_as_the_scalar_solver(params, impact, end,
                                                                                        amplitude):
    """Releases ulp by ulp around the one whose first zone arc turns exactly at the zone's end, mixed with
    releases whose first zone arc turns well inside or well past it, as one ensemble: some trajectories turn
    back, some pass; each gives the scalar solver's outcome and numbers (to rounding: NumPy's arctan2 and
    hypot)."""
    x0 = release_for_zone_turning_at(params, impact, mpmath.mpf(getattr(params, end)))
    releases = np.array([x0 + k * math.ulp(x0) for k in range(-60, 61)] + [0.9 * x0, 1.1 * x0, 2 * x0, x0 / 3])
    ens = solve_ensemble(*(getattr(params, k) for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")), x0=releases,
                         n_cycles=6, largest_displacement=amplitude)
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


def test_inputs_too_large_are_refused_from_their_shapes_before_any_array_is_made():
    """10**8 trajectories given as a broadcast view (no memory of its own): refused naming the trajectories,
    with no allocation at their size (tracemalloc's peak stays below 1 MB)."""
    import tracemalloc

    from escapement.model.limits import MemoryBudgetError

    tracemalloc.start()
    with pytest.raises(MemoryBudgetError, match=r"^trajectories = 100000000 is invalid: trajectories must be at most"):
        solve_ensemble(M=1.0, K=1.0, F=np.broadcast_to(1.0, (10**8,)), b=0.1, a1=-0.1, a2=0.05, n_cycles=1)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 1_000_000, peak


def test_a_budget_below_one_trajectory_of_one_cycle_names_the_budget():
    from escapement.model.limits import MemoryBudgetError
    from escapement.solvers.ensemble import ensemble_bytes

    with pytest.raises(MemoryBudgetError, match=rf"^memory_budget = 10 is invalid: memory_budget must be at least "
                                                rf"{ensemble_bytes(1, 1):_} bytes"):
        solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, n_cycles=1, memory_budget=10)
