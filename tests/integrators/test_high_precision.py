"""The 50-digit reference: closed forms in 50 digits, converged in its precision, and the float solver within 1e-14
of it."""

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


@pytest.mark.parametrize("p, x0", CASES)
def test_exact_solver_against_50_digits(p, x0):
    """The float solver stays within 1e-14 (relative) of the 50-digit reference over 30 cycles."""
    hp = solve_high_precision(p, x0, n_cycles=30).cycles
    run = solve_exact(p, x0, n_cycles=30)
    for name in ("impact_time", "velocity_before_impact", "largest_displacement"):
        ref = getattr(hp, name).astype(float)  # the nearest doubles
        assert np.max(np.abs(getattr(run.cycles, name) - ref) / np.abs(ref)) < 1e-14, name
    ref = hp.period.astype(float)
    assert np.max(np.abs(run.cycles.period - ref) / ref) < 5e-14  # a difference of two times of up to 300 s


def test_first_events_against_closed_forms_in_50_digits():
    """From rest at x0 = 1 (w = 1) the swing x = cos t meets a3 (the double nearest 0.1) moving left at t = acos(a3),
    v = -sqrt(1 - a3^2); the zone (a4, a3) then adds f (a3 - a4) and w^2 (a3^2 - a4^2) / 2 to v^2 / 2."""
    p, x0 = CASES[0]
    s = solve_high_precision(p, x0, n_cycles=3)
    assert s.status == Status.COMPLETED and s.method == "mpmath 50 digits" and s.trajectory is None
    for name in ("impact_time", "velocity_before_impact", "period", "largest_displacement"):
        column = getattr(s.cycles, name)
        assert column.dtype == object and len(column) == 3 and all(isinstance(v, mpmath.mpf) for v in column)
    with mpmath.workdps(50):
        a3, a4, b = mpmath.mpf(p.a3), mpmath.mpf(p.a4), mpmath.mpf(p.b)
        v3 = -mpmath.sqrt(1 - a3**2)
        v_a4 = -mpmath.sqrt(((1 - b) * v3) ** 2 + (a3**2 - a4**2) + 2 * (a3 - a4))
        assert list(s.events.kind[:2]) == [EventKind.IMPACT_A3, EventKind.ZONE_END_A4]
        got = (s.events.t[0], s.events.v_before[0], s.events.v_after[0], s.events.v_before[1])
        for value, expected in zip(got, (mpmath.acos(a3), v3, (1 - b) * v3, v_a4)):
            assert abs(value - expected) < mpmath.mpf("1e-45")


def test_the_reference_is_converged_in_its_precision():
    p, x0 = CASES[0]
    a = solve_high_precision(p, x0, n_cycles=10, dps=50).cycles
    b = solve_high_precision(p, x0, n_cycles=10, dps=80).cycles
    with mpmath.workdps(80):
        assert max(abs(u - v) / abs(v) for u, v in zip(a.impact_time, b.impact_time)) < mpmath.mpf("1e-45")


def test_leaving_the_regime_is_a_typed_outcome():
    p, _ = CASES[0]
    s = solve_high_precision(p, 0.05, n_cycles=2)
    assert s.status == Status.STOPPED and not s.success and "never passes the next impact position" in s.message
    assert s.exit.turning_point == pytest.approx(0.05, rel=1e-15) and s.exit.margin == pytest.approx(0.05, rel=1e-14)
    assert s.t_final == math.inf and len(s.cycles) == 0
    chatter = Parameters(M=1, K=1, F=1, b=1.5, a1=-0.1, a2=0.05)
    hp = solve_high_precision(chatter, 1.0, n_cycles=2)
    assert hp.status == Status.CHATTERING
    assert hp.exit.t_accumulation == pytest.approx(solve_exact(chatter, 1.0, n_cycles=2).exit.t_accumulation, rel=1e-14)
