"""Tolerance tests of the paper's claims (the claims register, the verdict's claims.yaml): a reproduced claim
within the tolerance the paper's precision allows; one that does not reproduce at its replicated value, against an
independent source (a closed form derived on paper, or 50 digits), the paper's value a strict xfail that says why
(one that starts passing fails the suite)."""

from __future__ import annotations

import functools
import math
from importlib.resources import files

import numpy as np
import pytest
import yaml
from expectations import paper_fails

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.paper import corrected as d
from escapement.paper import printed as pe
from escapement.studies.poincare import measure_cycle
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision

REGISTER = files("escapement.verdict") / "claims.yaml"  # the claims register, package data of the verdict
PRINTED_4_DECIMALS = 5e-5  # half a unit of the last digit of "6.2832 s"


def paper(F: float, a1=-0.1, a2=0.05, a3=None, a4=None, K: float = 1.0, b: float = 0.1) -> Parameters:
    return Parameters(M=1.0, K=K, F=F, b=b, a1=a1, a2=a2, a3=a3, a4=a4)


CASE = {"a": (paper(1.0), 1.0), "b": (paper(0.5), 3.0)}
K_VALUES = (0.1, 1.0, 10.0)


@functools.cache
def cycles(case: str):
    p, x0 = CASE[case]
    return p, solve_exact(p, x0, n_cycles=50, record_trajectory=False).cycles


def test_the_register_keeps_the_paper_precision_as_tolerance():
    """Widening a tolerance in the register fails here."""
    claims = {c["id"]: c for c in yaml.safe_load(REGISTER.read_text())["claims"]}
    for cid in ("fig3_period_a", "fig3_period_b", "fig3_periods_identical"):
        assert claims[cid]["tolerance"] == PRINTED_4_DECIMALS
    assert claims["eq21_multiplier"]["tolerance"] <= 1e-8 and claims["eq19_fixed_point_case_a"]["tolerance"] <= 1e-8
    assert claims["eq16_map"]["tolerance"] <= 1e-13


@pytest.mark.parametrize("case", ["a", "b"])
def test_eq19_fixed_point_and_eq21_multiplier_measured_from_the_return_map(case):
    p, c = cycles(case)
    assert c.velocity_before_impact[-1] == pytest.approx(pe.fixed_point_19(p), rel=1e-8)
    assert measure_cycle(p, CASE[case][1]).multiplier == pytest.approx(0.6561, abs=1e-8)


ASYMMETRIC = [(-0.1, 0.05, 0.2, -0.02), (-0.15, 0.0, 0.08, -0.1), (-0.1, 0.05, 0.3, 0.0)]


@pytest.mark.parametrize("F, positions, b", [
    *[(F, positions, 0.1) for F in (0.2, 1.0, 5.0) for positions in ((-0.1, 0.05), (-0.3, 0.2), (-0.05, 0.01))],
    *[(1.0, (-0.1, 0.05), b) for b in (0.05, 0.3, 0.6, 0.9, 1.0)],
    *[(F, positions, 0.1) for F in (0.5, 1.0, 3.0) for positions in ASYMMETRIC],  # Sec. 5 says otherwise (below)
])
def test_the_multiplier_is_1_minus_b_to_the_4_whatever_the_force_and_positions_for_b_up_to_1(F, positions, b):
    """Symmetric stability depends neither on force nor on position; the asymmetric too (replicated)."""
    m = measure_cycle(paper(F, *positions, b=b), 1.0)
    assert m.outcome == "completed" and m.multiplier == pytest.approx((1 - b) ** 4, abs=1e-8)


def test_both_fig3_motions_converge_case_a_to_greater_velocity_and_amplitude_inside_the_printed_axes():
    (_, a), (_, b) = cycles("a"), cycles("b")
    for c in (a, b):
        assert abs(c.velocity_before_impact[-1] / c.velocity_before_impact[-2] - 1) < 1e-8
    assert a.velocity_before_impact[-1] > b.velocity_before_impact[-1]
    assert a.largest_displacement[-1] > b.largest_displacement[-1]
    for c, velocity, amplitude in ((a, (0.95, 1.3), (1.0, 1.4)), (b, (0.5, 3.0), (0.5, 3.0))):
        for values, (low, high) in ((c.velocity_before_impact, velocity), (c.largest_displacement, amplitude)):
            assert low <= values.min() and values.max() <= high


@pytest.mark.parametrize("case, other_x0", [("a", 3.0), ("b", 1.0)])
def test_the_converged_period_does_not_depend_on_the_initial_condition(case, other_x0):
    p, x0 = CASE[case]
    t1, t2 = (solve_exact(p, x, n_cycles=300, record_trajectory=False).cycles.period[-1] for x in (x0, other_x0))
    assert t1 == pytest.approx(t2, abs=1e-10)


def test_fig4_impulse_and_dissipated_energy_follow_from_the_velocity_jump():
    p, x0 = CASE["b"]
    run = solve_exact(p, x0, t_end=87.0)
    impacts = (run.events.kind == 1) | (run.events.kind == 3)
    vb, va = run.events.v_before[impacts], run.events.v_after[impacts]
    assert np.allclose(p.M * (va - vb), -p.b * p.M * vb, rtol=1e-14)
    assert np.allclose(0.5 * p.M * (vb**2 - va**2), 0.5 * p.M * vb**2 * (2 * p.b - p.b**2), rtol=1e-12)


def test_fig5_smaller_spring_constant_greater_converged_amplitude():
    amplitudes = [solve_exact(paper(0.5, K=k), 1.0, n_cycles=60).cycles.largest_displacement[-1] for k in K_VALUES]
    assert amplitudes[0] > amplitudes[1] > amplitudes[2]
    for k, h in zip(K_VALUES, amplitudes):
        p = paper(0.5, K=k)
        assert h == pytest.approx(math.hypot(p.a2, d.cycle_velocities(d.fixed_point(p), p)["v2"] / p.omega), rel=1e-9)


# --- not reproduced: the replicated value (the paper's, as a strict xfail, at the end) --------------


@pytest.mark.parametrize("case", ["a", "b"])
def test_converged_period_replicated(case):
    """The simulated period equals the corrected Eq. (23) and the 50-digit reference; as a daily rate,
    86400 (T0/T - 1), case (a) runs about 171 s a day slow."""
    p, c = cycles(case)
    period = float(solve_high_precision(p, CASE[case][1], n_cycles=50).cycles.period[-1])
    assert c.period[-1] == pytest.approx(period, rel=1e-13)
    assert c.period[-1] == pytest.approx(d.period(pe.fixed_point_19(p), p), rel=1e-8)
    if case == "a":
        assert 86_400 * (2 * math.pi / period - 1) == pytest.approx(-171.4, abs=0.05)


def _contraction(case: str) -> np.ndarray:
    """(x1(k+1)^2 - x*^2) / (x1(k)^2 - x*^2), k = 1..9."""
    p, c = cycles(case)
    e, star = c.velocity_before_impact**2, d.fixed_point(p) ** 2
    return (e[1:10] - star) / (e[:9] - star)


def test_convergence_rate_replicated_is_the_multiplier_for_both_forces():
    """x1^2 - x*^2 shrinks by (1-b)^4 per cycle: Eq. (16) is linear in x1^2 (derived on paper)."""
    for case in ("a", "b"):
        assert _contraction(case) == pytest.approx(0.6561, rel=1e-9)


@pytest.mark.parametrize("b", [1.2, 1.5, 1.9])
def test_b_above_1_replicated_chatters(b):
    run = solve_exact(paper(1.0, b=b), 1.0, n_cycles=10)
    assert run.status == Status.CHATTERING and run.exit.t_accumulation > run.events.t[-1]


def _limit_cycle_max_speed(p: Parameters) -> float:
    """Largest speed on the symmetric limit cycle, derived on paper: in free flight the speed falls away from 0 and
    the left swing ends at a1 below its speed at a4; in the zone (a1, a2) it peaks at the zone's centre F/K, or at
    a2 if the centre lies beyond."""
    v1 = d.fixed_point(p)
    xm = min(max(p.zone_offset, p.a1), p.a2)
    return max(v1, math.sqrt(((1 - p.b) * v1) ** 2 + p.omega2 * (p.a1**2 - xm**2) + 2 * p.f * (xm - p.a1)))


def test_fig5_max_velocity_replicated_grows_with_K():
    speeds = [_limit_cycle_max_speed(paper(0.5, K=k)) for k in K_VALUES]
    assert speeds[0] < speeds[1] < speeds[2]
    for k, v in zip(K_VALUES, speeds):
        run = solve_exact(paper(0.5, K=k), 1.0, n_cycles=80)
        t0 = run.cycles.impact_time[-1]
        t = np.linspace(t0, t0 + run.cycles.period[-1], 20001)
        # The peak may sit at a kink (the end of the impulse at a2), where the event log holds it exactly.
        peak = max(np.nanmax(np.abs(run.sample(t)[1])), np.max(np.abs(run.events.v_before[run.events.t >= t0])))
        assert peak == pytest.approx(v, rel=1e-9)


def test_fig5_recovery_replicated():
    """Faster for small K relative to the cycle, slower in absolute time (closed form against sampling)."""
    rows = []
    for k in K_VALUES:
        p = paper(0.5, K=k)
        _, t_rec = d.velocity_recovery(d.fixed_point(p), p)
        run = solve_exact(p, 1.0, n_cycles=100)
        t0 = run.cycles.impact_time[-1]
        t, dt = np.linspace(t0, t0 + 2 * t_rec, 40001, retstep=True)
        sampled = t[np.argmax(run.sample(t)[1] >= run.cycles.velocity_before_impact[-1])] - t0
        assert t_rec <= sampled < t_rec + 2 * dt  # the first sample at or past the recovery
        rows.append((t_rec, t_rec / p.natural_period))
    assert rows[0][1] < rows[1][1] < rows[2][1] and rows[0][0] > rows[1][0] > rows[2][0]


@functools.cache
def _fig4_velocity() -> np.ndarray:
    p, x0 = CASE["b"]
    return solve_exact(p, x0, t_end=87.0).sample(np.linspace(80.0, 87.0, 7001))[1]


def test_fig4_velocity_swings_about_zero_replicated():
    v = _fig4_velocity()
    assert abs(v.max() + v.min()) < 0.01 * v.max()


def test_asymmetric_existence_replicated_follows_the_sign_of_C():
    """(a1..a4) = (-0.3, -0.25, 0.1, 0.05): C = -0.0152 + 0.181 F (derived on paper), F* = 0.0839779 N."""
    run = solve_exact(paper(0.05, -0.3, -0.25, 0.1, 0.05), -0.4, n_cycles=50, record_trajectory=False)
    e = [0.4**2 - 0.3**2]
    while e[-1] > 0:
        e.append(0.6561 * e[-1] - 0.0152 + 0.181 * 0.05)
    assert run.status == Status.STOPPED
    assert run.events.v_before[run.events.kind == 1] ** 2 == pytest.approx(e[:-1], rel=1e-12)  # every impact allowed
    converged = solve_exact(paper(0.1, -0.3, -0.25, 0.1, 0.05), -0.4, n_cycles=200, record_trajectory=False)
    assert converged.cycles.velocity_before_impact[-1] == pytest.approx(math.sqrt(0.0029 / 0.3439), rel=1e-10)


def test_grazing_release_has_two_continuations_50_digits():
    """a3 = 0.3, F = 0.1: from rest at -A the swing after the first impulse turns exactly at a3; A^2 = 0.01 + 0.05
    / 0.81, and a touch counted as an impact leads to v1^2 = 0.15 (derived on paper)."""
    p = paper(0.1, a3=0.3, a4=-0.05)
    a = math.sqrt(0.01 + 0.05 / 0.81)
    above = solve_high_precision(p, -a * (1 + 1e-12), n_cycles=2)
    assert float(above.events.v_before[above.events.kind == 1][1]) == pytest.approx(math.sqrt(0.15), rel=1e-9)
    assert solve_high_precision(p, -a * (1 - 1e-12), n_cycles=2).status == Status.STOPPED


def _period(case: str) -> float:
    return cycles(case)[1].period[-1]


@functools.cache
def _asymmetric_multipliers() -> list[float]:
    values = [measure_cycle(paper(F, -0.1, 0.05, 0.2, -0.02), 1.0).multiplier for F in (0.5, 3.0)]
    return values + [measure_cycle(paper(1.0, *positions), 1.0).multiplier for positions in ASYMMETRIC]


def _in_order(values: list[float], ascending: bool) -> bool:
    return all((a < b) == ascending and a != b for a, b in zip(values, values[1:]))


#: the paper's claims that the replication does not reproduce, each asserted as printed: why it fails, its name, and
#: the claim (each a strict xfail of its own)
PAPER = [
    ("Sec. 4 says 6.2832 s; the impacts and impulses change the period", "converged_period_a",
     lambda: _period("a") == pytest.approx(6.2832, abs=PRINTED_4_DECIMALS)),
    ("Sec. 4 says 6.2832 s; the impacts and impulses change the period", "converged_period_b",
     lambda: _period("b") == pytest.approx(6.2832, abs=PRINTED_4_DECIMALS)),
    ("Sec. 4 says both periods are identical; the period depends on the force", "periods_identical",
     lambda: _period("a") == pytest.approx(_period("b"), abs=PRINTED_4_DECIMALS)),
    *[("Fig. 3 period axes (6.283-6.2846 s, 6.2826-6.2834 s) cannot hold the periods", f"period_inside_axis_{case}",
       lambda case=case, axis=axis: axis[0] <= cycles(case)[1].period.min() and cycles(case)[1].period.max() <= axis[1])
      for case, axis in (("a", (6.283, 6.2846)), ("b", (6.2826, 6.2834)))],
    ("Sec. 4: the period is the natural one, 6.2832 s; the impacts delay each cycle", "period_is_the_natural_period",
     lambda: _period("a") == pytest.approx(2 * math.pi, abs=PRINTED_4_DECIMALS)),
    ("Sec. 4: converging speed dependent on the force; the rate is (1-b)^4 for all", "convergence_rate",
     lambda: abs(_contraction("a")[4] - _contraction("b")[4]) > 1e-6),
    *[("Sec. 3.4: stable for 0 < b < 2; for b > 1 the impact reverses the velocity", f"b_above_1_{b}",
       lambda b=b: measure_cycle(paper(1.0, b=b), 1.0).outcome == "completed") for b in (1.2, 1.5, 1.9)],
    ("Sec. 5: convergence dependent on force and position; mu2 = (1-b)^4 regardless", "asymmetric_multiplier",
     lambda: max(_asymmetric_multipliers()) - min(_asymmetric_multipliers()) > 1e-6),
    ("Sec. 4: greater K, smaller maximum velocity; it is the other way round", "fig5_max_velocity",
     lambda: _in_order([_limit_cycle_max_speed(paper(0.5, K=k)) for k in K_VALUES], ascending=False)),
    ("Sec. 4: small K recovers faster; in absolute time the stiff spring does", "fig5_recovery_absolute_time",
     lambda: _in_order([d.velocity_recovery(d.fixed_point(paper(0.5, K=k)), paper(0.5, K=k))[1] for k in K_VALUES],
                       ascending=True)),
    ("Fig. 4 axes span -0.1 to 0.9; the velocity swings between about -0.9 and 0.9", "fig4_velocity_axis",
     lambda: _fig4_velocity().min() >= -0.1 and _fig4_velocity().max() <= 0.9),
    ("Sec. 4: the initial amplitude has no effect; from |x0| <= |a1| nothing starts", "initial_amplitude_inside_a1",
     lambda: measure_cycle(paper(1.0), 0.0999).outcome == "completed"),
]


@pytest.mark.parametrize("claim", [pytest.param(claim, marks=paper_fails(why), id=name) for why, name, claim in PAPER])
def test_the_paper_s_claim(claim):
    assert claim()
