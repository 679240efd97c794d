"""The stress cases, each run once and checked against an answer derived here independently of the solver (its outcome,
and its numbers against closed forms or sums), and its row of the summary table."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from escapement.model import automaton
from escapement.model.parameters import ParameterError, Parameters
from escapement.model.status import Status
from escapement.studies.poincare import stability_grid
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.studies import stress
from escapement.studies.stress import CASES, StressCase, row, run_all


def paper(**changes) -> Parameters:
    return Parameters(**{**dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), **changes})


def symmetric_velocities(p: Parameters, x0: float, n: int) -> np.ndarray:
    """Velocity before each impact at a1 from release at rest at x0 > a3, symmetric geometry. Energy per unit mass:
    an impact multiplies v^2 by r^2 = (1 - b)^2, a zone adds 2 f (a2 - a1), the spring's terms cancel (a3 = -a1,
    a4 = -a2); the first impact (at a3) has v^2 = w^2 (x0^2 - a3^2), so v1(1)^2 = r^2 w^2 (x0^2 - a1^2) +
    2 f (a2 - a1), then Eq. (17): v1(k+1)^2 = r^4 v1(k)^2 + 2 (b^2 - 2b + 2)(a2 - a1) f."""
    r2 = (1 - p.b) ** 2
    zone = 2 * p.f * (p.a2 - p.a1)
    v2 = [r2 * p.omega2 * (x0 * x0 - p.a1 * p.a1) + zone]
    for _ in range(n - 1):
        v2.append(r2 * r2 * v2[-1] + zone * (r2 + 1))
    return np.sqrt(v2)


def zeno_time(omega: float, distance: float, speed: float, ratio: float) -> float:
    """2/w sum_n atan(y r^n), y = speed / (w d): summed term by term (math.fsum) while y r^n > 1e-9, and the
    rest as sum y r^n - (y r^n)^3 / 3, whose neglected part is below 1e-45 / (1 - r^5)."""
    y = speed / (omega * distance)
    terms = []
    while y > 1e-9:
        terms.append(math.atan(y))
        y *= ratio
    terms += [y / (1 - ratio), -(y**3) / (3 * (1 - ratio**3))]
    return 2 * math.fsum(terms) / omega


def check_stop_below_a1():  # each case's independent check, check_<name>: the outcome the closed form predicts
    # x = 0.05 cos t never reaches |a1| = a3 = 0.1 m
    s = solve_exact(paper(), 0.05, n_cycles=10)
    t = np.array([1.0, 37.0, 100.0])
    x, v, _ = s.sample(t)
    assert len(s.events) == 0 and s.exit.margin == pytest.approx(0.05, rel=1e-14)
    assert (x, v) == (pytest.approx(0.05 * np.cos(t), abs=1e-15), pytest.approx(-0.05 * np.sin(t), abs=1e-15))
    return "stopped"


def check_stop_energy_runs_out():
    # F = 0: the radius R of the free swing only shrinks, R^2 -> a^2 + r^2 (R^2 - a^2) at an impact at a;
    # impacts alternate a3 = 0.3 m and a1 = -0.1 m, each followed by its zone end, until R <= a3 when a3 is awaited
    p = paper(F=0.0, a3=0.3, a4=0.0)
    s = solve_exact(p, 1.0, n_cycles=100)
    r2, radius_sq, events, awaited = 0.81, 1.0, 0, 0.3
    while radius_sq > awaited**2:
        radius_sq = awaited**2 + r2 * (radius_sq - awaited**2)
        events += 2
        awaited = 0.1 if awaited == 0.3 else 0.3
    assert awaited == 0.3 and len(s.events) == events  # it stops waiting for a3, after the impulse at a1
    assert s.exit.turning_point == pytest.approx(math.sqrt(radius_sq), rel=1e-13)
    assert s.exit.margin == pytest.approx(0.3 - math.sqrt(radius_sq), rel=1e-12)
    return "stopped"


def check_turned_back_in_zone():
    # w = 10, F/K = 1e-4: from rest at 0.021 m the impact at a3 = 0.02 m comes at t = acos(0.02/0.021)/w with
    # v = -w sqrt(0.021^2 - 0.02^2); the zone motion about c = -F/K then turns at c - R, far short of a4 = -0.1 m,
    # after the clockwise phase from its start to the bottom of the circle, atan2(w0, u0) + pi
    p = Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1)
    s = solve_exact(p, 0.021, n_cycles=3)
    w, c = 10.0, -1e-4
    t_hit = math.acos(0.02 / 0.021) / w
    w0 = 0.9 * -math.sqrt(0.021**2 - 0.02**2)  # v / w after the impact
    u0 = 0.02 - c
    assert s.exit.turning_point == pytest.approx(c - math.hypot(u0, w0), rel=1e-14)
    assert s.t_final == pytest.approx(t_hit + (math.atan2(w0, u0) + math.pi) / w, rel=1e-13)
    return "turned_back_in_zone"


def check_stiff_spring_paper_geometry():
    p = paper(K=1000.0, F=0.5)
    s = solve_exact(p, 1.0, n_cycles=50)
    assert s.cycles.velocity_before_impact == pytest.approx(symmetric_velocities(p, 1.0, 50), rel=1e-12)
    return "completed"


def check_b_small():
    # Eqs. (19), (21) hold (derived from the energy map): v* = sqrt(2 f (a2 - a1) / (2b - b^2)), mu = (1 - b)^4
    b = 1e-4
    g = stability_grid(dict(M=1.0, K=1.0, a1=-0.1, a2=0.05), np.array([b]), np.array([1.0]))
    assert (g["multiplier"][0], g["fixed_point"][0]) == (pytest.approx((1 - b) ** 4, abs=1e-8),
                                                         pytest.approx(math.sqrt(0.3 / (2 * b - b * b)), rel=1e-9))
    return "completed"


def check_b_one():
    # r = 0: every impact stops the mass, and every cycle starts with v^2 = 2 f (a2 - a1) = 0.3
    s = solve_exact(paper(b=1.0), 1.0, n_cycles=5)
    assert np.all(s.events.v_after[np.isin(s.events.kind, [1, 3])] == 0.0)
    assert s.cycles.velocity_before_impact == pytest.approx(np.full(5, math.sqrt(0.3)), rel=1e-14)
    return "completed"


def _check_chattering(b, rebounds, rel):
    # from rest at 1 m the first impact is at a3 = 0.1 m at t = acos(0.1), v = -sqrt(0.99); it rebounds
    # to the right with |1 - b| of that speed, and the spring (centre 0) drives it back to a3
    s = solve_exact(paper(b=b), 1.0, n_cycles=5)
    assert len(s.events) == 1 and s.events.kind[0] == 3
    t_hit = math.acos(0.1)
    expected = t_hit + rebounds(1.0, 0.1, abs(1 - b) * math.sqrt(0.99), abs(1 - b))
    assert s.exit.t_accumulation == pytest.approx(expected, rel=rel)
    return "chattering"


def zeno_time_near_one(omega: float, distance: float, speed: float, ratio: float) -> float:
    """Euler-Maclaurin on paper for r = e^-lam close to 1: sum_n atan(y e^(-lam n)) = Ti2(y)/lam + atan(y)/2
    + lam y / (12 (1 + y^2)) + O(lam^3), with Ti2(y) = Im Li2(i y) (in 30 digits)."""
    with mpmath.workdps(30):
        y = mpmath.mpf(speed) / (mpmath.mpf(omega) * mpmath.mpf(distance))
        lam = -mpmath.log(mpmath.mpf(ratio))
        total = mpmath.im(mpmath.polylog(2, 1j * y)) / lam + mpmath.atan(y) / 2 + lam * y / (12 * (1 + y * y))
        return float(2 * total / mpmath.mpf(omega))


#: the chattering cases: b, the sum of the flights, its tolerance
CHATTERING = {"b_between_one_and_two": (1.5, zeno_time, 1e-12), "b_near_two": (1.999, zeno_time, 1e-12),
              "b_two_minus_1e9": (2.0 - 1e-9, zeno_time_near_one, 1e-13),
              "b_two_minus_1e12": (2.0 - 1e-12, zeno_time_near_one, 1e-13)}


def _refused(run, name, row=None):  # an input refused before any work: the check is the error itself, by its name
    with pytest.raises(ParameterError) as caught:
        run()
    assert (caught.value.name, caught.value.row) == (name, row)
    return "refused"


def check_float_range_state():
    with np.errstate(over="ignore"):
        assert np.isinf(np.float64(0.5) * np.float64(1e200) ** 2)  # the energy the state would have
    return _refused(lambda: solve_exact(paper(), 1e200, n_cycles=5), "x0")


def check_float_range_subnormal_mass():
    with np.errstate(over="ignore", divide="ignore"):
        assert np.isinf(np.float64(1.0) / np.float64(1e-320))  # K/M
    return _refused(lambda: paper(M=1e-320), "M")


def check_ensemble_bad_row():
    return _refused(lambda: solve_ensemble(1.0, 1.0, 1.0, [0.1, 0.2, True], -0.1, 0.05, n_cycles=5), "b", row=2)


def check_memory_budget():
    from escapement.model.limits import MemoryBudgetError

    # What the result must hold at the least, counted here: 4 events a cycle, each a time, a position, the velocities
    # before and after (8 bytes each) and a kind (1 byte at least); a row of the cycle table, 4 * 8 bytes: 164 bytes a
    # cycle, 1.64e11 bytes for 1e9 cycles, 82 times the 2 GB budget (2e9 bytes, a quarter of a laptop's 8 GB).
    with pytest.raises(MemoryBudgetError) as caught:
        solve_exact(paper(), 1.0, n_cycles=10**9, record_trajectory=False)
    assert (caught.value.name, caught.value.value, caught.value.budget) == ("n_cycles", 10**9, 2_000_000_000)
    assert caught.value.estimate >= 10**9 * (4 * (4 * 8 + 1) + 4 * 8)
    return "refused"


def check_counts_refused():
    return [_refused(lambda: solve_exact(paper(), 1.0, n_cycles=n), "n_cycles") for n in (0, -1, 1.5, True)][0]


def check_graze_on_impact_position():
    s = solve_exact(paper(), 0.1, n_cycles=5)
    assert len(s.events) == 0 and s.exit.margin == 0.0 and s.exit.turning_point == 0.1
    return "stopped"


def check_graze_just_inside():
    x0 = math.nextafter(0.1, 0.0)
    s = solve_exact(paper(), x0, n_cycles=5)
    assert len(s.events) == 0 and s.exit.margin == 0.1 - x0 > 0  # the difference is exact (Sterbenz)
    return "stopped"


def check_graze_just_beyond():
    x0 = math.nextafter(0.1, 1.0)
    s = solve_exact(paper(), x0, n_cycles=5)
    # first impact at a3 with v^2 = (x0 - a3)(x0 + a3), about 2.8e-18; then v1^2 = 0.3 + 0.81 v^2
    assert abs(s.events.v_before[0]) == pytest.approx(math.sqrt((x0 - 0.1) * (x0 + 0.1)), rel=1e-6)
    assert s.cycles.velocity_before_impact == pytest.approx(symmetric_velocities(paper(), x0, 5), rel=1e-12)
    return "completed"


def check_graze_zone_end():
    # x0 chosen (in 50 digits) so that the zone motion from a3 turns exactly at a4 = -0.1 m. In the limit the
    # mass reaches a4 at rest; from there the free swing (radius 0.1 m, w = 10) meets a1 = -0.02 m moving
    # right with v / w = sqrt(0.1^2 - 0.02^2), and the zone motion about F/K = 1e-4 turns at
    # 1e-4 + |(a1 - 1e-4, 0.9 v / w)| < a2 = 0.1 m: turned back in the zone (a1, a2).
    p = Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1)
    with mpmath.workdps(50):
        c = mpmath.mpf(p.F) / mpmath.mpf(p.K)
        radius = -mpmath.mpf(p.a4) - c
        x0 = float(mpmath.sqrt((radius**2 - (mpmath.mpf(p.a3) + c) ** 2) / mpmath.mpf(0.81) + mpmath.mpf(p.a3) ** 2))
    s = solve_exact(p, x0, n_cycles=3)
    assert s.status == Status.TURNED_BACK_IN_ZONE
    if s.events.kind[-1] == 1:  # passed a4 at the grazing speed, then the predicted turn in (a1, a2)
        assert list(s.events.kind) == [3, 4, 1]
        assert abs(s.events.v_before[1]) < 1e-6
        turning = 1e-4 + math.hypot(-0.02 - 1e-4, 0.9 * math.sqrt(0.1**2 - 0.02**2))
        assert s.exit.turning_point == pytest.approx(turning, rel=1e-9)
    else:  # turned back at the grazing point itself
        assert list(s.events.kind) == [3]
        assert s.exit.turning_point == pytest.approx(-0.1, abs=1e-15)
    return "turned_back_in_zone"


def check_reference_grazes_zone_end():
    # closed form: the zone arc from a3 turns at c - R = a4 - 1e-9 m, beyond a4; the exact solver (its
    # own closed forms, tested on such arcs in tests/solvers/test_grazing.py) crosses a4
    p = Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.02, a2=0.05, a3=0.02, a4=-0.05)
    with mpmath.workdps(50):
        c = -mpmath.mpf("0.01")
        radius = c - (mpmath.mpf(p.a4) - mpmath.mpf("1e-9"))
        x0 = mpmath.sqrt(mpmath.mpf(p.a3) ** 2 + (radius**2 - (mpmath.mpf(p.a3) - c) ** 2) / mpmath.mpf("0.81"))
        speed_at_a4 = mpmath.sqrt(radius**2 - (mpmath.mpf(p.a4) - c) ** 2)  # w = 1
    s = solve_exact(p, float(x0), n_cycles=3)
    assert list(s.events.kind[:2]) == [3, 4]
    assert abs(s.events.v_before[1]) == pytest.approx(float(speed_at_a4), rel=1e-3)
    return s.status.value


def check_scales():
    for K in (1e-3, 1.0, 1e3):
        for M in (1e-3, 1.0, 1e3):
            for F in (0.0, 1.0, 1e3):
                p = Parameters(M=M, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)
                s = solve_exact(p, 1.0, n_cycles=20, record_trajectory=False)
                assert s.status == Status.COMPLETED, (M, K, F)
                assert s.cycles.velocity_before_impact == pytest.approx(symmetric_velocities(p, 1.0, 20), rel=1e-12)
    return "completed"


def check_near_origin():
    p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-1e-9, a2=1e-9)
    s = solve_exact(p, 1.0, n_cycles=20, record_trajectory=False)
    assert s.cycles.velocity_before_impact == pytest.approx(symmetric_velocities(p, 1.0, 20), rel=1e-13)
    # the zones are 2e-9 m wide: the period is the natural one, less the impacts' phase jumps, to O(1e-9) s
    assert s.cycles.period == pytest.approx(np.full(20, 2 * math.pi), abs=1e-7)
    return "completed"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_stress_case_against_its_independent_answer(case):
    chattering = CHATTERING.get(case.name)  # the case's own answer, derived here
    expected_outcome = _check_chattering(*chattering) if chattering else globals()[f"check_{case.name}"]()
    result = case.run()
    assert result.outcome == expected_outcome and result.passed, f"{case.name}: {result.detail}"
    assert row(case, result) == {"case": case.name, "regime": case.regime, "outcome": expected_outcome,
                                 "check": result.check, "passed": "yes", "detail": result.detail}


def test_the_cases_that_test_the_impact_law_fail_under_a_wrong_one_and_their_rows_say_no(monkeypatch):
    monkeypatch.setattr(automaton, "impact_factor", lambda b: 1.0 - 0.5 * b)  # v+ = (1 - b/2) v-
    names = ("b_one", "stiff_spring_paper_geometry", "b_between_one_and_two", "stop_below_a1")
    monkeypatch.setattr(stress, "CASES", [c for c in CASES if c.name in names])
    rows = {r["case"]: r for r in run_all()}
    assert list(rows) == [c.name for c in CASES if c.name in names]
    for name in names[:3]:
        assert (rows[name]["outcome"], rows[name]["passed"]) == ("completed", "no")
    assert rows["stop_below_a1"]["passed"] == "yes"  # no impact: the law does not enter


@pytest.mark.parametrize("name", ["stop_below_a1", "graze_on_impact_position", "graze_just_inside",
                                  "graze_just_beyond", "graze_zone_end", "near_origin"])
def test_a_case_fails_when_the_solver_runs_from_a_release_off_by_a_part_in_1e9(monkeypatch, name):
    """These cases check the run against closed forms of their own release: a solver that starts 1e-9 (relative)
    away must fail them (x(100) of the free swing moves by 4e-11 m, a graze becomes an impact or none, ...)."""
    def off(params, x0, *args, **kwargs):
        return solve_exact(params, x0 * (1 + 1e-9), *args, **kwargs)

    monkeypatch.setattr(stress, "solve_exact", off)
    (case,) = [c for c in CASES if c.name == name]
    assert not case.run().passed


def test_a_case_that_crashes_fails_loudly_instead_of_writing_a_row(monkeypatch):
    # a case whose run the solver refuses (no cycles asked for): the ParameterError is a bug of the case, not a result
    crashing = StressCase("zero_cycles", "a case whose run raises", lambda: solve_exact(paper(), 1.0, n_cycles=0))
    monkeypatch.setattr(stress, "CASES", [CASES[0], crashing])
    with pytest.raises(ParameterError) as caught:
        run_all()
    assert caught.value.name == "n_cycles"
