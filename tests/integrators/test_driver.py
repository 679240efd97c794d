"""The integrators' loop (escapement.integrators.driver.drive): its bookkeeping with a scripted integrator. That
every solver follows the automaton's impact law is tested in test_impact_law.py, and the exact solver's loop
against this one with a closed-form stepper in test_kernel.py."""

import math

import mpmath
import pytest

from escapement.model.automaton import Mode
from escapement.model.events import EventKind
from escapement.model.limits import RunLimits, RunSpec
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.integrators.driver import HORIZON, NO_EVENT, Step, drive

A1, A2, A3, A4 = EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4
P = Parameters(M=1.0, K=4.0, F=2.0, b=0.25, a1=-0.1, a2=0.05)  # w = 2 rad/s, F/K = 0.5 m


class Scripted:
    """A stepper that answers from a script and records what the loop asked."""

    name = "scripted"

    def __init__(self, script):
        self.script, self.asked, self.trajectory_asked = list(script), [], None

    def next_event(self, mode, centre, t, x, v, watched, t_stop):
        self.asked.append((mode, centre, t, x, v, tuple(watched)))
        return self.script.pop(0)

    def trajectory(self, t_final):
        self.trajectory_asked = t_final


def _drive(script, params=P, **limits):
    stepper = Scripted(script)
    return drive(RunSpec(params, 1.0, 0.0, RunLimits(**limits)), stepper), stepper


def test_the_loop_follows_the_automaton_and_keeps_the_books():
    script = [Step(A3, 1.0, -2.0, 1.0), Step(A4, 0.5, -1.0, 0.1), Step(A1, 2.0, 3.0, -0.05), Step(A2, 0.25, 2.5, 0.05),
              Step(A3, 1.5, -2.0, 0.7), Step(A4, 0.5, -1.0, 0.1), Step(A1, 2.0, 4.0, -0.05)]
    sol, stepper = _drive(script, n_cycles=1)
    assert sol.status == Status.COMPLETED and sol.message == "completed 1 cycles"
    assert sol.events.kind.tolist() == [3, 4, 1, 2, 3, 4, 1]
    assert sol.events.t.tolist() == [1.0, 1.5, 3.5, 3.75, 5.25, 5.75, 7.75]
    assert sol.events.x.tolist() == [0.1, -0.05, -0.1, 0.05, 0.1, -0.05, -0.1]
    assert sol.events.v_before.tolist() == [-2.0, -1.0, 3.0, 2.5, -2.0, -1.0, 4.0]
    assert sol.events.v_after.tolist() == [-1.5, -1.0, 2.25, 2.5, -1.5, -1.0, 3.0]  # (1 - b) v at impacts only
    # one complete cycle, from the impact at a1 at 3.5 s to the next at 7.75 s
    cycles = sol.cycles
    assert (cycles.impact_time.tolist(), cycles.velocity_before_impact.tolist()) == ([3.5], [3.0])
    assert (cycles.period.tolist(), cycles.largest_displacement.tolist()) == ([4.25], [0.7])
    assert sol.t_final == 7.75 and stepper.trajectory_asked == 7.75
    # what the loop asked: mode, centre (0, +F/K, -F/K), time, state after the jump, watched surfaces
    assert stepper.asked == [
        (Mode.FREE, 0.0, 0.0, 1.0, 0.0, (A1, A3)), (Mode.ZONE_LEFT, -0.5, 1.0, 0.1, -1.5, (A4,)),
        (Mode.FREE, 0.0, 1.5, -0.05, -1.0, (A1,)), (Mode.ZONE_RIGHT, 0.5, 3.5, -0.1, 2.25, (A2,)),
        (Mode.FREE, 0.0, 3.75, 0.05, 2.5, (A3,)), (Mode.ZONE_LEFT, -0.5, 5.25, 0.1, -1.5, (A4,)),
        (Mode.FREE, 0.0, 5.75, -0.05, -1.0, (A1,))]


def test_an_integrator_time_and_position_are_used_when_given():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0, t_abs=0.9, x_at=0.09), Step(A4, 0.5, -1.0, 0.1)], max_events=2,
                    n_cycles=3)
    assert sol.events.t.tolist() == [0.9, 1.4] and sol.events.x.tolist() == [0.09, -0.05]
    assert sol.status == Status.EVENT_LIMIT and "max_events = 2" in sol.message and sol.t_final == 1.4


def test_no_event_in_free_flight_is_stopped_and_a_stepper_without_a_trajectory_keeps_none():
    class Bare:  # a stepper that keeps no motion has no trajectory method
        name, next_event = "bare", Scripted([Step(A3, 1.0, -2.0, 1.0), Step(A4, 0.5, -1.0, 0.1),
                                             Step(NO_EVENT, math.inf, 0.0, 0.08)]).next_event

    sol = drive(RunSpec(P, 1.0, 0.0, RunLimits(n_cycles=3)), Bare())
    assert sol.status == Status.STOPPED and sol.t_final == math.inf and sol.trajectory is None
    # after the impulse (a4, a3) only a1 is awaited
    assert "a1 = -0.1 m (moving right)" in sol.message and "a3 =" not in sol.message
    assert sol.exit.turning_point == 0.08 and sol.exit.margin == pytest.approx(0.02, rel=1e-14)


def test_no_event_in_a_zone_is_turned_back():
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), Step(NO_EVENT, 0.25, 0.0, -0.04)], n_cycles=3)
    assert sol.status == Status.TURNED_BACK_IN_ZONE and "(a4, a3)" in sol.message and sol.t_final == 1.25
    assert sol.exit.turning_point == -0.04 and sol.exit.margin == pytest.approx(0.01, rel=1e-14)


@pytest.mark.parametrize("last", [Step(A4, 5.0, -1.0, 0.1), Step(HORIZON, math.inf, 0.0, 0.1)], ids=["late", "horizon"])
def test_the_end_time_ends_the_run_inside_an_arc(last):
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0), last], t_end=2.0)
    assert sol.status == Status.COMPLETED and sol.t_final == 2.0 and len(sol.events) == 1


def test_a_reversing_impact_is_chattering_with_the_zeno_time():
    p = Parameters(M=1.0, K=4.0, F=2.0, b=1.5, a1=-0.1, a2=0.05)
    sol, _ = _drive([Step(A3, 1.0, -2.0, 1.0)], params=p, n_cycles=3)
    assert sol.status == Status.CHATTERING and sol.events.v_after.tolist() == [1.0]
    # flights of (2/w) atan(r^n v / (w d)) with v = 1, d = a3 = 0.1, w = 2, r = |1 - b| = 0.5
    with mpmath.workdps(30):
        total = mpmath.nsum(lambda n: mpmath.atan(5 * mpmath.mpf(0.5) ** n), [0, mpmath.inf])
    assert sol.exit.t_accumulation == pytest.approx(1.0 + float(total), rel=1e-14)
