"""The reference solver (SciPy's solve_ivp, SUNDIALS CVODE) against the exact one: the same outcomes and events,
times and velocities within the integrator's tolerance, grazing crossings and turning points not missed."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from strategies import initial_displacement, initial_velocity, parameters

from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.exact import solve_exact
from escapement.integrators.reference import solve_reference

AGREEMENT = 1e-8


@settings(max_examples=6, deadline=None)
@given(p=parameters(), x0=initial_displacement, v0=initial_velocity)
def test_exact_and_reference_agree_to_1e8(p, x0, v0):
    """Same outcome, same events; times and velocities within 1e-8 of their scales."""
    exact = solve_exact(p, x0, v0, n_cycles=3)
    length = max(abs(x0), abs(p.a1), abs(p.a2), abs(p.a3), abs(p.a4), p.zone_offset, abs(v0) / p.omega)
    t_scale, v_scale = p.natural_period, length * p.omega
    # Grazing is decided by rounding and has its own tests: solve_ivp places x within atol = 1e-12 L of a surface,
    # which moves an event slower than 1e-4 v_scale by more than 1e-8 T, so such runs are left out.
    assume(math.isnan(exact.exit.margin) or exact.exit.margin > 1e-4 * v_scale / p.omega)
    assume(len(exact.events) == 0 or np.min(np.abs(exact.events.v_before)) > 1e-4 * v_scale)
    ref = solve_reference(p, x0, v0, n_cycles=3, rtol=1e-12)
    assert ref.status == exact.status, (ref.message, exact.message)
    assert np.array_equal(ref.events.kind, exact.events.kind)
    assert np.max(np.abs(ref.events.t - exact.events.t), initial=0.0) < AGREEMENT * t_scale
    for name in ("v_before", "v_after"):
        gap = np.abs(getattr(ref.events, name) - getattr(exact.events, name))
        assert np.max(gap, initial=0.0) < AGREEMENT * v_scale
    gap = np.max(np.abs(ref.cycles.largest_displacement - exact.cycles.largest_displacement), initial=0.0)
    assert gap < AGREEMENT * v_scale / p.omega
    if exact.status == Status.TURNED_BACK_IN_ZONE:
        assert abs(ref.t_final - exact.t_final) < AGREEMENT * t_scale


def test_paper_case_a_over_10_cycles(case_a):
    exact = solve_exact(case_a, 1.0, n_cycles=10)
    ref = solve_reference(case_a, 1.0, n_cycles=10)
    assert ref.status == Status.COMPLETED
    assert list(ref.events.kind[:4]) == [EventKind.IMPACT_A3, EventKind.ZONE_END_A4, EventKind.IMPACT_A1,
                                         EventKind.ZONE_END_A2]
    assert ref.cycles.period == pytest.approx(exact.cycles.period, rel=1e-10)
    assert ref.cycles.velocity_before_impact == pytest.approx(exact.cycles.velocity_before_impact, rel=1e-10)


def test_a_run_to_an_end_time_samples_as_the_exact_arcs(case_b):
    exact = solve_exact(case_b, 3.0, t_end=10.0)
    ref = solve_reference(case_b, 3.0, t_end=10.0)
    assert ref.status == exact.status == Status.COMPLETED and ref.t_final == 10.0
    t = np.linspace(0.0, 10.0, 501)
    for a, b in zip(ref.sample(t), exact.sample(t)):
        assert a == pytest.approx(b, abs=1e-9)


@pytest.mark.parametrize("p, x0, status", [
    (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 0.05, Status.STOPPED),
    (Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1), 0.021, Status.TURNED_BACK_IN_ZONE),
    (Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, Status.CHATTERING),
    (Parameters(M=1, K=1, F=0.0, b=0.1, a1=-0.1, a2=0.05, a3=0.3, a4=0.0), 0.4, Status.STOPPED),
], ids=["stopped", "turned back", "chattering", "stopped after cycles"])
def test_regime_exits_are_those_of_the_exact_solver(p, x0, status):
    ref, exact = solve_reference(p, x0, n_cycles=100), solve_exact(p, x0, n_cycles=100)
    assert ref.status == exact.status == status and len(ref.events) == len(exact.events)
    assert ref.exit.t_accumulation == pytest.approx(exact.exit.t_accumulation, rel=1e-9, nan_ok=True)


def test_cvode_agrees_keeps_no_trajectory_and_takes_numpy_tolerances(case_a):
    exact = solve_exact(case_a, 1.0, n_cycles=2)
    ref = solve_reference(case_a, 1.0, n_cycles=2, method="CVODE-Adams", rtol=np.float32(1e-10),
                          atol=np.float64(1e-12), record_trajectory=False)
    assert ref.status == Status.COMPLETED and ref.trajectory is None
    assert ref.cycles.impact_time == pytest.approx(exact.cycles.impact_time, rel=1e-7)


def test_a_loose_tolerance_misses_no_turning_point(case_a):
    """At rtol 0.1 DOP853 would take steps of more than half a period, over two zeros of the velocity
    (no change of sign across the step: no turning point found, and the run stopped after two events);
    steps are kept below half a period, so each holds at most one."""
    exact = solve_exact(case_a, 1.0, n_cycles=2)
    for record in (True, False):
        ref = solve_reference(case_a, 1.0, n_cycles=2, rtol=0.1, record_trajectory=record)
        assert ref.status == Status.COMPLETED, ref.message
        assert np.array_equal(ref.events.kind, exact.events.kind)


def test_a_zone_end_passed_just_before_the_turning_point_is_not_missed():
    """The zone arc from a1 about F/K = 0.01 m turns 1e-6 m beyond a2 = 0.05 m, at
    c + sqrt((a1 - c)**2 + ((1 - b) v- / w)**2) with v- = -w sqrt(x0**2 - a1**2) from rest at x0
    (x0 from that closed form, 17 digits); one step of the integrator spans the crossing of a2 and the
    turning point beyond it, where x - a2 has the same sign at both ends."""
    p = Parameters(M=1, K=1, F=0.01, b=0.1, a1=-0.02, a2=0.05, a3=0.02, a4=-0.05)
    x0 = -0.0355569444346792  # -sqrt(a1**2 + (0.040001**2 - 0.03**2) / 0.9**2)
    radius = math.sqrt((p.a1 - p.zone_offset) ** 2 + (1 - p.b) ** 2 * (x0 * x0 - p.a1 * p.a1))
    assert p.zone_offset + radius - p.a2 == pytest.approx(1e-6, rel=1e-6)
    exact = solve_exact(p, x0, n_cycles=1)
    for record in (True, False):
        ref = solve_reference(p, x0, n_cycles=1, rtol=1e-12, record_trajectory=record)
        assert ref.status == exact.status == Status.COMPLETED, ref.message
        assert list(ref.events.kind[:2]) == [EventKind.IMPACT_A1, EventKind.ZONE_END_A2]
        assert np.array_equal(ref.events.kind, exact.events.kind)
