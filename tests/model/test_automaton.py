"""The escapement's rules as a hybrid automaton (Sec. 2 and Appendix A of the paper), table by table."""

import mpmath
import numpy as np
import pytest

from escapement.model import automaton as am
from escapement.model.automaton import Awaited, Mode
from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status

A1, A2, A3, A4 = EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4
P = Parameters(M=1.0, K=4.0, F=2.0, b=0.1, a1=-0.1, a2=0.05, a3=0.2, a4=-0.03)


def test_surfaces_are_the_paper_positions_and_directions():
    # a1, a2 are met moving right (first half cycle), a3, a4 moving left (second half cycle)
    assert {k: (s.position, s.direction) for k, s in am.SURFACES.items()} == {
        A1: ("a1", 1), A2: ("a2", 1), A3: ("a3", -1), A4: ("a4", -1)}
    assert [am.position(k, P) for k in (A1, A2, A3, A4)] == [-0.1, 0.05, 0.2, -0.03]


def test_event_codes_and_impacts():
    assert [int(k) for k in (A1, A2, A3, A4)] == [1, 2, 3, 4]
    assert (int(Awaited.EITHER), int(Awaited.A1), int(Awaited.A3)) == (0, 1, 3)
    assert [am.is_impact(k) for k in (A1, A2, A3, A4)] == [True, False, True, False]
    assert [k.is_impact for k in (A1, A2, A3, A4)] == [True, False, True, False]


def test_watched_surfaces_in_each_state():
    assert am.INITIAL == (Mode.FREE, Awaited.EITHER)
    assert set(am.watched(Mode.FREE, Awaited.EITHER)) == {A1, A3}
    assert am.watched(Mode.FREE, Awaited.A1) == (A1,)
    assert am.watched(Mode.FREE, Awaited.A3) == (A3,)
    # in a zone only its end is watched, whatever impact is awaited next
    for awaited in Awaited:
        assert am.watched(Mode.ZONE_RIGHT, awaited) == (A2,)
        assert am.watched(Mode.ZONE_LEFT, awaited) == (A4,)


def test_transitions_alternate_the_impacts():
    assert am.transition(A1) == (Mode.ZONE_RIGHT, Awaited.A3)  # the impulse follows the impact
    assert am.transition(A2) == (Mode.FREE, Awaited.A3)
    assert am.transition(A3) == (Mode.ZONE_LEFT, Awaited.A1)
    assert am.transition(A4) == (Mode.FREE, Awaited.A1)


def test_following_the_automaton_gives_the_cycle_of_the_paper():
    mode, awaited = am.INITIAL
    kinds = []
    chosen = A3  # released to the right of a3: the first impact is at a3
    for _ in range(8):
        assert chosen in am.watched(mode, awaited)
        kinds.append(chosen)
        mode, awaited = am.transition(chosen)
        (chosen,) = am.watched(mode, awaited)
    assert kinds == [A3, A4, A1, A2, A3, A4, A1, A2]


def test_centres_of_oscillation():
    # x'' = -w^2 x + f in (a1, a2), -f in (a4, a3): centres +F/K, -F/K, and 0 in free flight
    assert [am.centre(m, P.zone_offset) for m in Mode] == [0.0, 0.5, -0.5]
    assert am.centre(Mode.ZONE_LEFT, np.array([0.5, 2.0])).tolist() == [-0.5, -2.0]


def test_exits_without_an_event():
    assert am.EXIT_WITHOUT_EVENT == {Mode.FREE: Status.STOPPED, Mode.ZONE_RIGHT: Status.TURNED_BACK_IN_ZONE,
                                     Mode.ZONE_LEFT: Status.TURNED_BACK_IN_ZONE}
    assert am.ZONE_OF[Mode.ZONE_RIGHT] == ("(a1, a2)", A2)
    assert am.ZONE_OF[Mode.ZONE_LEFT] == ("(a4, a3)", A4)


def test_impact_law_on_floats_arrays_and_mpmath():
    # Eqs., (A-4): v+ = (1 - b) v- at an impact; no jump at the end of an impulse zone
    assert am.velocity_after(2.0, 0.25, True) == 1.5
    assert am.velocity_after(-2.0, 0.25, True) == -1.5
    assert am.velocity_after(2.0, 0.25, False) == 2.0
    got = am.velocity_after(np.array([2.0, 2.0, -4.0]), np.array([0.25, 0.25, 1.5]), np.array([True, False, True]))
    assert got.tolist() == [1.5, 2.0, 2.0]
    with mpmath.workdps(50):
        v = am.velocity_after(mpmath.mpf(2), mpmath.mpf("0.1"), True)
        assert isinstance(v, mpmath.mpf)
        assert abs(v - mpmath.mpf("1.8")) < mpmath.mpf("1e-49")


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
