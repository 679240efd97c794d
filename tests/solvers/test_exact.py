"""The exact solver against closed forms derived by hand: the first impact, the energy balance of the impacts and
the zones, the arcs between them, the amplitude, and every way a run ends, with its message."""

import math
import re

import mpmath
import numpy as np
import pytest

from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper.printed import poincare_map_16
from escapement.solvers.describe import ArcTable
from escapement.solvers.exact import solve_exact

PAPER = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)


def relative(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))


def test_the_first_impact_from_rest_is_the_closed_form():
    # From x0 = 1 at rest, x = cos t reaches a3 = 0.1 moving left at t = acos(0.1).
    s = solve_exact(PAPER, 1.0, n_cycles=1)
    assert s.events.kind[0] == EventKind.IMPACT_A3
    assert s.events.t[0] == pytest.approx(math.acos(0.1), rel=1e-15)
    assert s.events.v_before[0] == pytest.approx(-math.sqrt(1 - 0.01), rel=1e-15)


@pytest.mark.parametrize("params, x0", [(PAPER, 1.0), (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
                                        (ASYMMETRIC, 0.8)])
def test_cycles_follow_the_map_of_eq16_to_1e13_over_10_000_cycles(params, x0):
    s = solve_exact(params, x0, n_cycles=10_000, record_trajectory=False)
    v = s.cycles.velocity_before_impact
    assert s.status == Status.COMPLETED and len(v) == 10_000
    predicted = np.array([poincare_map_16(vk, params) for vk in v[:-1]])
    assert np.max(relative(v[1:], predicted)) < 1e-13


def _speeds_before_impacts_by_energy(p, x0, n):
    """|v-| at the first ``n`` impacts from rest at x0 > a3, by energy alone, written out here.

    Released at rest at x0, the mass swings left freely to a3: (1/2) M v^2 + (1/2) K a3^2 = (1/2) K x0^2, so
    v-(1)^2 = (K/M)(x0^2 - a3^2). An impact v+ = (1 - b) v- takes (1 - (1-b)^2) M v-^2 / 2 of the energy. On the
    way from a3 to a1 the force F pushes the mass through the zone [a4, a3] (it gives F (a3 - a4)), and from
    a1 back to a3 through [a1, a2] (F (a2 - a1)); the spring's energy is (1/2) K x^2 at the impact position.
    So E-(k+1) = E-(k) - (1 - (1-b)^2) M v-(k)^2 / 2 + F zone(k), and v-(k+1)^2 = 2 (E-(k+1) - K x(k+1)^2 / 2) / M.
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
    """Sampled inside each arc: free flight keeps E, the zones keep E -/+ F x; across an event x is continuous
    and v jumps from v- to v+."""
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
    """In a regular cycle only the free arc from a2 to a3 passes the top of its circle, so the amplitude is its
    radius sqrt(a2**2 + (v2 / w)**2), with v2 at a2 from energy through the zone (a1, a2) about c = F/K:
    v2**2 = ((1 - b) v1)**2 + w**2 ((a1 - c)**2 - (a2 - c)**2), v1 the velocity before the impact at a1."""
    s = solve_exact(params, x0, n_cycles=200, record_trajectory=False)
    with mpmath.workdps(40):
        w2 = mpmath.mpf(params.K) / mpmath.mpf(params.M)
        c, a1, a2 = mpmath.mpf(params.F) / mpmath.mpf(params.K), mpmath.mpf(params.a1), mpmath.mpf(params.a2)
        for v1, amplitude in zip(s.cycles.velocity_before_impact, s.cycles.largest_displacement):
            v2_sq = ((1 - mpmath.mpf(params.b)) * mpmath.mpf(v1)) ** 2 + w2 * ((a1 - c) ** 2 - (a2 - c) ** 2)
            assert amplitude == pytest.approx(float(mpmath.sqrt(a2**2 + v2_sq / w2)), rel=2e-15)


def _zeno(t_hit: float, speed: float, distance: float, ratio: float) -> float:
    """The rebounds' flights 2 atan(r**n speed / distance) (w = 1) summed in 30 digits after the impact at t_hit."""
    with mpmath.workdps(30):
        return t_hit + float(2 * mpmath.nsum(lambda n: mpmath.atan(speed / distance * mpmath.mpf(ratio) ** n),
                                             [0, mpmath.inf]))


# closed forms of the exits below (w = 1 unless said): from rest at 0.05 m the swing turns at +-0.05 m, short of
# |a1| = a3 = 0.1 m; with w = 10, F/K = 1e-4, the impact at a3 = 0.02 m from rest at 0.021 m comes at
# acos(0.02/0.021)/w with v = -w sqrt(0.021**2 - 0.02**2), and the zone arc about c = -1e-4 turns at c - R after
# the phase from its start to the bottom of the circle, atan2(w0, u0) + pi; for b = 1.5 the first impact, at a3
# at t = acos(0.1) with |v| = sqrt(0.99), rebounds with half the speed and the spring drives the mass back to a3
_W0, _U0 = 0.9 * -math.sqrt(0.021**2 - 0.02**2), 0.02 + 1e-4
_TURN = (math.acos(0.02 / 0.021) / 10 + (math.atan2(_W0, _U0) + math.pi) / 10, -1e-4 - math.hypot(_U0, _W0))
#: every way a run ends: the parameters, release and limits; the status, the message with {} for each number and
#: the numbers (12 significant digits in the message), the exit's numbers and t_final
ENDINGS = [
    (PAPER, 0.05, dict(n_cycles=10), Status.STOPPED,
     "the escapement stopped at t = {} s: the free swing turns at x = {} m and x = {} m and never passes the next "
     "impact position, a1 = -0.1 m (moving right) or a3 = 0.1 m (moving left); from then on the mass oscillates "
     "freely", [0.0, -0.05, 0.05], (0.05, 0.05, math.nan), math.inf),
    (Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1), 0.021, dict(n_cycles=3), Status.TURNED_BACK_IN_ZONE,
     "the mass turned back inside the impulse zone (a4, a3) at t = {} s: about the zone's centre x = {} m (F/K) the "
     "motion turns at x = {} m, short of the zone's end at -0.1 m; the escapement model does not cover this",
     [_TURN[0], -1e-4, _TURN[1]], (_TURN[1], _TURN[1] + 0.1, math.nan), _TURN[0]),
    (Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, dict(n_cycles=5), Status.CHATTERING,
     "the impact at a3 at t = {} s reversed the velocity (b = 1.5 > 1, v+ = {} v-): the mass rebounds instead of "
     "entering the impulse zone; the spring drives it back to a3 and the impacts accumulate at t = {} s (a Zeno "
     "point), past which the impulsive model has no solution",
     [math.acos(0.1), -0.5, _zeno(math.acos(0.1), 0.5 * math.sqrt(0.99), 0.1, 0.5)],
     (math.nan, math.nan, _zeno(math.acos(0.1), 0.5 * math.sqrt(0.99), 0.1, 0.5)), math.acos(0.1)),
    (PAPER, 1.0, dict(t_end=20.0), Status.COMPLETED, "reached t_end = {} s after {} impacts at a1", [20, 3],
     (math.nan,) * 3, 20.0),
    (PAPER, 1.0, dict(n_cycles=100, max_events=1), Status.EVENT_LIMIT,
     "ended after max_events = {} event at t = {} s; raise max_events to go on", [1, math.acos(0.1)],
     (math.nan,) * 3, math.acos(0.1)),
    (PAPER, 1.0, dict(n_cycles=3), Status.COMPLETED, "completed {} cycles", [3], (math.nan,) * 3, None),
]


@pytest.mark.parametrize("params, x0, limits, status, message, numbers, exit_, t_final", ENDINGS,
                         ids=[e[3].value for e in ENDINGS])
def test_every_way_a_run_ends_is_an_outcome_with_its_message_and_numbers(params, x0, limits, status, message,
                                                                         numbers, exit_, t_final):
    s = solve_exact(params, x0, **limits)
    assert s.status is status and s.success == (status is Status.COMPLETED)
    pattern = "^" + r"(\S+?)".join(re.escape(part) for part in message.split("{}")) + "$"
    found = re.match(pattern, s.message)
    assert found, s.message
    assert [float(text) for text in found.groups()] == pytest.approx(numbers, rel=1e-11, abs=1e-300)
    got = (s.exit.turning_point, s.exit.margin, s.exit.t_accumulation)
    assert got == pytest.approx(exit_, rel=1e-12, nan_ok=True)
    if t_final is not None:
        assert s.t_final == pytest.approx(t_final, rel=1e-13)


def test_a_run_stops_later_when_no_force_keeps_up_an_asymmetric_swing():
    # F = 0: the radius R of the free swing only shrinks, R^2 -> a^2 + r^2 (R^2 - a^2) at an impact at a;
    # impacts alternate a3 = 0.3 m and a1 = -0.1 m, each followed by its zone end, until R <= a3 when a3 is awaited
    s = solve_exact(Parameters(M=1, K=1, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0), 1.0, n_cycles=100)
    radius_sq, events, awaited = 1.0, 0, 0.3
    while radius_sq > awaited**2:
        radius_sq = awaited**2 + 0.81 * (radius_sq - awaited**2)
        events, awaited = events + 2, 0.1 if awaited == 0.3 else 0.3
    assert s.status == Status.STOPPED and len(s.events) == events and s.events.kind[-1] == EventKind.ZONE_END_A2
    assert "a3 = 0.3 m (moving left)" in s.message and "a1 =" not in s.message  # only a3 is awaited
    assert s.exit.turning_point == pytest.approx(math.sqrt(radius_sq), rel=1e-13)


def test_b_equal_one_brings_the_mass_to_rest_at_the_impact_and_the_map_converges_in_one_cycle():
    s = solve_exact(Parameters(M=1, K=1, F=1, b=1.0, a1=-0.1, a2=0.05), 1.0, n_cycles=5)
    assert s.status == Status.COMPLETED
    assert np.all(s.events.v_after[(s.events.kind == 1) | (s.events.kind == 3)] == 0.0)
    # From rest at a1 the zone and the spring give v^2 = 2 f (a2 - a1) at the next impact (symmetric case).
    assert s.cycles.velocity_before_impact[1:] == pytest.approx(math.sqrt(2 * 1.0 * 0.15), rel=1e-14)


def test_chattering_accumulates_in_finite_time_for_b_close_to_two():
    s = solve_exact(Parameters(M=1, K=1, F=0.1, b=1.999999, a1=-0.1, a2=-0.05), 1.0, n_cycles=5)
    assert s.status == Status.CHATTERING and math.isfinite(s.exit.t_accumulation)
    assert s.exit.t_accumulation > s.events.t[-1]


def test_a_run_to_an_end_time_ends_inside_an_arc():
    s = solve_exact(PAPER, 1.0, t_end=20.0)
    x, _, _ = s.sample(np.array([20.0, 20.0 + 1e-9]))
    assert s.events.t[-1] <= 20.0 and np.isfinite(x[0]) and np.isnan(x[1])


def test_a_release_on_an_impact_surface_is_the_state_after_any_jump():
    """Eq. (2) gives the initial state at t0+: a release at a3 moving left is not an impact at t = 0."""
    s = solve_exact(PAPER, 0.1, -1.0, n_cycles=2)
    assert s.events.t[0] > 0 and s.events.kind[0] == EventKind.IMPACT_A1


def test_a_completed_run_holds_its_events_cycles_and_arcs():
    s = solve_exact(PAPER, 1.0, n_cycles=100)
    assert isinstance(s.trajectory, ArcTable) and s.method == "exact" and (s.x0, s.v0) == (1.0, 0.0)
    # n_cycles complete cycles: n_cycles + 1 impacts at a1; the kinds go round a3, a4, a1, a2 from the release
    assert len(s.cycles) == 100 and len(s.events.of_kind(EventKind.IMPACT_A1)) == 101
    assert s.cycles.cycle.tolist() == list(range(1, 101))
    assert s.events.kind.tolist() == [[3, 4, 1, 2][i % 4] for i in range(len(s.events))]
    # the arcs start at the release and at each event, over the loop's own buffers (no copy)
    assert s.trajectory.t_start[0] == 0.0 and s.trajectory.t_start[1:].tolist() == s.events.t[:-1].tolist()
    for column in (s.events.t, s.events.v_before):
        assert not column.flags.owndata and column.base is not None
    assert solve_exact(PAPER, 1.0, n_cycles=2, record_trajectory=np.bool_(False)).trajectory is None
