"""Each of the paper's closed forms (Sec. 3.3-3.4), as printed and as corrected, against the exact solution: an
equation that does not hold is asserted at its replicated value, and the paper's form kept as a strict xfail that says
why."""

import math

import mpmath
import numpy as np
import pytest
from expectations import paper_fails

from escapement.model.events import EventKind
from escapement.model.parameters import Parameters
from escapement.paper import corrected as d
from escapement.paper import printed as pe
from escapement.solvers.exact import solve_exact

CASES = {
    "fig3a": (Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05), 1.0),
    "fig3b": (Parameters(M=1, K=1, F=0.5, b=0.1, a1=-0.1, a2=0.05), 3.0),
    "asym": (Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04), 0.8),
    "stiff": (Parameters(M=1, K=10, F=0.5, b=0.1, a1=-0.1, a2=0.05), 1.0),
    "asym_b": (Parameters(M=1.3, K=2.1, F=0.7, b=0.2, a1=-0.12, a2=0.03, a3=0.08, a4=-0.07), 1.0),
}
SYMMETRIC = ["fig3a", "fig3b"]
PRINTED = ["fig3a", "fig3b", "asym"]


def converged(name, n_cycles=200):
    p, x0 = CASES[name]
    return p, solve_exact(p, x0, n_cycles=n_cycles)


def step_durations(solution, cycle):  # the simulated durations inside cycle ``cycle`` (0-based), from the event log
    ev = solution.events
    start = ev.of_kind(EventKind.IMPACT_A1)[cycle]
    t = ev.t[start : start + 5]
    assert list(ev.kind[start : start + 5]) == [1, 2, 3, 4, 1]
    return {"zone_right": t[1] - t[0], "a2_to_a3": t[2] - t[1], "zone_left": t[3] - t[2], "a4_to_a1": t[4] - t[3]}


@pytest.mark.parametrize("name", PRINTED)
def test_eq16_is_the_composition_of_the_energy_steps_and_eq14_corrected_gives_the_velocity_at_a4(name):
    p, s = converged(name, 20)
    for v in (0.7, 1.0, 2.5):
        assert pe.poincare_map_16(v, p) == pytest.approx(d.cycle_velocities(v, p)["v1_next"], rel=1e-14)
    ev = s.events
    for i in ev.of_kind(EventKind.IMPACT_A1)[:-1]:
        assert d.cycle_velocities(ev.v_before[i], p)["v5"] == pytest.approx(ev.v_before[i + 3], rel=1e-13)


@pytest.mark.parametrize("name", SYMMETRIC)
def test_eqs_17_to_21_in_the_symmetric_case(name):
    """(17) is (16) there, (19) the converged velocity, (20) the derivative of (17), (21) (20) at the fixed point."""
    p, s = converged(name)
    for v in (0.5, 1.2, 3.0):
        assert pe.poincare_map_17(v, p) == pytest.approx(pe.poincare_map_16(v, p), rel=1e-15)
    assert s.cycles.velocity_before_impact[-1] == pytest.approx(pe.fixed_point_19(p), rel=1e-13)
    v, h = 1.1, 1e-6
    numeric = (pe.poincare_map_17(v + h, p) - pe.poincare_map_17(v - h, p)) / (2 * h)
    assert pe.map_derivative_20(v, p) == pytest.approx(numeric, rel=1e-8)
    assert pe.map_derivative_20(pe.fixed_point_19(p), p) == pytest.approx(pe.multiplier_21(p), rel=1e-14)
    assert pe.multiplier_21(p) == pytest.approx(0.6561, rel=1e-15)


@paper_fails("Eq. (14) as printed subtracts the work 2(a3 - a4) f that the force adds")
@pytest.mark.parametrize("name", PRINTED)
def test_eq14_as_printed(name):
    p, s = converged(name, 3)
    ev = s.events
    i = ev.of_kind(EventKind.IMPACT_A1)[0]
    assert pe.step_velocities(ev.v_before[i], p)["v5"] == pytest.approx(ev.v_before[i + 3], rel=1e-6)


@pytest.mark.parametrize("name", PRINTED)
def test_eqs_22a_to_22d_and_22e_corrected_give_the_simulated_step_times(name):
    p, s = converged(name, 10)
    w, c = p.omega, p.zone_offset
    for k in range(9):
        v = s.cycles.velocity_before_impact[k]
        times, sim = pe.step_times_22(v, p, left_amplitude=1.0), step_durations(s, k)
        assert times["22b"] == pytest.approx(sim["zone_right"], rel=1e-12)
        assert times["22c"] + times["22d"] == pytest.approx(sim["a2_to_a3"], rel=1e-12)
        vel = d.cycle_velocities(v, p)
        h3 = math.hypot(p.a3 + c, vel["v4p"] / w)
        corrected = (math.atan(vel["v4p"] / (w * (p.a3 + c))) + math.acos((p.a4 + c) / h3)) / w
        assert corrected == pytest.approx(sim["zone_left"], rel=1e-12)
        if k:  # (22a): from the left turning point, the swing's amplitude by energy, to a1
            h0 = math.hypot(p.a1, v / p.omega)
            a4_to_turning = math.acos(-p.a4 / h0) / p.omega
            previous = step_durations(s, k - 1)["a4_to_a1"]
            assert pe.step_times_22(v, p, h0)["22a"] == pytest.approx(previous - a4_to_turning, rel=1e-12)


@paper_fails("Eq. (22e) as printed subtracts the arccos term and gives a negative time")
@pytest.mark.parametrize("name", PRINTED)
def test_eq22e_as_printed(name):
    p, s = converged(name, 3)
    times = pe.step_times_22(s.cycles.velocity_before_impact[0], p, 1.0)
    assert times["22e"] == pytest.approx(step_durations(s, 0)["zone_left"], rel=1e-6)


@paper_fails(
    "Eq. (23) as printed: its last two terms need -a4 and -a1 (acos(a4/h) + acos(a1/h) is 2 pi minus the right phase)"
)
@pytest.mark.parametrize("name", PRINTED)
def test_eq23_as_printed(name):
    p, s = converged(name, 50)
    assert pe.period_23(s.cycles.velocity_before_impact[-1], p) == pytest.approx(s.cycles.period[-1], rel=1e-6)


def eq24(v, p):  # Eq. (24), first form, at v before the impact at a1 and (1 - b) v after
    return pe.phase_jump_24(v, (1 - p.b) * v, pe.symbols_of(p))


@pytest.mark.parametrize("name", PRINTED)
def test_eq24_first_form_is_the_phase_jump_of_the_impact_and_its_second_form_with_the_velocity_before(name):
    p, _ = CASES[name]
    w, b, a1 = p.omega, p.b, p.a1
    for v in (0.5, 1.25, 2.0):
        assert eq24(v, p) == pytest.approx(d.impact_phase_jump(a1, v, p), rel=1e-13)
        # the second form, -(1/w) atan(a1 w b v / (a1^2 w^2 + (1 - b) v^2)), with v the velocity before the impact
        assert -math.atan(a1 * w * b * v / (a1**2 * w**2 + (1 - b) * v**2)) / w == pytest.approx(eq24(v, p), rel=1e-13)


@paper_fails("Eq. (24) second form as printed uses the velocity after the impact")
@pytest.mark.parametrize("name", PRINTED)
def test_eq24_second_form_as_printed(name):
    p, _ = CASES[name]
    v = 1.25
    assert pe.phase_jump_24_closed((1 - p.b) * v, p.b, pe.symbols_of(p)) == pytest.approx(eq24(v, p), rel=1e-6)


@paper_fails(
    "Eq. (25) as printed takes atan of velocity over position; the phase needs position over velocity"
)
@pytest.mark.parametrize("name", SYMMETRIC)
def test_eq24_plus_25_as_printed_give_the_limit_cycle_period(name):
    p, s = converged(name)
    v = pe.fixed_point_19(p)
    predicted = p.natural_period + 2 * (eq24(v, p) + pe.zone_change_25((1 - p.b) * v, pe.symbols_of(p)))
    assert predicted == pytest.approx(s.cycles.period[-1], rel=1e-6)


def test_eq21_multiplier_is_correctly_rounded():
    """(1 - b)**4 is the float nearest the exact fourth power of the float 1 - b: in 300-bit arithmetic the power
    is exact (4 x 53 bits), and mpmath rounds it to the nearest float."""
    with mpmath.workprec(300):
        for b in [*np.linspace(0.0, 2.0, 200), 1e-12, 0.1, 0.3, 1.999999, 2.0 - 2**-40]:
            assert float(mpmath.mpf(1.0 - float(b)) ** 4) == pe.multiplier_21_of(float(b)), b


@pytest.mark.parametrize("name", list(CASES))
def test_corrected_eq23_and_the_natural_period_plus_the_perturbations_give_every_simulated_period(name):
    p, s = converged(name, 80)
    for period in (d.period, d.period_from_perturbations):
        predicted = np.array([period(v, p) for v in s.cycles.velocity_before_impact])
        assert predicted == pytest.approx(s.cycles.period, rel=1e-13), period.__name__
    # the map is linear in v**2: v1(k)**2 - v*^2 = (1 - b)**(4(k-1)) (v1(1)**2 - v*^2), around Eq. (16)'s fixed point
    v, star = s.cycles.velocity_before_impact, d.fixed_point(p)
    assert v[-1] == pytest.approx(star, rel=1e-13)
    assert v**2 == pytest.approx(star**2 + (1 - p.b) ** (4 * np.arange(80)) * (v[0] ** 2 - star**2), rel=1e-12)
    if name == "fig3a":  # C of the map v1(k+1)**2 = (1 - b)**4 v1(k)**2 + C, symmetric: 2 (b^2 - 2b + 2)(a2 - a1) f
        assert d.map_constant(p) == pytest.approx(2 * (0.1**2 - 0.2 + 2) * 0.15 * 1.0, rel=1e-15)
