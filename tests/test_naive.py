import pytest

from escapement import Parameters, solve_exact
from escapement.naive import solve_naive

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)


def test_error_shrinks_about_linearly_with_the_step():
    exact = solve_exact(P, 1.0, n_cycles=10).cycles.impact_time[-1]
    errors = [abs(solve_naive(P, 1.0, 0.0, 10, h)[0][9] - exact) for h in (0.01, 0.001)]
    assert 3 < errors[0] / errors[1] < 30


def test_invalid_step_and_step_bound():
    with pytest.raises(ValueError, match="step"):
        solve_naive(P, 1.0, 0.0, 5, 0.0)
    with pytest.raises(ValueError, match="max_steps"):
        solve_naive(P, 1.0, 0.0, 5, 0.01, max_steps=10)
