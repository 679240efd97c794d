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


def test_surfaces_are_the_paper_positions_and_directions():
    # a1, a2 are met moving right (first half cycle), a3, a4 moving left (second half cycle)
    assert {k: (s.kind, s.position, s.direction, s.impact) for k, s in am.SURFACES.items()} == {
        A1: (A1, "a1", 1, True), A2: (A2, "a2", 1, False), A3: (A3, "a3", -1, True), A4: (A4, "a4", -1, False)}
    assert [am.position(k, P) for k in (A1, A2, A3, A4)] == [-0.1, 0.05, 0.2, -0.03]
    assert [am.position(int(k), P) for k in (A1, A2, A3, A4)] == [-0.1, 0.05, 0.2, -0.03]  # by code too


def test_event_codes_and_impacts():
    assert [int(k) for k in (A1, A2, A3, A4)] == [1, 2, 3, 4]
    assert RELEASE == 0 and RELEASE not in [int(k) for k in EventKind]  # the state before any event
    assert [am.is_impact(k) for k in (A1, A2, A3, A4)] == [True, False, True, False]
    assert [am.is_impact(int(k)) for k in (A1, A2, A3, A4)] == [k.is_impact for k in (A1, A2, A3, A4)]


def test_the_rows_of_the_automaton():
    """After the release the escapement awaits whichever impact comes first; the impulse follows an impact
    (the escapement unlocks there), free flight follows the end of a zone and awaits the other impact."""
    assert set(am.ARCS) == {RELEASE, A1, A2, A3, A4}
    assert am.ARCS[RELEASE].mode == Mode.FREE and set(am.ARCS[RELEASE].watched) == {A1, A3}
    assert am.ARCS[A1] == am.Arc(Mode.ZONE_RIGHT, (A2,))
    assert am.ARCS[A2] == am.Arc(Mode.FREE, (A3,))
    assert am.ARCS[A3] == am.Arc(Mode.ZONE_LEFT, (A4,))
    assert am.ARCS[A4] == am.Arc(Mode.FREE, (A1,))
    # every row after the release watches one surface, and the surfaces watched in free flight are impacts
    for state, arc in am.ARCS.items():
        if state != RELEASE:
            assert len(arc.watched) == 1
        if arc.mode == Mode.FREE:
            assert all(am.is_impact(k) for k in arc.watched)
        else:  # in a zone only its own end
            assert arc.watched == (am.ZONE_OF[arc.mode][1],)


def test_the_cycle_plan_follows_the_rows_from_a1_back_to_a1():
    assert am.cycle_plan() == (A2, A3, A4, A1)


def test_following_the_rows_gives_the_cycle_of_the_paper():
    kinds, state = [], RELEASE
    chosen = A3  # released to the right of a3: the first impact is at a3
    for _ in range(8):
        assert chosen in am.ARCS[state].watched
        kinds.append(chosen)
        state = chosen  # the event reached is the next state
        (chosen,) = am.ARCS[state].watched
    assert kinds == [A3, A4, A1, A2, A3, A4, A1, A2]


def test_a_cycle_plan_that_never_returns_to_a1_is_refused(monkeypatch):
    broken = {**am.ARCS, A4: am.Arc(Mode.FREE, (A3,))}  # a4 -> a3 -> a4 -> ...: a1 is never reached again
    monkeypatch.setattr(am, "ARCS", broken)
    with pytest.raises(RuntimeError, match="do not return to the impact at a1"):
        am.cycle_plan()


def test_centres_of_oscillation():
    # x'' = -w^2 x + f in (a1, a2), -f in (a4, a3): centres +F/K, -F/K, and 0 in free flight
    assert [am.centre(m, P.zone_offset) for m in Mode] == [0.0, 0.5, -0.5]
    assert am.centre(Mode.ZONE_LEFT, np.array([0.5, 2.0])).tolist() == [-0.5, -2.0]
    assert [am.centre(am.ARCS[s].mode, P.zone_offset) for s in (RELEASE, A1, A2, A3, A4)] == [0.0, 0.5, 0.0,
                                                                                               -0.5, 0.0]


def test_exits_without_an_event():
    assert am.EXIT_WITHOUT_EVENT == {Mode.FREE: Status.STOPPED, Mode.ZONE_RIGHT: Status.TURNED_BACK_IN_ZONE,
                                     Mode.ZONE_LEFT: Status.TURNED_BACK_IN_ZONE}
    assert am.ZONE_OF[Mode.ZONE_RIGHT] == ("(a1, a2)", A2)
    assert am.ZONE_OF[Mode.ZONE_LEFT] == ("(a4, a3)", A4)


def test_impact_law_on_floats_arrays_and_mpmath():
    # Eqs., (A-4): v+ = (1 - b) v- at an impact (the ends of the impulse zones leave v as it is)
    assert am.impact_factor(0.25) == 0.75 and am.impact_factor(1.5) == -0.5
    assert am.velocity_after(2.0, 0.25) == 1.5
    assert am.velocity_after(-2.0, 0.25) == -1.5
    got = am.velocity_after(np.array([2.0, -4.0]), np.array([0.25, 1.5]))
    assert got.tolist() == [1.5, 2.0]
    with mpmath.workdps(50):
        v = am.velocity_after(mpmath.mpf(2), mpmath.mpf("0.1"))
        assert isinstance(v, mpmath.mpf)
        assert abs(v - mpmath.mpf("1.8")) < mpmath.mpf("1e-49")


def test_the_velocity_after_follows_the_impact_factor(monkeypatch):
    """velocity_after applies impact_factor, looked up when it is called: the law is the one function."""
    monkeypatch.setattr(am, "impact_factor", lambda b: 1.0 - 2.0 * b)
    assert am.velocity_after(2.0, 0.25) == 1.0


def test_reversal():
    assert am.reverses(1.0, -0.5) and am.reverses(-1.0, 0.5)
    assert not am.reverses(1.0, 0.0)  # b = 1: the mass stops, it does not rebound
    assert not am.reverses(1.0, 0.9)
    assert am.reverses(np.array([1.0, 1.0]), np.array([-0.1, 0.1])).tolist() == [True, False]


def test_rebound_distance_is_positive_where_the_spring_brings_the_mass_back():
    # a rebound at a1 < 0 sends the mass left; the spring pulls it back right to a1: distance |a1|
    assert am.rebound_distance(A1, -0.1) == pytest.approx(0.1)
    assert am.rebound_distance(A3, 0.2) == pytest.approx(0.2)
    # an impact position on the far side of the centre: the spring drives the mass away, no return
    assert am.rebound_distance(A1, 0.1) < 0 and am.rebound_distance(A3, -0.2) < 0


def test_centre_sign_table_matches_the_modes():
    assert am.CENTRE_SIGN == (0.0, 1.0, -1.0)
    assert [int(m) for m in Mode] == [0, 1, 2]
