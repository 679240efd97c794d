"""The corrected closed forms against the exact solution and against each other."""

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.paper import corrected as d
from escapement.solvers.exact import solve_exact

CASES = [
    (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 1.0),
    (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
    (Parameters(M=1.3, K=2.1, F=0.7, b=0.2, a1=-0.12, a2=0.03, a3=0.08, a4=-0.07), 1.0),
    (Parameters(M=1, K=10, F=0.5, b=0.1, a1=-0.1, a2=0.05), 1.0),
]


@pytest.mark.parametrize("p, x0", CASES)
def test_corrected_eq23_and_the_natural_period_plus_the_perturbations_give_every_simulated_period(p, x0):
    s = solve_exact(p, x0, n_cycles=60)
    for period in (d.period, d.period_from_perturbations):
        predicted = np.array([period(v, p) for v in s.cycles.velocity_before_impact])
        assert predicted == pytest.approx(s.cycles.period, rel=1e-13), period.__name__


@pytest.mark.parametrize("p, x0", CASES)
def test_fixed_point_and_linear_energy_map(p, x0):
    """The map is linear in v**2: v1(k)**2 - v*^2 = (1 - b)**(4(k-1)) (v1(1)**2 - v*^2)."""
    v = solve_exact(p, x0, n_cycles=80).cycles.velocity_before_impact
    star = d.fixed_point(p)
    assert v[-1] == pytest.approx(star, rel=1e-13)
    assert v**2 == pytest.approx(star**2 + (1 - p.b) ** (4 * np.arange(80)) * (v[0] ** 2 - star**2), rel=1e-12)


def test_map_constant_is_positive_and_symmetric_form_reduces():
    p = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
    assert d.map_constant(p) == pytest.approx(2 * (0.1**2 - 0.2 + 2) * 0.15 * 1.0, rel=1e-15)
