import mpmath
import numpy as np
import pytest

from escapement import Parameters, solve_exact
from escapement.highprecision import solve_high_precision

CASES = [
    (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 1.0),
    (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
    (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), 0.8),
]


def as_float(values):
    return np.array([float(v) for v in values])


@pytest.mark.parametrize("p, x0", CASES)
def test_exact_solver_against_50_digits(p, x0):
    """The float solver stays within 1e-14 (relative) of the 50-digit reference over 50 cycles."""
    hp = solve_high_precision(p, x0, n_cycles=50)
    run = solve_exact(p, x0, n_cycles=50)
    for name in ("impact_time", "velocity_before_impact", "amplitude"):
        ref = as_float(getattr(hp, name))
        got = getattr(run.cycles, name)
        assert np.max(np.abs(got - ref) / np.abs(ref)) < 1e-14, name
    ref = as_float(hp.period)
    assert np.max(np.abs(run.cycles.period - ref) / ref) < 5e-14  # a difference of two times of up to 300 s


def test_the_reference_is_converged_in_its_precision():
    p, x0 = CASES[0]
    a = solve_high_precision(p, x0, n_cycles=20, dps=50)
    b = solve_high_precision(p, x0, n_cycles=20, dps=80)
    with mpmath.workdps(80):
        assert max(abs(u - v) / abs(v) for u, v in zip(a.impact_time, b.impact_time)) < mpmath.mpf("1e-45")


def test_the_reference_refuses_to_leave_the_regime():
    with pytest.raises(ValueError, match="never reaches"):
        solve_high_precision(Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 0.05, n_cycles=2)
