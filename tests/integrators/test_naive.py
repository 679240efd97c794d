"""The naive fixed-step RK4: an event is applied at the end of the step that passes it, so the errors are O(h)."""

import math

import pytest

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.exact import solve_exact
from escapement.integrators.naive import solve_naive

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)


def test_events_lie_at_most_one_step_past_their_surface_and_the_error_shrinks_with_the_step():
    """An event is applied up to one step late: the error is O(h), a factor about 10 for h / 10."""
    exact = solve_exact(P, 1.0, n_cycles=10).cycles.impact_time[-1]
    errors = []
    for h in (0.02, 0.002):
        run = solve_naive(P, 1.0, n_cycles=10, step=h)
        assert run.status == Status.COMPLETED and len(run.cycles) == 10
        errors.append(abs(run.cycles.impact_time[-1] - exact))
        positions = {1: P.a1, 2: P.a2, 3: P.a3, 4: P.a4}
        for kind, x, v in zip(run.events.kind, run.events.x, run.events.v_before):
            gap = (x - positions[int(kind)]) * (1 if kind in (1, 2) else -1)
            assert 0 <= gap <= abs(v) * h * 1.01
    assert 3 < errors[0] / errors[1] < 30
    assert errors[1] < len(run.events) * 0.002  # each of the events late by at most one step


def test_leaving_the_regime_is_a_typed_outcome_not_an_exception():
    run = solve_naive(P, 0.05, n_cycles=3, step=0.01)
    assert run.status == Status.STOPPED and not run.success
    assert run.exit.turning_point == pytest.approx(0.05, rel=1e-6)
    turned = solve_naive(Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1), 0.021, n_cycles=3, step=1e-4)
    assert turned.status == Status.TURNED_BACK_IN_ZONE
    chatter = solve_naive(Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, n_cycles=3, step=0.01)
    assert chatter.status == Status.CHATTERING


def test_the_largest_step_allowed_runs():
    run = solve_naive(P, 1.0, n_cycles=2, step=2 * math.pi / 20)
    assert run.status == Status.COMPLETED and len(run.cycles) == 2
