"""The runs of Figs. 3-5: what each keeps, how it is sampled, and the settings it refuses."""

import numpy as np
import pytest

from escapement.experiments.figures import phase, poincare, sample_times, shock
from escapement.model.parameters import ParameterError
from escapement.paper.printed import fixed_point_19
from escapement.solvers.exact import solve_exact


def test_the_poincare_run_keeps_no_trajectory(case_a):
    run = poincare(case_a, 1.0, 50)
    assert run.solution.trajectory is None and len(run.solution.cycles) == 50
    assert run.n_cycles == 50 and run.fixed_point_19 == fixed_point_19(case_a)


def test_the_poincare_amplitudes_by_definition(case_a):
    """From -1 m the free arc before the first impact has the Step-1 amplitude |x0| = 1 m (energy
    is conserved on it: derived on paper); Step 1 has one value more than there are cycles, Step 8
    is it shifted by one; the largest displacement is the right turning point."""
    step1 = poincare(case_a, -1.0, 5, "amplitude_h0")
    assert len(step1.amplitude) == 6 and step1.amplitude_definition == "amplitude_h0"
    assert step1.amplitude_cycle.tolist() == list(range(1, 7))
    assert float(step1.amplitude[0]) == pytest.approx(1.0, rel=1e-14)
    step8 = poincare(case_a, -1.0, 5, "amplitude_h4")
    np.testing.assert_array_equal(step8.amplitude, step1.amplitude[1:])
    largest = poincare(case_a, -1.0, 5, "largest_displacement")
    np.testing.assert_array_equal(largest.amplitude, solve_exact(case_a, -1.0, n_cycles=5).cycles.largest_displacement)
    with pytest.raises(ParameterError, match="amplitude"):
        poincare(case_a, -1.0, 5, "peak")


def test_the_shock_run_is_sampled_only_inside_its_windows(case_b):
    run = shock(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 100)
    assert run.t[0] == 80.0 and run.t[-1] == 87.0 and run.window == (80.0, 87.0)
    events = run.solution.events.t
    inside = np.count_nonzero((events > 80.0) & (events <= 87.0))
    assert inside >= 4
    assert len(run.t) == 701 + 2 * inside  # the grid, and both sides of each event


def test_the_phase_run_resolution_follows_the_natural_period(case_b):
    run = phase(case_b, 3.0, 5, 100)
    assert run.t[1] - run.t[0] <= case_b.natural_period / 100
    assert len(run.solution.cycles) == 5 and run.t[-1] == run.solution.t_final


def test_a_stopped_motion_is_an_outcome_not_an_error(case_a):
    run = phase(case_a, 0.05, 5, 50)
    assert run.solution.status.value == "stopped" and len(run.solution.cycles) == 0
    assert np.all(np.diff(run.t) > 0)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(velocity_window=(87.0, 80.0)), "velocity_window"),
        (dict(acceleration_window=(-1.0, 2.0)), "acceleration_window"),
        (dict(velocity_window="80-87"), "velocity_window"),
        (dict(samples_per_second=0), "samples_per_second"),
    ],
)
def test_the_shock_run_refuses_bad_settings(case_b, kwargs, name):
    args = dict(velocity_window=(80.0, 87.0), acceleration_window=(81.0, 85.0), samples_per_second=10)
    args.update(kwargs)
    with pytest.raises(ParameterError, match=f"^{name} = "):
        shock(case_b, 3.0, **args)


@pytest.mark.parametrize("n_cycles", [0, 2.5, True])
def test_the_cycle_counts_must_be_positive_integers(case_a, n_cycles):
    for run in (lambda: poincare(case_a, 1.0, n_cycles), lambda: phase(case_a, 1.0, n_cycles, 20)):
        with pytest.raises(ParameterError, match="^n_cycles = "):
            run()


def test_sample_times_add_a_sample_on_each_side_of_each_jump():
    below = np.nextafter
    t = sample_times(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.5, 2.0, 0.0, 5.0]))
    # 1.5: both sides added; 2.0 on the grid: the sample below it added; 0.0 at the start: nothing below it;
    # 5.0 outside the grid: nothing
    assert t.tolist() == [0.0, 1.0, below(1.5, 0.0), 1.5, below(2.0, 0.0), 2.0, 3.0]
    assert np.all(np.diff(t) > 0)


def test_sample_times_keep_the_grid_without_jumps():
    grid = np.linspace(80.0, 87.0, 8)
    assert sample_times(grid, np.array([])).tolist() == grid.tolist()
