import math

import mpmath
import numpy as np
import pytest

from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision

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
    hp = solve_high_precision(p, x0, n_cycles=50).cycles
    run = solve_exact(p, x0, n_cycles=50)
    for name in ("impact_time", "velocity_before_impact", "largest_displacement"):
        ref = as_float(getattr(hp, name))
        got = getattr(run.cycles, name)
        assert np.max(np.abs(got - ref) / np.abs(ref)) < 1e-14, name
    ref = as_float(hp.period)
    assert np.max(np.abs(run.cycles.period - ref) / ref) < 5e-14  # a difference of two times of up to 300 s


def test_cycles_hold_mpmath_numbers():
    p, x0 = CASES[0]
    s = solve_high_precision(p, x0, n_cycles=3)
    assert s.status == Status.COMPLETED and s.success
    assert s.method == "mpmath 50 digits"
    for name in ("impact_time", "velocity_before_impact", "period", "largest_displacement"):
        column = getattr(s.cycles, name)
        assert column.dtype == object and len(column) == 3
        assert all(isinstance(v, mpmath.mpf) for v in column)
    assert s.trajectory is None


def test_first_events_against_closed_forms_in_50_digits():
    # From rest at x0 = 1 (w = 1) the swing x = cos t meets a3 moving left at t = acos(a3), with
    # v = -sqrt(1 - a3^2); the zone (a4, a3) then adds f (a3 - a4) and the spring w^2 (a3^2 - a4^2) / 2 to v^2 / 2.
    # a3 and a4 are the doubles nearest 0.1 and -0.05, taken exactly.
    p, x0 = CASES[0]
    s = solve_high_precision(p, x0, n_cycles=1, dps=50)
    with mpmath.workdps(50):
        a3, a4, b = mpmath.mpf(p.a3), mpmath.mpf(p.a4), mpmath.mpf(p.b)
        v3 = -mpmath.sqrt(1 - a3**2)
        v_a4 = -mpmath.sqrt(((1 - b) * v3) ** 2 + (a3**2 - a4**2) + 2 * (a3 - a4))
        tol = mpmath.mpf("1e-45")
        assert list(s.events.kind[:2]) == [EventKind.IMPACT_A3, EventKind.ZONE_END_A4]
        assert abs(s.events.t[0] - mpmath.acos(a3)) < tol
        assert abs(s.events.v_before[0] - v3) < tol
        assert abs(s.events.v_after[0] - (1 - b) * v3) < tol
        assert abs(s.events.v_before[1] - v_a4) < tol


def test_the_reference_is_converged_in_its_precision():
    p, x0 = CASES[0]
    a = solve_high_precision(p, x0, n_cycles=20, dps=50).cycles
    b = solve_high_precision(p, x0, n_cycles=20, dps=80).cycles
    with mpmath.workdps(80):
        assert max(abs(u - v) / abs(v) for u, v in zip(a.impact_time, b.impact_time)) < mpmath.mpf("1e-45")


def test_leaving_the_regime_is_a_typed_outcome():
    p, _ = CASES[0]
    s = solve_high_precision(p, 0.05, n_cycles=2)
    assert s.status == Status.STOPPED and not s.success
    assert "never passes the next impact position" in s.message
    assert s.exit.turning_point == pytest.approx(0.05, rel=1e-15)
    assert s.exit.margin == pytest.approx(0.05, rel=1e-14)
    assert s.t_final == math.inf and len(s.cycles) == 0
    chatter = solve_high_precision(Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, n_cycles=2)
    exact = solve_exact(Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05), 1.0, n_cycles=2)
    assert chatter.status == Status.CHATTERING
    assert chatter.exit.t_accumulation == pytest.approx(exact.exit.t_accumulation, rel=1e-14)
