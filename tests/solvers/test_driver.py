"""The one solver loop: its bookkeeping with a scripted integrator, and that every solver obeys the
automaton, so that a change of the impact law is one edit in :mod:`escapement.model.automaton`."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from escapement.model import automaton
from escapement.model.automaton import Mode
from escapement.model.events import EventKind
from escapement.model.limits import RunLimits
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.driver import HORIZON, NO_EVENT, Step, drive
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.solvers.high_precision import solve_high_precision
from escapement.solvers.naive import solve_naive
from escapement.solvers.reference import solve_reference

A1, A2, A3, A4 = EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4

# w = 2 rad/s, F/K = 0.5 m, b = 0.25
P = Parameters(M=1.0, K=4.0, F=2.0, b=0.25, a1=-0.1, a2=0.05)


class Scripted:
    """A stepper that answers from a script and records what the loop asked."""

    name = "scripted"

    def __init__(self, script):
        self.script = list(script)
        self.asked = []
        self.trajectory_asked = None

    def next_event(self, mode, centre, t, x, v, watched, t_stop):
        self.asked.append((mode, centre, t, x, v, tuple(watched)))
        return self.script.pop(0)

    def trajectory(self, t_final):
        self.trajectory_asked = t_final
        return None


def _drive(script, params=P, **limits):
    stepper = Scripted(script)
    sol = drive(params, 1.0, 0.0, RunLimits(**limits), stepper, x0=1.0, v0=0.0)
    return sol, stepper


def test_the_loop_follows_the_automaton_and_keeps_the_books():
    script = [
        Step(A3, 1.0, -2.0, 1.0),
        Step(A4, 0.5, -1.0, 0.1),
        Step(A1, 2.0, 3.0, -0.05),
        Step(A2, 0.25, 2.5, 0.05),
        Step(A3, 1.5, -2.0, 0.7),
        Step(A4, 0.5, -1.0, 0.1),
        Step(A1, 2.0, 4.0, -0.05),
    ]
    sol, stepper = _drive(script, n_cycles=1)
    assert sol.status == Status.COMPLETED and sol.message == "completed 1 cycles"
    assert sol.events.kind.tolist() == [3, 4, 1, 2, 3, 4, 1]
    assert sol.events.t.tolist() == [1.0, 1.5, 3.5, 3.75, 5.25, 5.75, 7.75]
    assert sol.events.x.tolist() == [0.1, -0.05, -0.1, 0.05, 0.1, -0.05, -0.1]
    assert sol.events.v_before.tolist() == [-2.0, -1.0, 3.0, 2.5, -2.0, -1.0, 4.0]
    assert sol.events.v_after.tolist() == [-1.5, -1.0, 2.25, 2.5, -1.5, -1.0, 3.0]  # (1 - b) v at impacts only
    # one complete cycle, from the impact at a1 at 3.5 s to the next at 7.75 s
    assert sol.cycles.impact_time.tolist() == [3.5]
    assert sol.cycles.velocity_before_impact.tolist() == [3.0]
    assert sol.cycles.period.tolist() == [4.25]
    assert sol.cycles.amplitude.tolist() == [0.7]
    assert sol.t_final == 7.75 and stepper.trajectory_asked == 7.75
    # what the loop asked: mode, centre (0, +F/K, -F/K), state after the jump, watched surfaces
    modes = [(a[0], a[1], a[3], a[4], a[5]) for a in stepper.asked]
    assert modes == [
        (Mode.FREE, 0.0, 1.0, 0.0, (A1, A3)),
        (Mode.ZONE_LEFT, -0.5, 0.1, -1.5, (A4,)),
        (Mode.FREE, 0.0, -0.05, -1.0, (A1,)),
        (Mode.ZONE_RIGHT, 0.5, -0.1, 2.25, (A2,)),
        (Mode.FREE, 0.0, 0.05, 2.5, (A3,)),
        (Mode.ZONE_LEFT, -0.5, 0.1, -1.5, (A4,)),
        (Mode.FREE, 0.0, -0.05, -1.0, (A1,)),
    ]
    assert [a[2] for a in stepper.asked] == [0.0, 1.0, 1.5, 3.5, 3.75, 5.25, 5.75]


def test_an_integrator_time_and_position_are_used_when_given():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0, t_abs=0.9, x_at=0.09), Step(A4, 0.5, -1.0, 0.1)], max_events=2,
                    n_cycles=3)
    assert sol.events.t.tolist() == [0.9, 1.4]
    assert sol.events.x.tolist() == [0.09, -0.05]
    assert sol.status == Status.EVENT_LIMIT and "max_events = 2" in sol.message


def test_no_event_in_free_flight_is_stopped():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), Step(A4, 0.5, -1.0, 0.1), Step(NO_EVENT, math.inf, 0.0, 0.08)],
                    n_cycles=3)
    assert sol.status == Status.STOPPED and sol.t_final == math.inf
    # after the impulse (a4, a3) only a1 is awaited
    assert "a1 = -0.1 m (moving right)" in sol.message and "a3 =" not in sol.message
    assert sol.exit.turning_point == 0.08
    assert sol.exit.margin == pytest.approx(0.02, rel=1e-14)


def test_no_event_in_a_zone_is_turned_back():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), Step(NO_EVENT, 0.25, 0.0, -0.04)], n_cycles=3)
    assert sol.status == Status.TURNED_BACK_IN_ZONE and "(a4, a3)" in sol.message
    assert sol.t_final == 1.25
    assert sol.exit.turning_point == -0.04 and sol.exit.margin == pytest.approx(0.01, rel=1e-14)


def test_the_end_time_ends_the_run_inside_an_arc():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), Step(A4, 5.0, -1.0, 0.1)], t_end=2.0)
    assert sol.status == Status.COMPLETED and sol.t_final == 2.0 and len(sol.events) == 1
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), Step(HORIZON, math.inf, 0.0, 0.1)], t_end=2.0)
    assert sol.status == Status.COMPLETED and sol.t_final == 2.0


def test_a_reversing_impact_is_chattering_with_the_zeno_time():
    p = Parameters(M=1.0, K=4.0, F=2.0, b=1.5, a1=-0.1, a2=0.05)
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0)], params=p, n_cycles=3)
    assert sol.status == Status.CHATTERING and sol.events.v_after.tolist() == [1.0]
    # flights of (2/w) atan(r^n v / (w d)) with v = 1, d = a3 = 0.1, w = 2, r = |1 - b| = 0.5
    with mpmath.workdps(30):
        total = mpmath.nsum(lambda n: mpmath.atan(5 * mpmath.mpf(0.5) ** n), [0, mpmath.inf])
    assert sol.exit.t_accumulation == pytest.approx(1.0 + float(total), rel=1e-14)


# --- every solver drives the automaton: patch the impact law and all of them follow ------------------

#: the paper's case (a), symmetric, released at rest at x0 = 1 m (w = 1)
PAPER = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
N = 6


def patched_law(v_before, b, impact):
    """A different restitution, v+ = (1 - 2b) v- at an impact (0.8 for b = 0.1 instead of 0.9)."""
    return (1.0 - 2.0 * b * impact) * v_before


def closed_form_velocities(p: Parameters, r: float, x0: float, n: int) -> np.ndarray:
    """Velocity before each impact at a1, derived on paper from energy for v+ = r v- (symmetric case).

    Per half cycle the impact multiplies v^2 by r^2, the zone adds 2 f (a2 - a1), and the spring's
    terms cancel because a3 = -a1, a4 = -a2: v4^2 = r^2 v1^2 + 2 f (a2 - a1), and so
    v1(k+1)^2 = r^4 v1(k)^2 + 2 f (a2 - a1)(r^2 + 1). From rest at x0 > a3 the first impact is at a3 with
    v^2 = w^2 (x0^2 - a3^2), so v1(1)^2 = r^2 w^2 (x0^2 - a1^2) + 2 f (a2 - a1).
    """
    c = 2 * p.f * (p.a2 - p.a1) * (r * r + 1)
    v2 = [r * r * p.omega2 * (x0 * x0 - p.a1 * p.a1) + 2 * p.f * (p.a2 - p.a1)]
    for _ in range(n - 1):
        v2.append(r**4 * v2[-1] + c)
    return np.sqrt(v2)


def test_the_closed_form_is_eq17_for_the_paper_law():
    """The derivation checked against the unpatched solver: for r = 1 - b its constant is Eq. (17)'s."""
    b = PAPER.b
    assert 2 * PAPER.f * (PAPER.a2 - PAPER.a1) * ((1 - b) ** 2 + 1) == pytest.approx(
        2 * (b * b - 2 * b + 2) * (PAPER.a2 - PAPER.a1) * PAPER.f, rel=1e-15)
    v = solve_exact(PAPER, 1.0, n_cycles=N).cycles.velocity_before_impact
    assert v == pytest.approx(closed_form_velocities(PAPER, 1 - b, 1.0, N), rel=1e-14)


def _all_solvers(p, x0):
    hp = solve_high_precision(p, x0, n_cycles=N, dps=30)
    ens = solve_ensemble(p.M, p.K, p.F, p.b, p.a1, p.a2, x0=x0, n_cycles=N)
    return {
        "exact": (solve_exact(p, x0, n_cycles=N).cycles.velocity_before_impact, 1e-14),
        "reference": (solve_reference(p, x0, n_cycles=N, rtol=1e-12).cycles.velocity_before_impact, 1e-9),
        "high precision": (np.array([float(v) for v in hp.cycles.velocity_before_impact]), 1e-15),
        # RK4 with events applied up to a step late, at a state up to |v| h past the surface: each event
        # moves v by up to w^2 |x| h <= 1e-3 (|x| <= 1 m, w = 1, h = 1e-3); a few events' worth at most
        "naive": (solve_naive(p, x0, n_cycles=N, step=1e-3).cycles.velocity_before_impact, 5e-3),
        "ensemble": (ens.cycles.velocity_before_impact[0], 1e-14),
    }


def test_every_solver_follows_a_patched_impact_law(monkeypatch):
    paper = _all_solvers(PAPER, 1.0)
    monkeypatch.setattr(automaton, "velocity_after", patched_law)
    patched = _all_solvers(PAPER, 1.0)
    expected = closed_form_velocities(PAPER, 1 - 2 * PAPER.b, 1.0, N)
    unpatched = closed_form_velocities(PAPER, 1 - PAPER.b, 1.0, N)
    assert np.min(np.abs(expected - unpatched) / unpatched) > 0.05  # the two laws are far apart
    for name, (v, rel) in patched.items():
        assert len(v) == N, name
        assert v == pytest.approx(expected, rel=rel), name
        assert v == pytest.approx(patched["exact"][0], rel=rel), name
        assert np.all(np.abs(v - paper[name][0]) > 0.05 * np.abs(paper[name][0])), name
        assert paper[name][0] == pytest.approx(unpatched, rel=rel), name


def test_every_solver_applies_the_patched_law_at_each_impact(monkeypatch):
    monkeypatch.setattr(automaton, "velocity_after", patched_law)
    def naive(p, x0, n_cycles):
        return solve_naive(p, x0, n_cycles=n_cycles, step=1e-3)

    for solve in (solve_exact, solve_reference, solve_high_precision, naive):
        ev = solve(PAPER, 1.0, n_cycles=2).events
        impacts = np.isin(ev.kind, [1, 3])
        ratio = np.array([float(a / b) for a, b in zip(ev.v_after, ev.v_before)])
        assert ratio[impacts] == pytest.approx(0.8, rel=1e-14), solve.__name__
        assert ratio[~impacts] == pytest.approx(1.0, rel=1e-15), solve.__name__


def test_the_zeno_time_follows_a_patched_reversing_law(monkeypatch):
    # v+ = (1 - 1.2 b) v-: for b = 1.5 the rebound keeps 0.8 of the speed (the paper's law keeps 0.5)
    monkeypatch.setattr(automaton, "velocity_after", lambda v, b, impact: (1.0 - 1.2 * b * impact) * v)
    p = Parameters(M=1.0, K=1.0, F=1.0, b=1.5, a1=-0.1, a2=0.05)
    s = solve_exact(p, 1.0, n_cycles=3)
    assert s.status == Status.CHATTERING
    speed, distance = abs(s.events.v_after[-1]), 0.1  # the first impact is at a3 = 0.1 m, w = 1
    with mpmath.workdps(30):
        rest = 2 * mpmath.nsum(lambda n: mpmath.atan(speed / distance * mpmath.mpf(0.8) ** n), [0, mpmath.inf])
    assert s.exit.t_accumulation == pytest.approx(s.events.t[-1] + float(rest), rel=1e-12)
