"""The exact solver against closed forms derived by hand: the map of Eq. (16), the energy balance of the impacts
and the zones, the arcs, the amplitude, where the speed is regained, what a run holds (how it ends: test_kernel.py);
the geometry's conventions, the paper's signs a1 < 0 < a3 and the jump set read by the direction of motion for any
other placement; and the stopping rules at their exact boundaries and one ulp or one event either side (an event or
a turn back on ``t_end``, ``n_cycles``, ``max_events``; in the run, its stream and the ensemble), the times closed
forms (from rest at ``x0`` the free arc ``x0 cos(w t)`` reaches ``a1`` at ``arccos(a1 / x0) / w``, the zone arc about
``F / K`` turns where its velocity vanishes), the counts the automaton's (``n`` cycles from the left: ``4 n + 1``).
"""

import math

import numpy as np
import pytest

from escapement import iter_cycles, solve_ensemble, solve_reference
from escapement.model.limits import MAX_CYCLES, MAX_EVENTS, MemoryBudgetError
from escapement.model.arguments import ParameterError
from escapement.solvers.kernel import BLOCK_EVENTS
from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper.corrected import velocity_recovery
from escapement.paper.printed import poincare_map_16
from escapement.solvers.describe import ArcTable
from escapement.solvers.exact import solve_exact

PAPER = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)


@pytest.mark.parametrize("params, x0", [(PAPER, 1.0), (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
                                        (ASYMMETRIC, 0.8)])
def test_cycles_follow_the_map_of_eq16_to_1e13_over_10_000_cycles(params, x0):
    s = solve_exact(params, x0, n_cycles=10_000, record_trajectory=False)
    v = s.cycles.velocity_before_impact
    assert s.status == Status.COMPLETED and len(v) == 10_000
    predicted = np.array([poincare_map_16(vk, params) for vk in v[:-1]])
    assert np.max(np.abs(v[1:] - predicted) / predicted) < 1e-13


def _speeds_before_impacts_by_energy(p, x0, n):
    """|v-| at the first ``n`` impacts from rest at x0 > a3, by energy alone: the free swing to a3 gives
    v-(1)^2 = (K/M)(x0^2 - a3^2); an impact takes (1 - (1-b)^2) M v-^2 / 2 of E = M v^2 / 2 + K x^2 / 2, the zone
    it opens gives F (a3 - a4) after a3 and F (a2 - a1) after a1, and v-(k+1)^2 = 2 (E-(k+1) - K x(k+1)^2 / 2) / M."""
    positions, zones = (p.a3, p.a1), (p.a3 - p.a4, p.a2 - p.a1)
    speeds = [math.sqrt(p.K / p.M * math.fsum([x0 * x0, -p.a3 * p.a3]))]
    for k in range(n - 1):
        x, x_next = positions[k % 2], positions[(k + 1) % 2]
        energy = math.fsum([0.5 * p.M * speeds[-1] ** 2, 0.5 * p.K * x * x])
        loss = (1 - (1 - p.b) ** 2) * 0.5 * p.M * speeds[-1] ** 2
        after = math.fsum([energy, -loss, p.F * zones[k % 2], -0.5 * p.K * x_next * x_next])
        speeds.append(math.sqrt(2 * after / p.M))
    return np.array(speeds)


@pytest.mark.parametrize("params", [PAPER, Parameters(M=2.5, K=0.4, F=0.3, b=0.6, a1=-0.3, a2=-0.1, a3=0.2, a4=0.05)])
def test_speeds_before_impacts_follow_the_energy_balance_derived_by_hand(params):
    """From one impact to the next: E drops by the impact loss and rises by F times the zone length."""
    s = solve_exact(params, 1.5, n_cycles=200)
    ev = s.events
    impacts = np.flatnonzero((ev.kind == EventKind.IMPACT_A1) | (ev.kind == EventKind.IMPACT_A3))
    # the impacts alternate from a3 (the first) to a1; 200 cycles between impacts at a1 end at the 201st
    assert s.status == Status.COMPLETED
    assert np.array_equal(ev.kind[impacts], np.tile([EventKind.IMPACT_A3, EventKind.IMPACT_A1], 201))
    expected = _speeds_before_impacts_by_energy(params, 1.5, len(impacts))
    assert np.abs(ev.v_before[impacts]) == pytest.approx(expected, rel=1e-12)
    assert np.abs(ev.v_after[impacts]) == pytest.approx((1 - params.b) * expected, rel=1e-12)


def test_energy_is_conserved_along_each_arc_and_x_is_continuous_at_the_events():
    """Inside each arc free flight keeps E, the zones E -/+ F x; across an event x is continuous, v jumps to v+."""
    s = solve_exact(PAPER, 1.0, n_cycles=20)
    arcs = s.trajectory
    for t0, t1, c in zip(arcs.t_start, np.append(arcs.t_start[1:], s.t_final), arcs.centre):
        x, v, a = s.sample(np.linspace(t0, t1, 7)[1:-1])
        invariant = 0.5 * PAPER.M * v**2 + 0.5 * PAPER.K * x**2 - PAPER.K * c * x
        assert np.ptp(invariant) < 1e-13 * np.max(np.abs(invariant))
        assert a == pytest.approx(-PAPER.omega2 * (x - c), rel=1e-12, abs=1e-15)
    for t_ev, vb, va in zip(s.events.t[:-1], s.events.v_before[:-1], s.events.v_after[:-1]):
        x, v, _ = s.sample(np.array([t_ev - 1e-9, t_ev]))
        assert x[0] == pytest.approx(x[1], abs=2e-9) and v[0] == pytest.approx(vb, abs=1e-8)
        assert v[1] == pytest.approx(va, rel=1e-14)
    assert s.t_final == s.events.t[-1]  # the run ends at its last impact


@pytest.mark.parametrize("params, x0", [(PAPER, 1.0), (ASYMMETRIC, 0.8)])
def test_the_amplitude_is_the_top_of_the_free_swing_from_a2(params, x0):
    """Only the free arc from a2 to a3 passes the top of its circle, sqrt(a2**2 + (v2 / w)**2), energy through the
    zone (a1, a2) about c = F/K giving v2**2 = ((1 - b) v1)**2 + w**2 ((a1 - c)**2 - (a2 - c)**2) from v1 at a1."""
    s = solve_exact(params, x0, n_cycles=200, record_trajectory=False)
    w2, c, a1, a2 = params.omega2, params.F / params.K, params.a1, params.a2
    v2_sq = ((1 - params.b) * s.cycles.velocity_before_impact) ** 2 + w2 * ((a1 - c) ** 2 - (a2 - c) ** 2)
    assert s.cycles.largest_displacement == pytest.approx(np.sqrt(a2**2 + v2_sq / w2), rel=2e-15)


def test_a_run_stops_later_when_no_force_keeps_up_an_asymmetric_swing():
    # F = 0: the radius R of the free swing only shrinks, R^2 -> a^2 + r^2 (R^2 - a^2) at an impact at a;
    # impacts alternate a3 = 0.3 m and a1 = -0.1 m, each followed by its zone end, until R <= a3 when a3 is awaited
    s = solve_exact(Parameters(M=1, K=1, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0), 1.0, n_cycles=100)
    radius_sq, events, awaited = 1.0, 0, 0.3
    while radius_sq > awaited**2:
        radius_sq = awaited**2 + 0.81 * (radius_sq - awaited**2)
        events, awaited = events + 2, 0.1 if awaited == 0.3 else 0.3
    assert s.status == Status.STOPPED and len(s.events) == events and s.events.kind[-1] == EventKind.ZONE_END_A2
    assert s.exit.turning_point == pytest.approx(math.sqrt(radius_sq), rel=1e-13)  # its message: test_kernel.py


def test_b_equal_one_brings_the_mass_to_rest_at_the_impact_and_the_map_converges_in_one_cycle():
    s = solve_exact(Parameters(M=1, K=1, F=1, b=1.0, a1=-0.1, a2=0.05), 1.0, n_cycles=5)
    assert s.status == Status.COMPLETED
    assert np.all(s.events.v_after[(s.events.kind == 1) | (s.events.kind == 3)] == 0.0)
    # From rest at a1 the zone and the spring give v^2 = 2 f (a2 - a1) at the next impact (symmetric case).
    assert s.cycles.velocity_before_impact[1:] == pytest.approx(math.sqrt(2 * 1.0 * 0.15), rel=1e-14)


def test_a_release_on_an_impact_surface_is_the_state_after_any_jump():
    """Eq. (2) gives the initial state at t0+: a release at a3 moving left is not an impact at t = 0."""
    s = solve_exact(PAPER, 0.1, -1.0, n_cycles=2)
    assert s.events.t[0] > 0 and s.events.kind[0] == EventKind.IMPACT_A1


def test_a_completed_run_holds_its_events_cycles_and_arcs():
    s = solve_exact(PAPER, 1.0, n_cycles=100)
    assert isinstance(s.trajectory, ArcTable) and s.method == "exact" and (s.x0, s.v0) == (1.0, 0.0)
    # n_cycles complete cycles: n_cycles + 1 impacts at a1, numbered from 1
    assert len(s.events.of_kind(EventKind.IMPACT_A1)) == 101 and s.cycles.cycle.tolist() == list(range(1, 101))
    # the arcs start at the release and at each event, over the loop's own buffers (no copy)
    assert s.trajectory.t_start[0] == 0.0 and s.trajectory.t_start[1:].tolist() == s.events.t[:-1].tolist()
    assert all(not column.flags.owndata and column.base is not None for column in (s.events.t, s.events.v_before))
    assert solve_exact(PAPER, 1.0, n_cycles=2, record_trajectory=np.bool_(False)).trajectory is None


@pytest.mark.parametrize("K, F", [(0.1, 0.5), (1.0, 0.5), (10.0, 0.5), (1.0, 1.0)])
def test_the_solver_regains_the_speed_before_the_impact_where_the_closed_form_says(K, F):
    p = Parameters(M=1.0, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)
    s = solve_exact(p, -1.0, n_cycles=300)  # converged to the limit cycle well within 300 cycles
    t_impact, v1 = s.cycles.impact_time[-2], s.cycles.velocity_before_impact[-2]
    x, dt = velocity_recovery(v1, p)
    assert p.a1 < x <= p.a2 and dt > 0  # inside the zone, after the impact
    (x_at, x_before), (v_at, v_before), _ = s.sample(np.array([t_impact + dt, t_impact + 0.999 * dt]))
    assert x_at == pytest.approx(x, abs=1e-10)
    assert v_at == pytest.approx(v1, abs=1e-10)
    assert v_before < v1  # not regained earlier: after the impact, (1 - b) v1 rises to v1 only there


# --- the geometry's conventions ----------------------------------------------------------------------------------

BASE = dict(M=1.0, K=1.0, F=1.0, b=0.1)
#: placements outside the paper's signs, (a1, a2, a3, a4), m: impacts after the equilibrium (the audit's a1 = 0.1,
#: a2 = 0.2; the escapement-error study's zone after it), a3 < a1 < 0, both left of the centre, one at it
OUTSIDE = [(0.1, 0.2, -0.1, -0.2), (0.05, 0.2, -0.05, -0.2), (-0.1, 0.05, -0.3, -0.4), (-0.2, -0.1, -0.05, -0.3),
           (0.0, 0.1, 0.1, -0.1)]
#: the paper's geometry (its Fig. 2) and the placements the workflow runs (the checks' positions in config/paper.yaml)
PAPER_SIGNS = [(-0.1, 0.05, 0.1, -0.05), (-0.1, 0.05, 0.2, -0.02), (-0.15, 0.0, 0.08, -0.1), (-0.1, 0.05, 0.3, 0.0),
               (-0.3, 0.2, 0.3, -0.2), (-0.05, 0.01, 0.05, -0.01)]
#: the escapement-error study's zones (a1, a2) by name, the second half cycle mirroring the first
ZONES = {"paper": (-0.1, 0.05), "symmetric": (-0.1, 0.1), "before": (-0.2, -0.05), "after": (0.05, 0.2)}


def test_the_papers_signs_are_said_for_each_placement_run():
    assert all(Parameters(**BASE, **dict(zip(("a1", "a2", "a3", "a4"), p))).paper_signs for p in PAPER_SIGNS)
    signs = {name: Parameters(**BASE, a1=a1, a2=a2).paper_signs for name, (a1, a2) in ZONES.items()}
    assert signs == {"paper": True, "symmetric": True, "before": True, "after": False}


def test_an_impact_after_the_equilibrium_is_met_moving_right_at_a1():
    """a1 = 0.1 m, a2 = 0.2 m (a3 = -0.1, a4 = -0.2 by symmetry), F = 0, K = M = 1, released at rest at -1 m:
    x = -cos t reaches a1 moving right at t = acos(-0.1) with v = sqrt(1 - 0.01): x v > 0, outside the paper's
    S. With F = 0 the radius after the impact is sqrt(0.01 + 0.81 * 0.99), so a3 = -0.1 is met moving left at
    v = -0.9 sqrt(0.99)."""
    p = Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=0.1, a2=0.2)
    assert not p.paper_signs
    run = solve_exact(p, -1.0, t_end=6.0)
    kinds = [EventKind(int(k)) for k in run.events.kind[:3]]
    assert kinds == [EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3]
    assert run.events.t[0] == pytest.approx(math.acos(-0.1), rel=1e-14)
    assert run.events.v_before[0] == pytest.approx(math.sqrt(0.99), rel=1e-14)
    assert run.events.x[0] * run.events.v_before[0] > 0
    assert run.events.v_before[2] == pytest.approx(-0.9 * math.sqrt(0.99), rel=1e-13)


def test_an_impact_at_a3_left_of_a1_is_met_moving_left():
    """a3 = -0.3 m < a1 = -0.1 m, F = 0, released at rest at 1 m: x = cos t passes a1 moving left (an impact
    there is met moving right only) and strikes a3 at t = acos(-0.3) with v = -sqrt(1 - 0.09)."""
    p = Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=-0.3, a4=-0.4)
    assert not p.paper_signs
    run = solve_exact(p, 1.0, n_cycles=2)
    assert EventKind(int(run.events.kind[0])) == EventKind.IMPACT_A3
    assert run.events.t[0] == pytest.approx(math.acos(-0.3), rel=1e-14)
    assert run.events.v_before[0] == pytest.approx(-math.sqrt(0.91), rel=1e-14)


@pytest.mark.parametrize("positions", OUTSIDE + PAPER_SIGNS)
def test_impacts_and_zone_ends_are_met_in_their_direction_and_on_the_papers_set_only_with_its_signs(positions):
    p = Parameters(**BASE, **dict(zip(("a1", "a2", "a3", "a4"), positions)))
    run = solve_exact(p, -1.0, n_cycles=5)
    assert run.status == Status.COMPLETED
    direction = {EventKind.IMPACT_A1: 1, EventKind.ZONE_END_A2: 1, EventKind.IMPACT_A3: -1, EventKind.ZONE_END_A4: -1}
    expected = np.array([direction[EventKind(int(k))] for k in run.events.kind])
    np.testing.assert_array_equal(np.sign(run.events.v_before), expected)
    impacts = np.isin(run.events.kind, [EventKind.IMPACT_A1, EventKind.IMPACT_A3])
    on_papers_set = run.events.x[impacts] * run.events.v_before[impacts] < 0
    assert on_papers_set.all() == p.paper_signs


@pytest.mark.parametrize("positions", OUTSIDE)
def test_the_mirror_image_of_a_placement_runs_as_its_mirror(positions):
    """Under x -> -x, (a1, a2, a3, a4) from x0 runs as (-a3, -a4, -a1, -a2) from -x0: a1's impacts become a3's."""
    a1, a2, a3, a4 = positions
    p = Parameters(**BASE, a1=a1, a2=a2, a3=a3, a4=a4)
    q = Parameters(**BASE, a1=-a3, a2=-a4, a3=-a1, a4=-a2)
    one, two = solve_exact(p, 1.0, t_end=40.0), solve_exact(q, -1.0, t_end=40.0)
    swap = {1: 3, 2: 4, 3: 1, 4: 2}
    assert len(one.events) == len(two.events) > 8
    np.testing.assert_array_equal([swap[int(k)] for k in one.events.kind], two.events.kind)
    np.testing.assert_allclose(one.events.t, two.events.t, rtol=1e-12)
    np.testing.assert_allclose(one.events.x, -two.events.x, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(one.events.v_before, -two.events.v_before, rtol=1e-10)


@pytest.mark.parametrize("positions", OUTSIDE[:3])
def test_outside_the_papers_signs_the_solvers_agree(positions):
    """The exact closed forms, a numerical integration of the same automaton and the ensemble's lock-step."""
    values = dict(zip(("a1", "a2", "a3", "a4"), positions))
    p = Parameters(**BASE, **values)
    exact = solve_exact(p, -1.0, n_cycles=4)
    ivp = solve_reference(p, -1.0, n_cycles=4, rtol=1e-12, record_trajectory=False)
    ensemble = solve_ensemble(**BASE, **values, x0=-1.0, n_cycles=4)
    np.testing.assert_allclose(ivp.cycles.period, exact.cycles.period, rtol=1e-9)
    np.testing.assert_allclose(ensemble.cycles.period[0], exact.cycles.period, rtol=1e-12)


# --- the stopping rules ------------------------------------------------------------------------------------------

#: Fig. 3 (a) as the configuration runs it (w = 1 rad/s), released from rest at x0 = -1 m
FIG3A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
X0 = -1.0
#: a weak force and a long zone: from rest at -0.3 m the mass turns back inside (a1, a2) after the first impact
WEAK = Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.1, a2=0.5)
X0_WEAK = -0.3


def first_impact_time(x0: float, a1: float) -> float:
    """From rest at ``x0 < a1 < 0`` (w = 1, free arc about 0): ``x0 cos t = a1``."""
    return float(np.arccos(a1 / x0))


def turn_back_time(x0: float, p: Parameters) -> float:
    """The first impact at a1, then the arc about ``c = F / K`` from ``a1 - c`` at ``(1 - b) v``, ``v = sqrt(x0**2 -
    a1**2)``, turns after the angle ``atan2((1 - b) v, a1 - c)`` (w = 1)."""
    v_after = (1.0 - p.b) * np.sqrt(x0**2 - p.a1**2)
    return first_impact_time(x0, p.a1) + float(np.arctan2(v_after, p.a1 - p.F / p.K))


def below(t: float) -> float:
    return float(np.nextafter(t, -np.inf))


def above(t: float) -> float:
    return float(np.nextafter(t, np.inf))


def events_of(n_cycles: int) -> int:
    """From the left (the first event the impact at a1), ``n`` cycles end at the ``(n + 1)``-th impact at a1."""
    return 4 * n_cycles + 1


def test_the_closed_forms_are_the_solver_s_doubles():
    """The boundaries below are exact only if the solver's numbers are the closed forms' to the last bit."""
    t1 = first_impact_time(X0, FIG3A.a1)
    assert solve_exact(FIG3A, X0, t_end=2.0).events.t[0] == t1
    weak = solve_exact(WEAK, X0_WEAK, n_cycles=3)
    assert weak.status is Status.TURNED_BACK_IN_ZONE and weak.t_final == turn_back_time(X0_WEAK, WEAK)


# -- t_end -------------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("side, events", [(below, 0), (lambda t: t, 1), (above, 1)])
def test_an_event_exactly_at_the_end_time_belongs_to_the_run(side, events):
    t_end = side(first_impact_time(X0, FIG3A.a1))
    run = solve_exact(FIG3A, X0, t_end=t_end)
    impacts = f"{events} impact{'' if events == 1 else 's'} at a1"
    assert len(run.events) == events and run.status is Status.COMPLETED and run.t_final == t_end
    assert run.message.endswith(impacts) and run.trajectory.t_final == t_end
    x, _, _ = run.sample([t_end, above(t_end)])  # the run ends inside an arc, at the end time
    assert np.isfinite(x[0]) and np.isnan(x[1])
    if events:
        assert run.events.kind[0] == EventKind.IMPACT_A1 and run.events.t[0] <= t_end
    stream = iter_cycles(FIG3A, X0, t_end=t_end)
    assert list(stream) == [] and stream.summary.n_events == events and stream.summary.t_final == t_end


@pytest.mark.parametrize("side, status", [(below, Status.COMPLETED), (lambda t: t, Status.TURNED_BACK_IN_ZONE),
                                          (above, Status.TURNED_BACK_IN_ZONE)])
def test_a_turn_back_in_a_zone_exactly_at_the_end_time_is_that_exit(side, status):
    turn = turn_back_time(X0_WEAK, WEAK)
    t_end = side(turn)
    run = solve_exact(WEAK, X0_WEAK, t_end=t_end)
    assert run.status is status and len(run.events) == 1
    assert run.t_final == (t_end if status is Status.COMPLETED else turn)
    stream = iter_cycles(WEAK, X0_WEAK, t_end=t_end)
    list(stream)
    assert stream.summary.status is status and stream.summary.t_final == run.t_final


# -- n_cycles ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", [1, 2, 7])
def test_n_cycles_end_at_the_impact_at_a1_that_ends_the_last(n):
    run = solve_exact(FIG3A, X0, n_cycles=n)
    at_a1 = np.flatnonzero(run.events.kind == EventKind.IMPACT_A1)
    assert run.status is Status.COMPLETED and len(run.cycles) == n
    assert len(run.events) == events_of(n) and len(at_a1) == n + 1 and at_a1[-1] == len(run.events) - 1
    assert run.t_final == run.events.t[-1] == run.cycles.impact_time[-1] + run.cycles.period[-1]
    # released on the other side, the impact at a3 and the end of the zone at a4 come first: two events more
    assert len(solve_exact(FIG3A, -X0, n_cycles=n).events) == events_of(n) + 2


# -- max_events --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("spare, status, cycles", [(-1, Status.EVENT_LIMIT, 2), (0, Status.COMPLETED, 3),
                                                   (1, Status.COMPLETED, 3)])
def test_the_event_that_ends_the_last_cycle_completes_the_run_even_as_the_last_allowed(spare, status, cycles):
    max_events = events_of(3) + spare
    run = solve_exact(FIG3A, X0, n_cycles=3, max_events=max_events)
    assert run.status is status and len(run.cycles) == cycles
    assert len(run.events) == min(max_events, events_of(3)) and run.t_final == run.events.t[-1]
    if status is Status.EVENT_LIMIT:
        assert run.message.startswith(f"ended after max_events = {max_events} events at t = ")
    stream = iter_cycles(FIG3A, X0, n_cycles=3, max_events=max_events)
    assert sum(len(chunk) for chunk in stream) == cycles
    assert (stream.summary.status, stream.summary.n_events) == (status, len(run.events))
    ensemble = solve_ensemble(**FIG3A.as_dict(), x0=[X0, X0], n_cycles=3, max_events=max_events)
    assert [ensemble.outcome(i) for i in range(2)] == [status, status]
    assert np.isfinite(ensemble.cycles.period).sum(axis=1).tolist() == [cycles, cycles]


@pytest.mark.parametrize("max_events, status, events", [(1, Status.EVENT_LIMIT, 1), (2, Status.COMPLETED, 1)])
def test_the_last_allowed_event_ends_a_run_to_t_end_before_the_end_time_is_looked_for(max_events, status, events):
    """With t_end an ulp after the first impact, one event allowed ends there by the bound, two by the end time."""
    t_end = above(first_impact_time(X0, FIG3A.a1))
    run = solve_exact(FIG3A, X0, t_end=t_end, max_events=max_events)
    assert run.status is status and len(run.events) == events
    assert run.t_final == (run.events.t[0] if status is Status.EVENT_LIMIT else t_end)


@pytest.mark.parametrize("max_events", [BLOCK_EVENTS - 1, BLOCK_EVENTS, BLOCK_EVENTS + 1, 2 * BLOCK_EVENTS + 1])
def test_the_event_bound_across_the_stream_s_blocks(max_events):
    stream = iter_cycles(FIG3A, X0, n_cycles=10 * BLOCK_EVENTS, max_events=max_events)
    cycles = sum(len(chunk) for chunk in stream)
    assert stream.summary.status is Status.EVENT_LIMIT and stream.summary.n_events == max_events
    assert cycles == (max_events - 1) // 4  # the (k + 1)-th impact at a1, event 4 k + 1, ends cycle k
    run = solve_exact(FIG3A, X0, n_cycles=10 * BLOCK_EVENTS, max_events=max_events, record_trajectory=False)
    assert (run.status, len(run.events), len(run.cycles)) == (Status.EVENT_LIMIT, max_events, cycles)


# -- the largest counts ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name, largest, limits", [("n_cycles", MAX_CYCLES, {}),
                                                   ("max_events", MAX_EVENTS, dict(t_end=1.0))])
def test_the_largest_count_is_refused_by_the_memory_budget_alone_and_one_more_by_its_name(name, largest, limits):
    with pytest.raises(MemoryBudgetError):
        solve_exact(FIG3A, X0, **limits, **{name: largest})
    with pytest.raises(ParameterError) as refused:
        solve_exact(FIG3A, X0, **limits, **{name: largest + 1})
    assert not isinstance(refused.value, MemoryBudgetError)
    assert (refused.value.name, refused.value.value) == (name, largest + 1)
