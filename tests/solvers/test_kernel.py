"""The exact solver's event loop (escapement.solvers.kernel) against an independent path: the integrators' loop
(:func:`escapement.integrators.driver.drive`) with a stepper written here, in 40-digit mpmath, by the phase of the
harmonic motion (``acos`` of the target over the radius; the kernel uses an energy square root and ``atan2``), and
against properties written by hand: the order of the events, the energy balance of a half cycle. And the loop's own
contract: its rows, the kinds after the first event, a run in passes equal to a run in one, the block's cycles."""

from __future__ import annotations

import math
import re

import mpmath
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from releases import release_for_zone_turning_at
from strategies import initial_displacement, initial_velocity, parameters

from escapement.model import automaton
from escapement.model.automaton import RELEASE, Mode
from escapement.model.events import EventKind
from escapement.model.limits import RunLimits, RunSpec
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.integrators.driver import NO_EVENT, Step, drive
from escapement.solvers.exact import solve_exact
from escapement.model.kinematics import arc_maximum
from escapement.solvers.kernel import A1, PLAN, EventRun, event_block, kinds_from
from escapement.solvers.stream import iter_cycles

A2, A3, A4 = (int(k) for k in (EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4))
PAPER = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
ASYMMETRIC = Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04)
CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")


class PhaseStepper:
    """The next event by the phase of the motion, in 40 digits from the float state.
    
    About the centre ``c`` the state ``(x - c, v / omega)`` is ``R (cos phi, sin phi)``, ``phi`` decreasing at the rate
    ``omega``. The surface ``p`` is met moving in ``d`` at ``phi = d acos((p - c) / R)`` (``|p - c| < R``), after the
    clockwise sweep from the start in ``(0, 2 pi]``, at the velocity ``omega R sin(phi)``; the top ``c + R`` is passed
    where the sweep reaches ``phi = 0``. No surface reached: in free flight the escapement stopped (the swing's
    radius), in a zone the mass turns at the next rest, ``phi = 0`` moving right or ``-pi`` moving left."""

    name = "phase stepper"

    def __init__(self, params: Parameters) -> None:
        self.params = params

    def next_event(self, mode, centre, t, x, v, watched, t_stop):
        with mpmath.workdps(40):
            omega = mpmath.sqrt(mpmath.mpf(self.params.K) / mpmath.mpf(self.params.M))
            c = mpmath.mpf(centre)
            u0, w0 = mpmath.mpf(x) - c, mpmath.mpf(v) / omega
            radius = mpmath.hypot(u0, w0)
            phi0 = mpmath.atan2(w0, u0)
            two_pi = 2 * mpmath.pi
            best = None
            for kind in watched:
                surface = automaton.SURFACES[kind]
                q = mpmath.mpf(automaton.position(kind, self.params)) - c
                if abs(q) >= radius:
                    continue
                phi1 = surface.direction * mpmath.acos(q / radius)
                sweep = (phi0 - phi1) % two_pi
                sweep = two_pi if sweep == 0 else sweep
                if best is None or sweep < best[0]:
                    best = (sweep, kind, phi1, q)
            if best is None:
                if mode == Mode.FREE:
                    return Step(NO_EVENT, math.inf, 0.0, float(radius))
                if w0 == 0:
                    return Step(NO_EVENT, 0.0, 0.0, float(x))
                to_rest = phi0 if w0 > 0 else phi0 + mpmath.pi
                return Step(NO_EVENT, float(to_rest / omega), 0.0, float(c + radius if w0 > 0 else c - radius))
            sweep, kind, phi1, q = best
            to_top = phi0 % two_pi
            x_max = c + radius if sweep >= to_top else max(u0, q) + c
            return Step(kind, float(sweep / omega), float(omega * radius * mpmath.sin(phi1)), float(x_max))

    def trajectory(self, t_final):
        return None


def by_phase(params: Parameters, x0: float, v0: float = 0.0, **limits):
    """The run of the integrators' loop with the phase stepper."""
    return drive(RunSpec(params, x0, v0, RunLimits(**limits)), PhaseStepper(params))


def assert_agree(kernel, independent, rel: float = 1e-13) -> None:
    """The same outcome, the same events, and every number within ``rel`` of the scale of its column."""
    assert kernel.status == independent.status, (kernel.message, independent.message)
    assert np.array_equal(kernel.events.kind, independent.events.kind)
    assert len(kernel.cycles) == len(independent.cycles)
    for table, names in ((lambda r: r.events, ("t", "x", "v_before", "v_after")), (lambda r: r.cycles, CYCLE_COLUMNS)):
        for name in names:
            a, b = getattr(table(kernel), name), getattr(table(independent), name)
            assert np.max(np.abs(a - b), initial=0.0) <= rel * max(np.max(np.abs(b), initial=0.0), 1e-300), name
    assert kernel.t_final == pytest.approx(independent.t_final, rel=rel)  # inf equals inf
    for name in ("turning_point", "margin", "t_accumulation"):
        a, b = getattr(kernel.exit, name), getattr(independent.exit, name)
        assert (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b, rel=rel, abs=1e-15), name


@pytest.mark.parametrize("params, x0, v0", [
    (PAPER, 1.0, 0.0),
    (Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0, 0.0),
    (ASYMMETRIC, -0.8, 0.3),
    (Parameters(M=1.0, K=1.0, F=1.0, b=0.2, a1=-0.1, a2=0.3, a3=0.1, a4=-0.2), 1.0, 0.0),  # a2 > a3
    (Parameters(M=1.0, K=1.0, F=0.5, b=1.0, a1=-0.1, a2=0.05), 1.0, 0.0),  # at rest after each impact
])
def test_the_kernel_gives_the_events_and_cycles_of_the_phase_stepper(params, x0, v0):
    assert_agree(solve_exact(params, x0, v0, n_cycles=100, record_trajectory=False),
                 by_phase(params, x0, v0, n_cycles=100))


def _zeno(t_hit: float, speed: float, distance: float, ratio: float) -> float:
    """The rebounds' flights 2 atan(r**n speed / distance) (w = 1) summed in 30 digits after the impact at t_hit."""
    with mpmath.workdps(30):
        return t_hit + float(2 * mpmath.nsum(lambda n: mpmath.atan(speed / distance * mpmath.mpf(ratio) ** n),
                                             [0, mpmath.inf]))


# the exits' closed forms (w = 1 unless said): from rest at 0.05 m the swing turns at +-0.05 m, short of |a1| = a3;
# with w = 10, F/K = 1e-4, the impact at a3 = 0.02 m from rest at 0.021 m comes at acos(0.02/0.021)/w with
# v = -w sqrt(0.021**2 - 0.02**2), and the zone arc about c = -1e-4 turns at c - R after atan2(w0, u0) + pi; for
# b = 1.5 the impact at a3 at t = acos(0.1), |v| = sqrt(0.99), rebounds at half the speed and the spring drives it back
_W0, _U0 = 0.9 * -math.sqrt(0.021**2 - 0.02**2), 0.02 + 1e-4
_TURN = (math.acos(0.02 / 0.021) / 10 + (math.atan2(_W0, _U0) + math.pi) / 10, -1e-4 - math.hypot(_U0, _W0))
_ZENO = _zeno(math.acos(0.1), 0.5 * math.sqrt(0.99), 0.1, 0.5)
_STOPPED = ("the escapement stopped at t = {} s: the free swing turns at x = {} m and x = {} m and never passes the "
            "next impact position, {}; from then on the mass oscillates freely")
#: every way a run ends: the parameters, release and limits; the status, the message with {} for each number and
#: the numbers (12 significant digits in the message; None: not by hand), the exit's numbers and t_final
ENDINGS = [
    (PAPER, 0.05, dict(n_cycles=10), Status.STOPPED,
     _STOPPED.replace("{};", "a1 = -0.1 m (moving right) or a3 = 0.1 m (moving left);"), [0.0, -0.05, 0.05],
     (0.05, 0.05, math.nan), math.inf),
    # F = 0: only a3 = 0.3 m is awaited when the swing stops (its turning point: test_exact.py)
    (Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0), 1.0, dict(n_cycles=100), Status.STOPPED,
     _STOPPED.replace("{};", "a3 = 0.3 m (moving left);"), None, None, math.inf),
    (Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1), 0.021, dict(n_cycles=3), Status.TURNED_BACK_IN_ZONE,
     "the mass turned back inside the impulse zone (a4, a3) at t = {} s: about the zone's centre x = {} m (F/K) the "
     "motion turns at x = {} m, short of the zone's end at -0.1 m; the escapement model does not cover this",
     [_TURN[0], -1e-4, _TURN[1]], (_TURN[1], _TURN[1] + 0.1, math.nan), _TURN[0]),
    (Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, dict(n_cycles=5), Status.CHATTERING,
     "the impact at a3 at t = {} s reversed the velocity (b = 1.5 > 1, v+ = {} v-): the mass rebounds instead of "
     "entering the impulse zone; the spring drives it back to a3 and the impacts accumulate at t = {} s (a Zeno "
     "point), past which the impulsive model has no solution", [math.acos(0.1), -0.5, _ZENO],
     (math.nan, math.nan, _ZENO), math.acos(0.1)),
    (PAPER, 1.0, dict(t_end=20.0), Status.COMPLETED, "reached t_end = {} s after {} impacts at a1", [20, 3],
     (math.nan,) * 3, 20.0),
    (PAPER, 1.0, dict(n_cycles=100, max_events=1), Status.EVENT_LIMIT,
     "ended after max_events = {} event at t = {} s; raise max_events to go on", [1, math.acos(0.1)],
     (math.nan,) * 3, math.acos(0.1)),
    (PAPER, 1.0, dict(n_cycles=3), Status.COMPLETED, "completed {} cycles", [3], (math.nan,) * 3, None),
]


@pytest.mark.parametrize("params, x0, limits, status, message, numbers, exit_, t_final", ENDINGS,
                         ids=[f"{i}-{e[3].value}" for i, e in enumerate(ENDINGS)])
def test_every_way_a_run_ends_is_an_outcome_with_its_message_the_phase_steppers_numbers_and_the_streams(
        params, x0, limits, status, message, numbers, exit_, t_final):
    """The outcome, its message and numbers by hand; the events, cycles and exit of the phase stepper; and the
    stream of the same run in chunks of three cycles: the same cycles, bit for bit, and the same ending."""
    kernel = solve_exact(params, x0, **limits)
    assert kernel.status is status and kernel.success == (status is Status.COMPLETED)
    found = re.match("^" + r"(\S+?)".join(re.escape(part) for part in message.split("{}")) + "$", kernel.message)
    assert found, kernel.message
    if numbers is not None:
        assert [float(text) for text in found.groups()] == pytest.approx(numbers, rel=1e-11, abs=1e-300)
        got = (kernel.exit.turning_point, kernel.exit.margin, kernel.exit.t_accumulation)
        assert got == pytest.approx(exit_, rel=1e-12, nan_ok=True)
    if t_final is not None:
        assert kernel.t_final == pytest.approx(t_final, rel=1e-13)
    assert_agree(kernel, by_phase(params, x0, **limits))
    stream = iter_cycles(params, x0, chunk=3, **limits)
    chunks = list(stream)
    for name in CYCLE_COLUMNS:
        joined = np.concatenate([np.zeros(0)] + [getattr(c, name) for c in chunks])
        assert joined.tobytes() == getattr(kernel.cycles, name).tobytes(), name
    s = stream.summary
    assert (s.status, s.message, s.t_final, s.n_cycles, s.n_events) == (
        kernel.status, kernel.message, kernel.t_final, len(kernel.cycles), len(kernel.events))
    assert np.array_equal([s.exit.turning_point, s.exit.margin, s.exit.t_accumulation],
                          [kernel.exit.turning_point, kernel.exit.margin, kernel.exit.t_accumulation], equal_nan=True)


@settings(max_examples=60, deadline=None)
@given(p=parameters(), x0=initial_displacement, v0=initial_velocity, b=st.one_of(st.none(), st.floats(0.02, 1.98)),
       limit=st.sampled_from(["cycles", "time", "events"]))
def test_random_runs_follow_the_phase_stepper_the_order_of_the_cycle_and_its_energy(p, x0, v0, b, limit):
    """The kinds go round the cycle from an impact (a1, a2, a3, a4); from an impact to the next, E = M v**2 / 2 +
    K x**2 / 2 loses the impact's loss and gains the zone's work, F (a2 - a1) after a1 and F (a3 - a4) after a3."""
    if b is not None:
        p = Parameters(**{**p.as_dict(), "b": b})
    limits = {"cycles": dict(n_cycles=20), "time": dict(t_end=30.0), "events": dict(n_cycles=20, max_events=37)}[limit]
    kernel = solve_exact(p, x0, v0, record_trajectory=False, **limits)
    ev, cycle = kernel.events, [int(k) for k in (EventKind.IMPACT_A1, A2, A3, A4)]
    if len(ev):
        assert ev.kind[0] in (cycle[0], cycle[2])
        assert ev.kind.tolist() == [cycle[(cycle.index(ev.kind[0]) + i) % 4] for i in range(len(ev))]
    impacts = np.flatnonzero((ev.kind == 1) | (ev.kind == 3))
    energy = 0.5 * p.M * ev.v_before**2 + 0.5 * p.K * ev.x**2
    for i, j in zip(impacts[:-1], impacts[1:]):
        loss = 0.5 * p.M * (ev.v_before[i] ** 2 - ev.v_after[i] ** 2)
        work = p.F * ((p.a2 - p.a1) if ev.kind[i] == 1 else (p.a3 - p.a4))
        assert abs(energy[j] - (energy[i] - loss + work)) <= 1e-12 * max(np.max(np.abs(energy[impacts])), abs(work))
    # away from grazing: an arc that arrives near its turning point amplifies the rounding of the velocity
    v_scale = math.hypot(p.omega * max(abs(x0), abs(p.a1), abs(p.a3)), v0, p.omega * p.zone_offset)
    assume(len(kernel.events) == 0 or np.min(np.abs(kernel.events.v_before)) > 1e-3 * v_scale)
    assume(not (kernel.status in (Status.STOPPED, Status.TURNED_BACK_IN_ZONE)
                and abs(kernel.exit.margin) < 1e-9 * v_scale / p.omega))
    assert_agree(kernel, by_phase(p, x0, v0, **limits), rel=1e-11)


@pytest.mark.parametrize("params, impact, end", [
    # the zone (a1, a2) about F/K = 0.02 m, narrower than a2's distance from its centre: it turns near a2
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.05, a2=0.1), "a1", "a2"),
    # the zone (a4, a3) about -F/K, turning near a4
    (Parameters(M=1.0, K=1.0, F=0.02, b=0.1, a1=-0.1, a2=0.05, a3=0.05, a4=-0.1), "a3", "a4"),
])
def test_arcs_that_reach_their_end_at_a_turning_point_decide_as_the_phase_stepper(params, impact, end):
    """Releases ulp by ulp around the one whose first zone arc turns exactly at the zone's end: some turn
    back, some pass. Where the 40-digit stepper's margin (the arrival's v**2, or how far short the turning
    point lies) is above the rounding of the kernel's v**2 = v0**2 + k, both decide alike and agree on
    every number after; within it either outcome is right."""
    x0 = release_for_zone_turning_at(params, impact, mpmath.mpf(getattr(params, end)))
    outcomes, compared = set(), 0
    for k in range(-60, 61):
        release = x0 + k * math.ulp(x0)
        kernel = solve_exact(params, release, n_cycles=3, record_trajectory=False)
        independent = by_phase(params, release, n_cycles=3)
        outcomes.add(kernel.status)
        # the zone arc from the impact: v**2 at its end = v+**2 + w**2 ((a - c)**2 - (p - c)**2), in 40 digits
        with mpmath.workdps(40):
            v_plus = mpmath.mpf(float(independent.events.v_after[0]))
            a, p = mpmath.mpf(getattr(params, impact)), mpmath.mpf(getattr(params, end))
            c = mpmath.mpf(params.zone_offset) * (1 if impact == "a1" else -1)
            energy = mpmath.mpf(params.omega2) * ((a - c) ** 2 - (p - c) ** 2)
            v_sq, scale = v_plus**2 + energy, v_plus**2 + abs(energy)
        if abs(v_sq) > 16 * np.finfo(float).eps * scale:
            compared += 1
            assert kernel.status == independent.status, (k, kernel.message, independent.message)
            if kernel.status is Status.COMPLETED:
                assert_agree(kernel, independent, rel=1e-9)  # a slow arrival: its time amplifies the rounding
        else:
            assert kernel.status in (Status.COMPLETED, Status.TURNED_BACK_IN_ZONE)
    assert {Status.TURNED_BACK_IN_ZONE, Status.COMPLETED} <= outcomes
    assert compared >= 100, compared


def test_the_plan_of_a_cycle_the_kinds_after_the_first_event_and_the_first_one():
    """From rest at x0 = 1 the swing goes left: a3 = 0.1 first; from x0 = -1 right: a1 = -0.1 first; moving right
    fast from x0 = 0.5, past the top and back: a3 again, after the top; from 0.05 neither is reached."""
    assert EventRun(RunSpec(PAPER, 1.0, 0.0, RunLimits(n_cycles=1))).first == A3
    assert EventRun(RunSpec(PAPER, -1.0, 0.0, RunLimits(n_cycles=1))).first == A1
    assert EventRun(RunSpec(PAPER, 0.5, 3.0, RunLimits(n_cycles=1))).first == A3
    assert EventRun(RunSpec(PAPER, 0.05, 0.0, RunLimits(n_cycles=1))).rows[RELEASE] is None
    assert PLAN == (A2, A3, A4, A1)
    assert kinds_from(A3, 0, 9).tolist() == [A3, A4, A1, A2, A3, A4, A1, A2, A3]
    assert kinds_from(A1, 0, 5).tolist() == [A1, A2, A3, A4, A1]
    assert kinds_from(A3, 6, 3).tolist() == [A1, A2, A3]  # events 6, 7, 8 of a run that began at a3
    assert kinds_from(A1, 10**9 + 2, 2).tolist() == [A3, A4]
    assert len(kinds_from(A1, 0, 0)) == 0


@pytest.mark.parametrize("limits", [dict(n_cycles=100), dict(t_end=160.0), dict(n_cycles=100, max_events=341)])
@pytest.mark.parametrize("size", [1, 3, 4, 997])
def test_a_run_in_passes_is_the_run_in_one(limits, size):
    """The columns taken after each pass put together are those of one pass, bit for bit, and the run ends alike."""
    one = EventRun(RunSpec(ASYMMETRIC, -0.8, 0.3, RunLimits(**limits)))
    one.advance(10**9)
    whole = one.take()
    run = EventRun(RunSpec(ASYMMETRIC, -0.8, 0.3, RunLimits(**limits)))
    parts, passes = [], 0
    while run.outcome is None:
        run.advance(size)
        parts.append(run.take())
        passes += 1
        assert sum(len(part[0]) for part in parts) == run.events <= passes * size
    for a, b in zip(whole, (np.concatenate(c) for c in zip(*parts))):
        assert np.array_equal(a, b)
    assert (run.outcome.status, run.outcome.message, run.outcome.t_final) == (
        one.outcome.status, one.outcome.message, one.outcome.t_final)
    assert run.events == one.events == len(whole[0]) and run.advance(5) is None and run.events == one.events


def test_the_times_are_the_compensated_sums_of_the_arcs():
    """Each time is the exactly rounded sum of the durations before it, to an ulp, over 40_000 events."""
    run = EventRun(RunSpec(PAPER, 1.0, 0.0, RunLimits(n_cycles=10_000)))
    run.advance(10**9)
    t, _, angle = run.take()
    dt = angle / PAPER.omega
    for i in (0, 1, 999, 20_000, len(t) - 1):
        assert abs(t[i] - math.fsum(dt[: i + 1])) <= math.ulp(t[i])


def test_the_block_derives_the_events_and_the_cycles_after_the_loop():
    """Positions, jumps, arcs from the automaton; periods the durations summed in order, amplitudes the largest x."""
    run = EventRun(RunSpec(ASYMMETRIC, -0.8, 0.3, RunLimits(n_cycles=50)))
    run.advance(10**9)
    t, v_before, angle = run.take()
    block = event_block(run, 0, t, v_before, angle, before=run.release)
    positions = np.array([math.nan, ASYMMETRIC.a1, ASYMMETRIC.a2, ASYMMETRIC.a3, ASYMMETRIC.a4])
    assert np.array_equal(block.x, positions[block.kind])
    impact = np.isin(block.kind, [A1, A3])
    assert np.array_equal(block.v_after, np.where(impact, (1 - ASYMMETRIC.b) * block.v_before, block.v_before))
    assert np.array_equal(block.arc_x, np.concatenate(([-0.8], block.x)))
    assert np.array_equal(block.arc_v, np.concatenate(([0.3], block.v_after)))
    (impact_time, velocity, period, amplitude), begins = block.cycles, block.begins
    dt = angle / ASYMMETRIC.omega
    arc_max = arc_maximum(block.arc_centre[:-1], block.arc_x[:-1], block.arc_v[:-1], ASYMMETRIC.omega, angle, block.x,
                          block.v_before)
    at_a1 = np.flatnonzero(block.kind == A1)
    assert len(period) == 50 and begins == at_a1[-1] == len(block.t) - 1
    assert np.array_equal(impact_time, block.t[at_a1[:-1]])
    assert np.array_equal(velocity, block.v_before[at_a1[:-1]])
    for j, i in enumerate(at_a1[:-1]):
        d = dt[i + 1:i + 5]
        assert period[j] == ((d[0] + d[1]) + d[2]) + d[3]
        assert period[j] == pytest.approx(block.t[i + 4] - block.t[i], rel=1e-14)
        assert amplitude[j] == max(ASYMMETRIC.a1, *arc_max[i + 1:i + 5])
