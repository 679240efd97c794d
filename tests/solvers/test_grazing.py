"""Grazing: a turning point a margin delta beyond or short of a surface, built in closed form.

Each case starts at rest at ``x0``, and its first decisive arc turns ``delta`` beyond a surface
(``delta < 0``: short of it):

* the impulse zone (a1, a2), entered by the impact at a1, turns beyond a2 (a2 is crossed just
  before the turning point) or short of it (the mass turns back in the zone);
* the same for the zone (a4, a3), entered at a3, and its end a4;
* the free swing turns beyond a3 (a3 is crossed moving left just after the turning point) or
  short of it (the escapement never starts); the same for a1.

Which surfaces can be grazed: an impact position is reached moving towards the free centre, so
only just after a turning point; a zone's end lies beyond the zone's centre (here a2 > F/K) and
is reached moving away from it, just before a turning point. The zones here are narrower than
their ends' distance from the centre, so that a zone arc can turn near its end (the arc from a1
about F/K turns at or beyond 2 F/K - a1 = 0.04 m, short of a2 = 0.05 m).

The release point comes from the closed form of the arcs in 50-digit arithmetic: from rest at
``x0`` the free arc ``x = x0 cos(w t)`` reaches the impact position ``p`` with
``v**2 = w**2 (x0**2 - p**2)``, the impact keeps ``(1 - b)`` of it, and the zone arc about ``c``
through ``(p, v+)`` turns at ``c +- R``, ``R**2 = (p - c)**2 + (v+ / w)**2``. The margin the
rounded ``x0`` really gives is computed again from it, so the expected outcome is the closed
form's, not either solver's.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import numpy as np
import pytest

from escapement.model import automaton
from escapement.model.automaton import Mode
from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.integrators.driver import NO_EVENT
from escapement.solvers.exact import solve_exact
from escapement.integrators.reference import (
    CvodeIntegrator,
    Hit,
    IvpStepper,
    SciPyIntegrator,
    Segment,
    Watch,
    solve_reference,
)

#: the margins, in m (the positions are 0.02 to 0.2 m): above every agreement margin, at the looser one, between
#: it and the tighter one, at the tighter one, and below it
MARGINS = tuple(10.0**-k for k in (3, 8, 9, 10, 12))
#: the stepper's tolerance in the agreement tests: that of the tests of the reference and of the stress table
RTOL = 1e-12
#: down to this margin the reference (DOP853, rtol 1e-12) agrees with the exact solver and the closed form:
#: 1e-9 of the 0.1 m scale, some 1000 times its absolute tolerance rtol * L (L = 0.05 to 0.2 m here). Measured,
#: it agrees at every margin down to 1e-12 m: its zone arcs turn within 2e-13 m of the closed form, its free
#: swings within 1.5e-12 m after three half swings. Below AGREEMENT_MARGIN only the consistency of its outcome
#: is required
AGREEMENT_MARGIN = 1e-10
#: the same for the integrators at rtol 1e-10. Measured: DOP853, RK45 and LSODA agree down to 1e-10 m,
#: CVODE-Adams down to 1e-9 m and CVODE-BDF down to 1e-8 m (its free swings turn some 1e-9 m short per
#: half swing, its zone arcs 4e-10 m short)
LOOSE_RTOL = 1e-10
LOOSE_AGREEMENT_MARGIN = 1e-8
#: a located crossing lies within this distance of the surface along the closed-form arc, in m
#: (the reference's positions are good to some 2e-13 m at rtol 1e-12)
CROSSING_POSITION = 1e-11

ZONE_GEOMETRY = Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.02, a2=0.05, a3=0.02, a4=-0.05)
#: free swings that reach one impact position and not the other (F = 0: the zones only end)
A3_GEOMETRY = Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.2, a2=0.0, a3=0.1, a4=0.0)
A1_GEOMETRY = Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.1, a2=0.0, a3=0.2, a4=0.0)

DIGITS = 50


def _mp(value: float) -> mpmath.mpf:
    return mpmath.mpf(value)  # the float's exact binary value


@dataclass(frozen=True)
class Case:
    """A release from rest at ``x0`` whose decisive turning point lies ``margin`` beyond ``surface``
    (``margin < 0``: short of it)."""

    name: str
    params: Parameters
    x0: float
    surface: EventKind
    margin: float  #: the margin the rounded x0 gives (50 digits, rounded to a float)

    @property
    def crosses(self) -> bool:
        return self.margin > 0.0

    @property
    def zone(self) -> bool:
        return not self.surface.is_impact

    @property
    def expected_start(self) -> list[int]:
        """The first events, from the closed form: the zone's entry and, if it crosses, its end; for
        a free swing, if it crosses, the impact and the end of the zone it opens (which the zone arc,
        leaving the impact position towards the centre with the ends between, always reaches)."""
        if self.zone:
            entry = EventKind.IMPACT_A1 if self.surface == EventKind.ZONE_END_A2 else EventKind.IMPACT_A3
            return [int(entry), int(self.surface)] if self.crosses else [int(entry)]
        end = EventKind.ZONE_END_A2 if self.surface == EventKind.IMPACT_A1 else EventKind.ZONE_END_A4
        return [int(self.surface), int(end)] if self.crosses else []

    @property
    def expected_exit(self) -> Status | None:
        """The outcome when the surface is not crossed (None: the run goes on)."""
        if self.crosses:
            return Status.STOPPED if not self.zone else None
        return Status.TURNED_BACK_IN_ZONE if self.zone else Status.STOPPED

    @property
    def turning_point(self) -> float:
        """The decisive turning point, closed form."""
        s = automaton.SURFACES[self.surface]
        position = automaton.position(self.surface, self.params)
        return float(_mp(position) + s.direction * (1 if self.zone else -1) * _mp(self.margin))


def _zone(p: Parameters, end: EventKind):
    """The impact that opens the zone ending at ``end``, its position, the zone's centre, and the side
    of the centre the zone arc turns on."""
    if end == EventKind.ZONE_END_A2:
        return EventKind.IMPACT_A1, _mp(p.a1), _mp(p.F) / _mp(p.K), 1
    return EventKind.IMPACT_A3, _mp(p.a3), -_mp(p.F) / _mp(p.K), -1


def _zone_radius(p: Parameters, end: EventKind, x0: mpmath.mpf) -> mpmath.mpf:
    """Closed form: from rest at x0 the free arc reaches the impact position; the zone arc after the
    impact has radius R about the zone's centre."""
    _, where, centre, _ = _zone(p, end)
    w2 = _mp(p.K) / _mp(p.M)
    v_sq_after = (1 - _mp(p.b)) ** 2 * w2 * (x0 * x0 - where * where)
    return mpmath.sqrt((where - centre) ** 2 + v_sq_after / w2)


def zone_case(end: EventKind, delta: float) -> Case:
    """The zone arc turns ``delta`` beyond the zone's end ``end`` (``delta < 0``: short of it)."""
    p = ZONE_GEOMETRY
    with mpmath.workdps(DIGITS):
        _, where, centre, side = _zone(p, end)
        w2 = _mp(p.K) / _mp(p.M)
        surface = _mp(automaton.position(end, p))
        target = surface + side * _mp(delta)
        v_sq_after = w2 * ((target - centre) ** 2 - (where - centre) ** 2)
        v_sq_before = v_sq_after / (1 - _mp(p.b)) ** 2
        x0 = float(-side * mpmath.sqrt(where * where + v_sq_before / w2))
        turning = centre + side * _zone_radius(p, end, _mp(x0))
        margin = float(side * (turning - surface))
    return Case(f"{end.name}{delta:+.0e}", p, x0, end, margin)


def free_case(impact: EventKind, delta: float) -> Case:
    """The free swing from rest turns ``delta`` beyond the impact position (``delta < 0``: short of
    it): it is released at rest on the other side, as far from the centre."""
    with mpmath.workdps(DIGITS):
        if impact == EventKind.IMPACT_A3:
            p = A3_GEOMETRY
            x0 = float(-(_mp(p.a3) + _mp(delta)))
            margin = float(-_mp(x0) - _mp(p.a3))  # the swing turns at -x0
        else:
            p = A1_GEOMETRY
            x0 = float(-_mp(p.a1) + _mp(delta))
            margin = float(_mp(p.a1) + _mp(x0))  # turns at -x0: beyond a1 is further left
    return Case(f"{impact.name}{delta:+.0e}", p, x0, impact, margin)


def _cases() -> list[Case]:
    cases = []
    for delta in MARGINS:
        for sign in (1.0, -1.0):
            cases.append(zone_case(EventKind.ZONE_END_A2, sign * delta))
            cases.append(zone_case(EventKind.ZONE_END_A4, sign * delta))
            cases.append(free_case(EventKind.IMPACT_A3, sign * delta))
            cases.append(free_case(EventKind.IMPACT_A1, sign * delta))
    return cases


CASES = _cases()
# the float margins are those asked for to within a few ulps of x0
ABOVE = [c for c in CASES if abs(c.margin) > 0.99 * AGREEMENT_MARGIN]
LOOSE = [c for c in CASES if abs(c.margin) > 0.99 * LOOSE_AGREEMENT_MARGIN]


def _ids(cases):
    return [c.name for c in cases]


def zone_end_crossing(case: Case) -> tuple[float, float]:
    """Closed form: the time and velocity at which a zone case's arc reaches the zone's end, before
    its turning point. The free arc from rest ``x = x0 cos(w t)`` reaches the impact position at
    ``acos(p / x0) / w``; the zone arc ``x = c + side R cos(w (t - t_turn))`` then turns after
    ``acos(side (p - c) / R) / w`` and passes the end ``e`` ``acos(side (e - c) / R) / w`` before that."""
    p = case.params
    with mpmath.workdps(DIGITS):
        _, where, centre, side = _zone(p, case.surface)
        w = mpmath.sqrt(_mp(p.K) / _mp(p.M))
        x0 = _mp(case.x0)
        radius = _zone_radius(p, case.surface, x0)
        end = _mp(automaton.position(case.surface, p))
        t_impact = mpmath.acos(where / x0) / w
        t = t_impact + (mpmath.acos(side * (where - centre) / radius) - mpmath.acos(side * (end - centre) / radius)) / w
        v = side * w * mpmath.sqrt(radius**2 - (end - centre) ** 2)
        return float(t), float(v)


def assert_consistent(run, case: Case) -> None:
    """A valid outcome whatever the margin: every surface is crossed moving in its direction, and the
    turning point an exit reports lies short of (or on) the surface it did not pass."""
    p = case.params
    assert run.status in (Status.COMPLETED, Status.STOPPED, Status.TURNED_BACK_IN_ZONE), run.message
    for kind, v in zip(run.events.kind, run.events.v_before):
        assert automaton.SURFACES[EventKind(kind)].direction * v >= 0.0, (case.name, run.events.kind)
    if run.status is Status.TURNED_BACK_IN_ZONE:
        if run.events.kind[-1] == EventKind.IMPACT_A1:
            assert run.exit.turning_point <= p.a2, run.message
        else:
            assert run.events.kind[-1] == EventKind.IMPACT_A3
            assert run.exit.turning_point >= p.a4, run.message
    if run.status is Status.STOPPED:
        assert run.exit.margin >= 0.0, run.message


@pytest.mark.parametrize("case", CASES, ids=_ids(CASES))
def test_the_exact_solver_follows_the_closed_form(case):
    exact = solve_exact(case.params, case.x0, n_cycles=3)
    assert list(exact.events.kind[: len(case.expected_start)]) == case.expected_start
    if case.expected_exit is not None:
        assert exact.status == case.expected_exit
        if not case.crosses:
            assert len(exact.events) == len(case.expected_start)
            assert abs(exact.exit.turning_point) == pytest.approx(abs(case.turning_point), abs=1e-16)


@pytest.mark.parametrize("case", ABOVE, ids=_ids(ABOVE))
def test_the_reference_agrees_with_the_exact_solver_and_the_closed_form(case):
    """Same outcome and events as the exact solver, the closed form's first events and exit, down to
    AGREEMENT_MARGIN; a crossing of a zone's end located on the closed-form arc, on the dense output kept (every
    other case) or on the segment integrated again."""
    exact = solve_exact(case.params, case.x0, n_cycles=3)
    record = ABOVE.index(case) % 2 == 0
    ref = solve_reference(case.params, case.x0, n_cycles=3, rtol=RTOL, record_trajectory=record)
    assert ref.status == exact.status, (ref.message, exact.message)
    assert np.array_equal(ref.events.kind, exact.events.kind)
    assert list(ref.events.kind[: len(case.expected_start)]) == case.expected_start
    if case.expected_exit is not None:
        assert ref.status == case.expected_exit
    if case.zone and not case.crosses:
        assert ref.exit.turning_point == pytest.approx(case.turning_point, abs=CROSSING_POSITION)
    if case.zone and case.crosses:
        t, v = zone_end_crossing(case)
        assert abs(ref.events.t[1] - t) * abs(v) < CROSSING_POSITION
        assert ref.events.v_before[1] * v >= 0.0
    assert_consistent(ref, case)


@pytest.mark.parametrize("case", [c for c in CASES if c not in ABOVE], ids=_ids([c for c in CASES if c not in ABOVE]))
def test_the_reference_outcome_is_consistent_below_the_agreement_margin(case):
    ref = solve_reference(case.params, case.x0, n_cycles=3, rtol=RTOL, record_trajectory=False)
    assert_consistent(ref, case)


@pytest.mark.parametrize("method", ["DOP853", "RK45", "LSODA", "CVODE-Adams", "CVODE-BDF"])
def test_other_integrators_agree_down_to_their_tolerance_and_stay_consistent_below(method):
    """At rtol 1e-10, agreement down to LOOSE_AGREEMENT_MARGIN (without dense output: the segment is
    integrated again where a crossing was missed); a consistent outcome at every margin. (Radau, an
    implicit method, takes some 30 s for these runs at this tolerance; it is left out.)"""
    for case in CASES:
        ref = solve_reference(case.params, case.x0, n_cycles=3, method=method, rtol=LOOSE_RTOL,
                              record_trajectory=False)
        assert_consistent(ref, case)
        if abs(case.margin) > 0.99 * LOOSE_AGREEMENT_MARGIN:
            exact = solve_exact(case.params, case.x0, n_cycles=3)
            assert ref.status == exact.status, (case.name, ref.message, exact.message)
            assert np.array_equal(ref.events.kind, exact.events.kind), case.name


# --- the pieces: locating a missed crossing, and the stop rule ------------------------------------


def _a2_segment(delta: float):
    """The zone arc of the case turning ``delta`` beyond a2, from the impact at a1 to its turning point
    (closed form): the segment, the turning point as its end, and the crossing of a2."""
    case = zone_case(EventKind.ZONE_END_A2, delta)
    p = case.params
    with mpmath.workdps(DIGITS):
        w = mpmath.sqrt(_mp(p.K) / _mp(p.M))
        x0 = _mp(case.x0)
        c = _mp(p.F) / _mp(p.K)
        t_impact = mpmath.acos(_mp(p.a1) / x0) / w
        v_after = (1 - _mp(p.b)) * w * mpmath.sqrt(x0 * x0 - _mp(p.a1) ** 2)
        radius = _zone_radius(p, EventKind.ZONE_END_A2, x0)
        t_turn = t_impact + mpmath.acos((_mp(p.a1) - c) / radius) / w
        turning = float(c + radius)
    seg = Segment(p.omega2, p.zone_offset, float(t_impact), (p.a1, float(v_after)), float(t_impact) + 5.0,
                  (Watch(p.a2, 1), Watch(None, 1)))
    return seg, Hit(float(t_turn), 1, (turning, 0.0)), zone_end_crossing(case)


@pytest.mark.parametrize("delta", [1e-4, 1e-6, 1e-8])
def test_cvode_locates_a_crossing_before_a_turning_point_by_integrating_back(delta):
    pytest.importorskip("sksundae")
    seg, end, (t, v) = _a2_segment(delta)
    atol = np.array([1e-10 * 0.05, 1e-10 * 0.05])
    hit = CvodeIntegrator("Adams", 1e-10, atol).crossing(seg, None, end, 0)
    assert hit.index == 0
    assert abs(hit.t - t) * abs(v) < 1e-9  # within 1e-9 m of a2 along the arc: 200 times atol
    assert hit.y[0] == pytest.approx(seg.watches[0].position, abs=1e-9)
    assert hit.y[1] == pytest.approx(v, abs=1e-9)


@pytest.mark.parametrize("delta", [1e-6, 1e-8, 1e-10])
def test_scipy_locates_a_crossing_on_the_dense_output_kept_or_computed_again(delta):
    seg, _, (t, v) = _a2_segment(delta)
    atol = np.array([RTOL * 0.05, RTOL * 0.05])
    kept = SciPyIntegrator("DOP853", RTOL, atol, dense=True)
    hit, dense = kept.segment(seg)
    assert hit.index == 1  # the segment ends at the turning point ...
    assert hit.y[0] > seg.watches[0].position  # ... beyond a2
    from_kept = kept.crossing(seg, dense, hit, 0)
    lean = SciPyIntegrator("DOP853", RTOL, atol, dense=False)
    lean_hit, nothing = lean.segment(seg)
    assert nothing is None and lean_hit == hit
    assert lean.crossing(seg, None, hit, 0) == from_kept  # the same steps, the same interpolant
    assert abs(from_kept.t - t) * abs(v) < CROSSING_POSITION
    assert from_kept.y[0] == pytest.approx(seg.watches[0].position, abs=1e-15)


class ScriptedIntegrator:
    """A stand-in integrator that ends each segment where a script says, and records what it watched."""

    name = "scripted"

    def __init__(self, ends: list[Hit]) -> None:
        self.ends = list(ends)
        self.watched: list[tuple[Watch, ...]] = []

    def segment(self, seg: Segment):
        self.watched.append(seg.watches)
        return self.ends.pop(0), None

    def crossing(self, seg, dense, end, index):
        raise AssertionError("no crossing is missed in the script")


def _free_stepper(ends: list[Hit]) -> tuple[IvpStepper, ScriptedIntegrator]:
    integrator = ScriptedIntegrator(ends)
    return IvpStepper(A3_GEOMETRY, integrator, record_trajectory=False), integrator


def test_a_free_run_stops_after_three_turning_points_short_of_the_awaited_impact():
    a3 = A3_GEOMETRY.a3
    stepper, integrator = _free_stepper([Hit(1.0, 0, (a3 - 1e-9, 0.0)), Hit(2.0, 1, (-(a3 - 1e-9), 0.0)),
                                         Hit(3.0, 0, (a3 - 1e-9, 0.0))])
    step = stepper.next_event(Mode.FREE, 0.0, 0.0, 0.05, 0.3, (EventKind.IMPACT_A3,), np.inf)
    assert step.kind == NO_EVENT and step.x_max == a3 - 1e-9
    assert len(integrator.watched) == 3


def test_a_free_run_does_not_stop_at_a_turning_point_beyond_the_awaited_impact():
    """The third turning point lies beyond a3 (within the integration error of the first): the swing
    after it crosses a3, so the run goes on rather than report a swing that turns beyond a3 but
    never passes it."""
    a3 = A3_GEOMETRY.a3
    beyond = a3 + 1e-15
    stepper, integrator = _free_stepper([Hit(1.0, 0, (a3 - 1e-15, 0.0)), Hit(2.0, 1, (-(a3 - 1e-15), 0.0)),
                                         Hit(3.0, 0, (beyond, 0.0)), Hit(3.001, 0, (a3, -1e-7))])
    step = stepper.next_event(Mode.FREE, 0.0, 0.0, 0.05, 0.3, (EventKind.IMPACT_A3,), np.inf)
    assert step.kind == EventKind.IMPACT_A3 and step.v == -1e-7 and step.t_abs == 3.001
    assert integrator.watched[3][0] == Watch(a3, -1)  # the fourth segment watched a3
