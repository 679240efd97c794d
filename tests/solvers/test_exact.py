import math

import mpmath
import numpy as np
import pytest

from escapement.model.events import EventKind
from escapement.model.parameters import ParameterError, Parameters
from escapement.model.status import Status
from escapement.paper.printed import poincare_map_16
from escapement.solvers.exact import solve_exact
from escapement.solvers.result import ArcTable


def relative(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))


def test_first_impact_time_from_rest_is_the_closed_form(case_a):
    # From x0 = 1 at rest, x = cos t reaches a3 = 0.1 moving left at t = acos(0.1).
    s = solve_exact(case_a, 1.0, n_cycles=1)
    assert s.events.kind[0] == EventKind.IMPACT_A3
    assert s.events.t[0] == pytest.approx(math.acos(0.1), rel=1e-15)
    assert s.events.v_before[0] == pytest.approx(-math.sqrt(1 - 0.01), rel=1e-15)


@pytest.mark.parametrize(
    "params, x0",
    [
        (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 1.0),
        (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
        (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), 0.8),
    ],
)
def test_cycles_follow_the_map_of_eq16_to_1e13_over_10_000_cycles(params, x0):
    s = solve_exact(params, x0, n_cycles=10_000, record_trajectory=False)
    assert s.status == Status.COMPLETED
    v = s.cycles.velocity_before_impact
    assert len(v) == 10_000
    predicted = np.array([poincare_map_16(vk, params) for vk in v[:-1]])
    assert np.max(relative(v[1:], predicted)) < 1e-13


def _energy(p, x, v):
    return 0.5 * p.M * v**2 + 0.5 * p.K * x**2


def _speeds_before_impacts_by_energy(p, x0, n):
    """|v-| at the first ``n`` impacts from rest at x0 > a3, by energy alone, written out here.

    Released at rest at x0, the mass swings left freely to a3: (1/2) M v^2 + (1/2) K a3^2 = (1/2) K x0^2, so
    v-(1)^2 = (K/M)(x0^2 - a3^2). An impact v+ = (1 - b) v- takes (1 - (1-b)^2) M v-^2 / 2 of the energy. On the
    way from a3 to a1 the force F pushes the mass through the zone [a4, a3] (it gives F (a3 - a4)), and from
    a1 back to a3 through [a1, a2] (F (a2 - a1)); the spring's energy is (1/2) K x^2 at the impact position.
    So E-(k+1) = E-(k) - (1 - (1-b)^2) M v-(k)^2 / 2 + F zone(k), and v-(k+1)^2 = 2 (E-(k+1) - K x(k+1)^2 / 2) / M.
    Sums of a few terms of like size: math.fsum keeps them exact to the last rounding.
    """
    positions, zones = (p.a3, p.a1), (p.a3 - p.a4, p.a2 - p.a1)
    speeds = [math.sqrt(p.K / p.M * math.fsum([x0 * x0, -p.a3 * p.a3]))]
    for k in range(n - 1):
        x, x_next = positions[k % 2], positions[(k + 1) % 2]
        energy = math.fsum([0.5 * p.M * speeds[-1] ** 2, 0.5 * p.K * x * x])
        loss = (1 - (1 - p.b) ** 2) * 0.5 * p.M * speeds[-1] ** 2
        after = math.fsum([energy, -loss, p.F * zones[k % 2], -0.5 * p.K * x_next * x_next])
        speeds.append(math.sqrt(2 * after / p.M))
    return np.array(speeds)


@pytest.mark.parametrize(
    "params",
    [
        Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05),
        Parameters(M=2.5, K=0.4, F=0.3, b=0.6, a1=-0.3, a2=-0.1, a3=0.2, a4=0.05),
    ],
)
def test_speeds_before_impacts_follow_the_energy_balance_derived_by_hand(params):
    """From one impact to the next: E drops by the impact loss and rises by F times the zone length."""
    s = solve_exact(params, 1.5, n_cycles=200)
    assert s.status == Status.COMPLETED
    ev = s.events
    impacts = np.flatnonzero((ev.kind == EventKind.IMPACT_A1) | (ev.kind == EventKind.IMPACT_A3))
    # the impacts alternate from a3 (the first) to a1; 200 cycles between impacts at a1 end at the 201st
    assert np.array_equal(ev.kind[impacts], np.tile([EventKind.IMPACT_A3, EventKind.IMPACT_A1], 201))
    expected = _speeds_before_impacts_by_energy(params, 1.5, len(impacts))
    assert np.abs(ev.v_before[impacts]) == pytest.approx(expected, rel=1e-12)
    assert np.abs(ev.v_after[impacts]) == pytest.approx((1 - params.b) * expected, rel=1e-12)


def test_energy_is_conserved_along_each_arc(case_a):
    """Sampled inside each arc: free flight keeps E, the zones keep E -/+ F x."""
    s = solve_exact(case_a, 1.0, n_cycles=20)
    arcs = s.trajectory
    ends = np.append(arcs.t_start[1:], s.t_final)
    for t0, t1, c in zip(arcs.t_start, ends, arcs.centre):
        t = np.linspace(t0, t1, 7)[1:-1]
        x, v, a = s.sample(t)
        invariant = _energy(case_a, x, v) - case_a.K * c * x
        assert np.ptp(invariant) < 1e-13 * np.max(np.abs(invariant))
        assert a == pytest.approx(-case_a.omega2 * (x - c), rel=1e-12, abs=1e-15)


def test_samples_are_continuous_in_x_and_jump_in_v_at_impacts(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=5)
    assert s.t_final == s.events.t[-1]  # the run ends at its last impact, whose aftermath is not computed
    for t_ev, vb, va in zip(s.events.t[:-1], s.events.v_before[:-1], s.events.v_after[:-1]):
        x, v, _ = s.sample(np.array([t_ev - 1e-9, t_ev]))
        assert x[0] == pytest.approx(x[1], abs=2e-9)
        assert v[0] == pytest.approx(vb, abs=1e-8)
        assert v[1] == pytest.approx(va, rel=1e-14)


def test_event_order_is_impact_zone_end_in_turn(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=30)
    kinds = list(s.events.kind)
    cycle = [EventKind.IMPACT_A3, EventKind.ZONE_END_A4, EventKind.IMPACT_A1, EventKind.ZONE_END_A2]
    assert kinds == [int(cycle[i % 4]) for i in range(len(kinds))]


def test_amplitude_is_the_right_turning_point_of_the_free_swing(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=10)
    ev = s.events
    a2_exits = ev.v_before[ev.kind == EventKind.ZONE_END_A2][: len(s.cycles)]
    expected = np.hypot(case_a.a2, a2_exits / case_a.omega)
    assert s.cycles.largest_displacement == pytest.approx(expected, rel=1e-14)


def test_stopped_when_the_initial_swing_never_reaches_an_impact_position(case_a):
    s = solve_exact(case_a, 0.05, n_cycles=10)
    assert s.status == Status.STOPPED
    assert "never passes the next impact position, a1 = -0.1 m (moving right) or a3 = 0.1 m" in s.message
    assert len(s.events) == 0 and len(s.cycles) == 0
    assert s.t_final == math.inf
    assert s.exit.turning_point == pytest.approx(0.05)
    x, v, _ = s.sample(np.array([1.0, 100.0]))
    assert x == pytest.approx(0.05 * np.cos([1.0, 100.0]), rel=1e-12)


def test_stopped_later_when_a_weak_force_cannot_keep_up_an_asymmetric_swing():
    # No force: every impact takes energy, and the far impact position a3 = 0.3 m is soon out of reach.
    p = Parameters(M=1, K=1, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0)
    s = solve_exact(p, 1.0, n_cycles=100)
    assert s.status == Status.STOPPED
    assert len(s.events) > 2
    # The escapement alternates: after the impulse at a1 it waits for a3, which the swing no longer reaches.
    assert s.events.kind[-1] == EventKind.ZONE_END_A2
    assert "a3 = 0.3 m (moving left)" in s.message and "a1 =" not in s.message
    radius = s.exit.turning_point
    assert radius == pytest.approx(math.hypot(s.events.x[-1], s.events.v_after[-1]), rel=1e-14)
    assert 0 < s.exit.margin == pytest.approx(0.3 - radius, rel=1e-14)


def test_turned_back_inside_the_zone():
    # a1 = -0.02 m close to the centre, a long zone to a4 = -0.1 m and a weak force: the swing entering the
    # left zone at a3 = 0.02 m turns at about -0.021 m, far short of a4.
    p = Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1)
    s = solve_exact(p, 0.021, n_cycles=3)
    assert s.status == Status.TURNED_BACK_IN_ZONE
    assert "(a4, a3)" in s.message
    x, v, _ = s.sample(np.array([s.t_final]))
    assert v[0] == pytest.approx(0.0, abs=1e-14)
    assert x[0] == pytest.approx(s.exit.turning_point, rel=1e-13)
    assert p.a4 < x[0] < p.a3


def test_b_equal_one_brings_the_mass_to_rest_at_the_impact_and_the_map_converges_in_one_cycle(case_a):
    p = Parameters(M=1, K=1, F=1, b=1.0, a1=-0.1, a2=0.05)
    s = solve_exact(p, 1.0, n_cycles=5)
    assert s.status == Status.COMPLETED
    assert np.all(s.events.v_after[(s.events.kind == 1) | (s.events.kind == 3)] == 0.0)
    # From rest at a1 the zone and the spring give v^2 = 2 f (a2 - a1) at the next impact (symmetric case).
    assert s.cycles.velocity_before_impact[1:] == pytest.approx(math.sqrt(2 * 1.0 * 0.15), rel=1e-14)


def test_chattering_when_the_impact_reverses_the_velocity():
    p = Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05)
    s = solve_exact(p, 1.0, n_cycles=5)
    assert s.status == Status.CHATTERING
    assert "Zeno" in s.message
    t_hit, speed = s.events.t[-1], abs(s.events.v_after[-1])
    with mpmath.workdps(30):
        x = mpmath.mpf(speed) / mpmath.mpf(0.1)
        total, term = mpmath.mpf(0), x
        while term > mpmath.mpf("1e-20"):
            total += mpmath.atan(term)
            term *= mpmath.mpf(0.5)
        total += 2 * term
    assert s.exit.t_accumulation == pytest.approx(t_hit + 2 * float(total), rel=1e-14)


def test_chattering_accumulates_in_finite_time_for_b_close_to_two():
    # b = 1.999999: each rebound keeps 0.999999 of the speed, yet the rebounds accumulate in finite time
    p = Parameters(M=1, K=1, F=0.1, b=1.999999, a1=-0.1, a2=-0.05)
    s = solve_exact(p, 1.0, n_cycles=5)
    assert s.status == Status.CHATTERING and "Zeno" in s.message
    assert math.isfinite(s.exit.t_accumulation) and s.exit.t_accumulation > s.events.t[-1]


def test_t_end_ends_the_run_inside_an_arc(case_a):
    s = solve_exact(case_a, 1.0, t_end=20.0)
    assert s.status == Status.COMPLETED
    assert s.t_final == 20.0
    assert s.events.t[-1] <= 20.0
    x, v, _ = s.sample(np.array([20.0, 20.0 + 1e-9]))
    assert np.isfinite(x[0]) and np.isnan(x[1])


def test_event_limit_is_a_typed_outcome(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=100, max_events=3)
    assert s.status == Status.EVENT_LIMIT
    assert len(s.events) == 3
    assert "max_events = 3" in s.message


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(n_cycles=0), "n_cycles"),
        (dict(n_cycles=2.5), "n_cycles"),
        (dict(t_end=-1.0), "t_end"),
        (dict(t_end=math.inf), "t_end"),
        (dict(), "n_cycles"),
        (dict(n_cycles=3, max_events=0), "max_events"),
    ],
)
def test_invalid_run_limits_are_rejected_before_any_work(case_a, kwargs, name):
    with pytest.raises(ParameterError, match=f"^{name} = "):
        solve_exact(case_a, 1.0, **kwargs)


def test_invalid_initial_state_is_rejected(case_a):
    with pytest.raises(ParameterError, match="^x0 = nan"):
        solve_exact(case_a, math.nan, n_cycles=1)


def test_params_must_be_parameters():
    with pytest.raises(TypeError, match="Parameters"):
        solve_exact({"M": 1}, 1.0, n_cycles=1)


def test_a_release_on_an_impact_surface_is_the_state_after_any_jump(case_a):
    """Eq. (2) gives the initial state at t0+: a release at a3 moving left is not an impact at t = 0."""
    s = solve_exact(case_a, 0.1, -1.0, n_cycles=2)
    assert s.events.t[0] > 0
    assert s.events.kind[0] == EventKind.IMPACT_A1


def test_a_completed_run_has_no_exit_numbers_and_success(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=3)
    assert s.success and s.message == "completed 3 cycles"
    assert math.isnan(s.exit.turning_point) and math.isnan(s.exit.margin) and math.isnan(s.exit.t_accumulation)
    assert isinstance(s.trajectory, ArcTable) and s.method == "exact"
    assert (s.x0, s.v0) == (1.0, 0.0)
    # n_cycles complete cycles: n_cycles + 1 impacts at a1
    assert len(s.cycles) == 3 and len(s.events.of_kind(EventKind.IMPACT_A1)) == 4
    assert s.cycles.cycle.tolist() == [1, 2, 3]


def test_without_a_trajectory_sampling_is_refused(case_a):
    s = solve_exact(case_a, 1.0, n_cycles=3, record_trajectory=False)
    assert s.trajectory is None
    with pytest.raises(ValueError, match="record_trajectory=True"):
        s.sample(np.array([1.0]))


def test_a_failed_run_is_not_success(case_a):
    s = solve_exact(case_a, 0.05, n_cycles=3)
    assert not s.success and s.status.code == 1
    assert s.exit.margin == pytest.approx(0.1 - 0.05)


@pytest.mark.parametrize("params, x0", [
    (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 1.0),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), 0.8),
])
def test_the_amplitude_is_the_top_of_the_free_swing_from_a2(params, x0):
    """In a regular cycle only the free arc from a2 to a3 passes the top of its circle, so the amplitude is
    its radius sqrt(a2**2 + (v2 / w)**2), with v2 at a2 from energy through the zone (a1, a2) about c = F/K:
    v2**2 = ((1 - b) v1)**2 + w**2 ((a1 - c)**2 - (a2 - c)**2), v1 the velocity before the impact at a1."""
    s = solve_exact(params, x0, n_cycles=200, record_trajectory=False)
    with mpmath.workdps(40):
        w2 = mpmath.mpf(params.K) / mpmath.mpf(params.M)
        c, a1, a2 = mpmath.mpf(params.F) / mpmath.mpf(params.K), mpmath.mpf(params.a1), mpmath.mpf(params.a2)
        for v1, amplitude in zip(s.cycles.velocity_before_impact, s.cycles.largest_displacement):
            v2_sq = ((1 - mpmath.mpf(params.b)) * mpmath.mpf(v1)) ** 2 + w2 * ((a1 - c) ** 2 - (a2 - c) ** 2)
            assert amplitude == pytest.approx(float(mpmath.sqrt(a2**2 + v2_sq / w2)), rel=2e-15)


def test_the_event_log_and_the_arcs_are_the_stored_buffers_not_copies(case_a):
    """The times and the velocities before the events are arrays over the loop's own buffers (no copy), and
    the arcs start at the release and at each event, the same numbers."""
    s = solve_exact(case_a, 1.0, n_cycles=100)
    for column in (s.events.t, s.events.v_before):
        assert not column.flags.owndata and column.base is not None  # over the loop's buffer
    assert len(s.trajectory.t_start) == len(s.events) and s.trajectory.t_start[0] == 0.0
    assert s.trajectory.t_start[1:].tolist() == s.events.t[:-1].tolist()


def test_a_run_over_its_memory_budget_is_refused_before_any_work(case_a):
    from escapement.model.limits import MemoryBudgetError

    with pytest.raises(MemoryBudgetError) as err:
        solve_exact(case_a, 1.0, n_cycles=10_000, memory_budget=1_000_000)
    assert (err.value.name, err.value.value, err.value.budget) == ("n_cycles", 10_000, 1_000_000)
    assert err.value.estimate > 1_000_000 and isinstance(err.value, ParameterError)
    assert solve_exact(case_a, 1.0, n_cycles=10_000, record_trajectory=False, memory_budget=10_000_000).success


@pytest.mark.parametrize("flag", ["no", "False", 0, 1, None])
def test_a_trajectory_flag_that_is_not_a_bool_is_refused(flag):
    """A string such as "no" is truthy: taken as a flag it would keep the trajectory the caller refused."""
    p = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
    message = r"^record_trajectory = .* is invalid: record_trajectory must be True or False"
    with pytest.raises(ParameterError, match=message):
        solve_exact(p, 1.0, n_cycles=2, record_trajectory=flag)
    assert solve_exact(p, 1.0, n_cycles=2, record_trajectory=np.bool_(False)).trajectory is None
