"""The escapement's rules as a hybrid automaton (Sec. 2 and Appendix A of the paper), row by row: the
surfaces, the arcs after each state, the cycle they make, the impact law and the exits."""

import mpmath
import numpy as np
import pytest

from escapement.model import automaton as am
from escapement.model.automaton import RELEASE, Mode
from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status

A1, A2, A3, A4 = EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4
P = Parameters(M=1.0, K=4.0, F=2.0, b=0.1, a1=-0.1, a2=0.05, a3=0.2, a4=-0.03)


def test_surfaces_are_the_paper_positions_directions_and_impacts():
    # a1, a2 are met moving right (first half cycle), a3, a4 moving left (second half cycle)
    assert {k: (s.kind, s.position, s.direction, s.impact) for k, s in am.SURFACES.items()} == {
        A1: (A1, "a1", 1, True), A2: (A2, "a2", 1, False), A3: (A3, "a3", -1, True), A4: (A4, "a4", -1, False)}
    assert [int(k) for k in (A1, A2, A3, A4)] == [1, 2, 3, 4] and RELEASE not in [int(k) for k in EventKind]
    for code in (int, EventKind):  # by code too
        assert [am.position(code(k), P) for k in (A1, A2, A3, A4)] == [-0.1, 0.05, 0.2, -0.03]
        assert [am.is_impact(code(k)) for k in (A1, A2, A3, A4)] == [True, False, True, False]
    assert [k.is_impact for k in (A1, A2, A3, A4)] == [True, False, True, False]


def test_the_rows_of_the_automaton_and_the_cycle_they_make():
    """After the release the escapement awaits whichever impact comes first; the impulse follows an impact
    (the escapement unlocks there), free flight follows the end of a zone and awaits the other impact."""
    assert am.ARCS == {RELEASE: am.Arc(Mode.FREE, (A1, A3)), A1: am.Arc(Mode.ZONE_RIGHT, (A2,)),
                       A2: am.Arc(Mode.FREE, (A3,)), A3: am.Arc(Mode.ZONE_LEFT, (A4,)), A4: am.Arc(Mode.FREE, (A1,))}
    assert am.cycle_plan() == (A2, A3, A4, A1)
    assert am.ZONE_OF == {Mode.ZONE_RIGHT: ("(a1, a2)", A2), Mode.ZONE_LEFT: ("(a4, a3)", A4)}
    assert am.EXIT_WITHOUT_EVENT == {Mode.FREE: Status.STOPPED, Mode.ZONE_RIGHT: Status.TURNED_BACK_IN_ZONE,
                                     Mode.ZONE_LEFT: Status.TURNED_BACK_IN_ZONE}


def test_a_cycle_plan_that_never_returns_to_a1_is_refused(monkeypatch):
    broken = {**am.ARCS, A4: am.Arc(Mode.FREE, (A3,))}  # a4 -> a3 -> a4 -> ...: a1 is never reached again
    monkeypatch.setattr(am, "ARCS", broken)
    with pytest.raises(RuntimeError, match="do not return to the impact at a1"):
        am.cycle_plan()


def test_centres_of_oscillation():
    # x'' = -w^2 x + f in (a1, a2), -f in (a4, a3): centres +F/K, -F/K, and 0 in free flight
    assert [int(m) for m in Mode] == [0, 1, 2] and am.CENTRE_SIGN == (0.0, 1.0, -1.0)
    assert [am.centre(am.ARCS[s].mode, P.zone_offset) for s in (RELEASE, A1, A2, A3, A4)] == [0.0, 0.5, 0.0, -0.5, 0.0]
    assert am.centre(Mode.ZONE_LEFT, np.array([0.5, 2.0])).tolist() == [-0.5, -2.0]


def test_impact_law_on_floats_arrays_and_mpmath(monkeypatch):
    # Eqs., (A-4): v+ = (1 - b) v- at an impact (the ends of the impulse zones leave v as it is)
    assert am.impact_factor(0.25) == 0.75 and am.impact_factor(1.5) == -0.5
    assert (am.velocity_after(2.0, 0.25), am.velocity_after(-2.0, 0.25)) == (1.5, -1.5)
    assert am.velocity_after(np.array([2.0, -4.0]), np.array([0.25, 1.5])).tolist() == [1.5, 2.0]
    with mpmath.workdps(50):
        v = am.velocity_after(mpmath.mpf(2), mpmath.mpf("0.1"))
        assert isinstance(v, mpmath.mpf) and abs(v - mpmath.mpf("1.8")) < mpmath.mpf("1e-49")
    # velocity_after looks impact_factor up when it is called: the law is the one function
    monkeypatch.setattr(am, "impact_factor", lambda b: 1.0 - 2.0 * b)
    assert am.velocity_after(2.0, 0.25) == 1.0


def test_reversal_and_the_rebound_distance():
    assert am.reverses(1.0, -0.5) and am.reverses(-1.0, 0.5)
    assert not am.reverses(1.0, 0.0) and not am.reverses(1.0, 0.9)  # b = 1: the mass stops, it does not rebound
    assert am.reverses(np.array([1.0, 1.0]), np.array([-0.1, 0.1])).tolist() == [True, False]
    # a rebound at a1 < 0 sends the mass left; the spring pulls it back right to a1: distance |a1|
    assert (am.rebound_distance(A1, -0.1), am.rebound_distance(A3, 0.2)) == (0.1, 0.2)
    # an impact position on the far side of the centre: the spring drives the mass away, no return
    assert am.rebound_distance(A1, 0.1) < 0 and am.rebound_distance(A3, -0.2) < 0
