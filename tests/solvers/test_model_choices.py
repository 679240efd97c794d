"""The model's choices where the paper is silent, run by the event solver as settings of the one automaton: the force
of Eq. (5) from a release at rest in S2, and the motion continued past an accumulation of impacts; each against hand
derivations, and refused in one line where it is wrong or where a solver does not run it."""

from __future__ import annotations

import math

import pytest

from escapement import ParameterError, Parameters, solve_exact
from escapement.solvers.cycles import solve_cycles

PAPER = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}  # a3 = 0.1, a4 = -0.05, omega = 1, F/K = 1


@pytest.mark.parametrize("x0, zone_end", [(-0.0999, 2), (0.0999, 4)])
def test_a_release_at_rest_in_s2_under_eq5_starts_in_its_zone_and_converges_to_the_closed_form(x0, zone_end):
    """At rest at -0.0999 m the spring moves the mass right, in (a1, a2): it starts under the force (centre F/K = 1),
    v^2 = 1.0999^2 - 0.95^2 at a2; at 0.0999 m, mirrored, at a4. Both converge to v*^2 = 2 (a2 - a1) f / (2b - b^2);
    under the model's default the free swing of radius 0.0999 m never reaches an impact position (0.1 m)."""
    star = math.sqrt(2 * 0.15 * 1.0 / (2 * 0.1 - 0.1**2))
    run = solve_exact(Parameters(**PAPER, release_force="eq5"), x0, n_cycles=200, record_trajectory=False)
    assert run.events.kind[0] == zone_end
    assert abs(run.events.v_before[0]) == pytest.approx(math.sqrt(1.0999**2 - 0.95**2), rel=1e-12)
    assert abs(run.cycles.velocity_before_impact[-1] - star) <= 1e-9 * star
    default = solve_exact(Parameters(**PAPER), x0, n_cycles=200)
    assert default.status.value == "stopped" and len(default.events.t) == 0


def test_a_run_continued_past_the_accumulation_rests_at_a1_then_leaves_it_from_rest_in_the_zone():
    """b = 1.5 from rest at -1 m: the first impact at a1 (x = -cos t) at acos(0.1) s, v^2 = 1 - 0.01; it reverses
    the velocity to 0.5 sqrt(0.99) m/s, and each flight from a1 and back lasts 2 atan(u / 0.1) s with u halved at
    each rebound. From rest at a1 in (a1, a2) (centre 1): v^2 = 1.1^2 - 0.95^2 at a2; every later impact rebounds
    too, so from cycle 2 on v1^2 = 1.1^2 - 0.95^2 + 0.05^2 - 0.1^2 = 0.3."""
    run = solve_exact(Parameters(**{**PAPER, "b": 1.5}, past_accumulation="continue"), -1.0, n_cycles=4)
    t_acc = math.acos(0.1) + sum(2 * math.atan(0.5**n * 0.5 * math.sqrt(0.99) / 0.1) for n in range(200))
    assert run.status.value == "completed" and run.exit.t_accumulation == pytest.approx(t_acc, rel=1e-12)
    assert run.cycles.velocity_before_impact.tolist() == pytest.approx([math.sqrt(0.99)] + [math.sqrt(0.3)] * 3,
                                                                       rel=1e-12)
    assert run.events.v_before[1] == pytest.approx(math.sqrt(1.1**2 - 0.95**2), rel=1e-12)
    x, v, _ = run.sample([0.5 * (run.events.t[0] + t_acc)])
    assert (float(x[0]), float(v[0])) == (-0.1, 0.0)
    assert solve_exact(Parameters(**{**PAPER, "b": 1.5}), -1.0, n_cycles=4).status.value == "chattering"


@pytest.mark.parametrize("name, value, allowed", [("release_force", "eq6", "'after_impact', 'eq5'"),
                                                  ("past_accumulation", True, "'stop', 'continue'")])
def test_a_choice_that_is_not_one_of_its_settings_is_refused_naming_it(name, value, allowed):
    with pytest.raises(ParameterError, match=f"^{name} = {value!r} is invalid: {name} must be one of {allowed}$"):
        Parameters(**PAPER, **{name: value})


def test_a_solver_that_does_not_run_a_choice_refuses_it_before_any_work():
    with pytest.raises(ParameterError, match=r"^past_accumulation = 'continue' is invalid: past_accumulation must be "
                                             r"'stop' for this solver: only the event solvers \(solve_exact, "
                                             r"iter_cycles\) run the model's other choices$"):
        solve_cycles(Parameters(**PAPER, past_accumulation="continue"), -1.0, n_cycles=2)
