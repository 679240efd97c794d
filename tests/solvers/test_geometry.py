"""The geometry's conventions: the paper's signs a1 < 0 < a3, and the model's jump set read by the direction of
motion for any other placement (an impact met at or after the equilibrium, as in the escapement-error study's
zone after it). The rules on the four positions are tested with the parameters (tests/model)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from escapement import EventKind, Parameters, Status, solve_ensemble, solve_exact, solve_reference

BASE = dict(M=1.0, K=1.0, F=1.0, b=0.1)

#: placements outside the paper's signs, each (a1, a2, a3, a4), m: impacts after the equilibrium (the audit's
#: a1 = 0.1, a2 = 0.2 with the symmetric default; the escapement-error study's zone after it), a3 < a1 < 0,
#: both impacts left of the centre, an impact at the centre
OUTSIDE = [(0.1, 0.2, -0.1, -0.2), (0.05, 0.2, -0.05, -0.2), (-0.1, 0.05, -0.3, -0.4), (-0.2, -0.1, -0.05, -0.3),
           (0.0, 0.1, 0.1, -0.1)]


#: the paper's geometry (its Fig. 2) and the placements the workflow runs (config/paper.yaml: the checks' symmetric
#: and asymmetric positions), each (a1, a2, a3, a4), m
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
    """Under x -> -x the impact at a1 (moving right) becomes the one at a3 (moving left): (a1, a2, a3, a4)
    from x0 and (-a3, -a4, -a1, -a2) from -x0 give the same times, opposite positions and velocities."""
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
