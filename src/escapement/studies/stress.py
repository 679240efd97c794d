"""Stress cases: the solver at the edges of its regime, each against an independent answer (a closed form
derived on paper, the 50-digit reference, or the reference solver at tight tolerance), far from the paper's
parameters. :func:`run_all` gives one row per case for ``results/stress/summary.csv``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import mpmath
import numpy as np

from ..model.limits import MemoryBudgetError
from ..model.parameters import ParameterError, Parameters
from ..model.status import Status
from ..paper import corrected as derived
from .poincare import stability_grid
from ..solvers.ensemble import solve_ensemble
from ..solvers.exact import solve_exact
from ..integrators.high_precision import solve_high_precision
from ..integrators.reference import solve_reference
from ..solvers.stream import iter_cycles

__all__ = ["CASES", "StressCase", "StressResult", "row", "run_all"]


@dataclass(frozen=True)
class StressResult:
    outcome: str
    check: str
    passed: bool
    detail: str


@dataclass(frozen=True)
class StressCase:
    name: str
    regime: str
    run: Callable[[], StressResult]


def _paper(**changes) -> Parameters:
    return Parameters(**{**dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), **changes})


def _rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b) if b != 0 else abs(a)


def stop_below_a1() -> StressResult:
    s = solve_exact(_paper(), 0.05, n_cycles=10)
    x = s.sample(np.array([100.0]))[0][0]
    ok = s.status == Status.STOPPED and len(s.events) == 0 and abs(x - 0.05 * math.cos(100.0)) < 1e-15
    return StressResult(s.status.value, "no event; free motion x = x0 cos(w t) at t = 100 s (closed form)", ok,
                        f"x(100) - 0.05 cos 100 = {x - 0.05 * math.cos(100.0):.1e}")


def stop_energy_runs_out() -> StressResult:
    p = _paper(F=0.0, a3=0.3, a4=0.0)
    s = solve_exact(p, 1.0, n_cycles=100)
    radius = math.hypot(s.events.x[-1], s.events.v_after[-1] / p.omega)
    energy = 0.5 * p.M * s.events.v_before**2 + 0.5 * p.K * s.events.x**2
    ok = (s.status == Status.STOPPED and radius < p.a3 and abs(s.exit.turning_point - radius) < 1e-15
          and np.all(np.diff(energy[s.events.kind % 2 == 1]) < 0))
    return StressResult(s.status.value, "last swing short of a3 = 0.3 m; energy falls at every impact (F = 0)", ok,
                        f"last swing {radius:.6f} m after {len(s.events)} events")


def turned_back_in_zone() -> StressResult:
    p = Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1)
    s = solve_exact(p, 0.021, n_cycles=3)
    ref = solve_reference(p, 0.021, n_cycles=3, rtol=1e-12)
    # closed form: from the impact at a3 the zone motion about -F/K turns at -F/K - R
    turning = -p.zone_offset - math.hypot(p.a3 + p.zone_offset, s.events.v_after[0] / p.omega)
    ok = (s.status == ref.status == Status.TURNED_BACK_IN_ZONE and abs(s.exit.turning_point - turning) < 1e-15
          and abs(s.t_final - ref.t_final) < 1e-8)
    return StressResult(s.status.value, "turning point -F/K - R (closed form); time against solve_ivp rtol 1e-12",
                        ok, f"turns at {turning:.9f} m, |t - t_ref| = {abs(s.t_final - ref.t_final):.1e} s")


def stiff_spring_paper_geometry() -> StressResult:
    p = _paper(K=1000.0, F=0.5)
    s = solve_exact(p, 1.0, n_cycles=50)
    v = s.cycles.velocity_before_impact
    map_error = max(_rel(b, math.sqrt((1 - p.b) ** 4 * a * a + derived.map_constant(p))) for a, b in zip(v, v[1:]))
    bound = 2 * p.zone_offset - p.a1  # the zone motion about F/K from a1 turns at or beyond 2 F/K - a1
    ok = s.status == Status.COMPLETED and bound > p.a2 and map_error < 1e-12
    return StressResult(s.status.value, "K >> F/|a2| with a1 = -0.1, a2 = 0.05: the turning point 2F/K - a1 > a2, so "
                        "no turning back; Eq. (16) per cycle", ok, f"2F/K - a1 = {bound:.4f} m > a2; map error "
                        f"{map_error:.1e}")


def b_small() -> StressResult:
    b = 1e-4
    g = stability_grid(dict(M=1.0, K=1.0, a1=-0.1, a2=0.05), np.array([b]), np.array([1.0]))
    mu = float(g["multiplier"][0])
    fixed = math.sqrt(2 * 0.15 / (2 * b - b * b))
    ok = abs(mu - (1 - b) ** 4) < 1e-8 and _rel(float(g["fixed_point"][0]), fixed) < 1e-9
    return StressResult("completed", "measured multiplier against (1-b)^4 and fixed point against Eq. (19)", ok,
                        f"mu2 = {mu:.12f}, 1 - mu2 = {1 - mu:.3e}")


def b_one() -> StressResult:
    s = solve_exact(_paper(b=1.0), 1.0, n_cycles=5)
    impacts = (s.events.kind == 1) | (s.events.kind == 3)
    ok = (s.status == Status.COMPLETED and np.all(s.events.v_after[impacts] == 0.0)
          and np.allclose(s.cycles.velocity_before_impact[1:], math.sqrt(2 * 0.15), rtol=1e-14))
    return StressResult(s.status.value, "v+ = 0 at every impact; from rest at a1, v^2 = 2 f (a2 - a1) next cycle",
                        ok, f"velocity before impact {s.cycles.velocity_before_impact[-1]:.15f} m/s")


def _zeno_reference(speed: float, distance: float, omega: float, ratio: float) -> tuple[float, str]:
    """The flights (2/omega) atan(x r**n) summed in 30 digits: term by term while that is feasible, else by
    Euler-Maclaurin with the closed-form integral Ti2(x)/lambda, Ti2(x) = Im Li2(i x), lambda = -log r."""
    with mpmath.workdps(30):
        x = mpmath.mpf(speed) / (mpmath.mpf(omega) * mpmath.mpf(distance))
        r = mpmath.mpf(ratio)
        if ratio <= 0.999:
            method = "a 30-digit sum"
            total, term = mpmath.mpf(0), x
            while term > mpmath.mpf("1e-20"):
                total += mpmath.atan(term)
                term *= r
            total += term / (1 - r)
        else:
            method = "30-digit Euler-Maclaurin summation"
            lam = -mpmath.log(r)
            integral = mpmath.im(mpmath.polylog(2, 1j * x)) / lam
            total = mpmath.sumem(lambda n: mpmath.atan(x * mpmath.exp(-lam * n)), [0, mpmath.inf], integral=integral)
        return float(2 * total / mpmath.mpf(omega)), method


def _chattering(b: float) -> StressResult:
    p = _paper(b=b)
    s = solve_exact(p, 1.0, n_cycles=5)
    t_hit = s.events.t[-1]
    rest, method = _zeno_reference(abs(s.events.v_after[-1]), abs(p.a1) if s.events.kind[-1] == 1 else p.a3,
                                   p.omega, abs(1 - b))
    ok = s.status == Status.CHATTERING and _rel(s.exit.t_accumulation, t_hit + rest) < 1e-12
    return StressResult(s.status.value, f"accumulation time of the rebounds against {method}", ok,
                        f"impacts accumulate {s.exit.t_accumulation - t_hit:.6g} s after the first rebound")


def _refused(run: Callable[[], object], name: str, words: str, row: int | None = None) -> tuple[bool, str]:
    """Whether ``run`` raises ParameterError naming ``name`` (and ``row``) with ``words`` in its message; the
    message, for the table."""
    try:
        run()
    except ParameterError as err:
        return err.name == name and err.row == row and words in str(err), str(err).split(", so that")[0]
    return False, "accepted"


def _refusal(check: str, run: Callable[[], object], name: str, words: str, row: int | None = None) -> Callable:
    return lambda: StressResult("refused", check, *_refused(run, name, words, row))


def memory_budget() -> StressResult:
    # 1e9 cycles would store some 1.8e11 bytes, over the 2 GB budget; streamed, a run is the stored one bit for bit
    try:
        solve_exact(_paper(), 1.0, n_cycles=10**9, record_trajectory=False)
        refused, message = False, "accepted"
    except MemoryBudgetError as err:
        refused, message = err.name == "n_cycles" and err.estimate > err.budget, str(err).split("; ")[0]
    streamed = np.concatenate([c.impact_time for c in iter_cycles(_paper(), 1.0, n_cycles=20_000, chunk=3_000)])
    stored = solve_exact(_paper(), 1.0, n_cycles=20_000, record_trajectory=False).cycles.impact_time
    return StressResult("refused", "n_cycles = 1e9 refused, naming the size; streamed in chunks, a "
                        "run equals the stored one bit for bit", refused and np.array_equal(streamed, stored), message)


def counts_refused() -> StressResult:
    results = [_refused(lambda n=n: solve_exact(_paper(), 1.0, n_cycles=n), "n_cycles", "") for n in (0, -1, 1.5, True)]
    results.append(_refused(lambda: solve_ensemble(1.0, 1.0, 1.0, 0.1, -0.1, 0.05, n_cycles=0), "n_cycles", ""))
    return StressResult("refused", "n_cycles = 0, -1, 1.5, True (and 0 for the ensemble): refused naming n_cycles",
                        all(r[0] for r in results), results[0][1][:90])


def graze_on_impact_position() -> StressResult:
    s = solve_exact(_paper(), 0.1, n_cycles=5)
    return StressResult(s.status.value, "turning point exactly at a3: not passed, no impact",
                        s.status == Status.STOPPED and s.exit.margin == 0.0, "released at rest at x0 = a3")


def graze_just_inside() -> StressResult:
    s = solve_exact(_paper(), math.nextafter(0.1, 0.0), n_cycles=5)
    return StressResult(s.status.value, "turning point one float below a3: stopped",
                        s.status == Status.STOPPED and 0 < s.exit.margin < 1e-16, f"margin {s.exit.margin:.1e} m")


def graze_just_beyond() -> StressResult:
    p = _paper()
    s = solve_exact(p, math.nextafter(0.1, 1.0), n_cycles=5)
    # limit x0 -> a3+: the impact at a3 has no speed; from rest at a3 the zone and the free swing give
    v_a4_sq = p.omega2 * (p.a3**2 - p.a4**2) + 2 * p.f * (p.a3 - p.a4)
    v_limit = math.sqrt(v_a4_sq + p.omega2 * (p.a4**2 - p.a1**2))
    first_speed = abs(s.events.v_before[0])
    ok = (s.status == Status.COMPLETED and first_speed < 1e-7
          and _rel(s.cycles.velocity_before_impact[0], v_limit) < 1e-12)
    return StressResult(s.status.value, "turning point one float beyond a3: impact at ~0 m/s, then the motion of the "
                        "limit from rest at a3 (closed form)", ok, f"first impact at {first_speed:.1e} m/s")


def graze_zone_end() -> StressResult:
    p = Parameters(M=1, K=100, F=0.01, b=0.1, a1=-0.02, a2=0.1)
    # release x0 such that the zone motion after the impact at a3 turns exactly at a4 (50 digits)
    with mpmath.workdps(50):
        c = mpmath.mpf(p.F) / mpmath.mpf(p.K)
        radius = -mpmath.mpf(p.a4) - c
        x0 = float(mpmath.sqrt((radius**2 - (mpmath.mpf(p.a3) + c) ** 2) / mpmath.mpf(0.81) + mpmath.mpf(p.a3) ** 2))
    s = solve_exact(p, x0, n_cycles=3)
    if len(s.events) >= 2 and s.events.kind[1] == 4:  # it passed a4, at the speed of the grazing limit
        ok = abs(s.events.v_before[1]) < 1e-6
        detail = f"passed a4 at {abs(s.events.v_before[1]):.1e} m/s, then {s.status.value}"
    else:  # it turned back in the zone, at the grazing point
        ok = s.status == Status.TURNED_BACK_IN_ZONE and abs(s.exit.turning_point - p.a4) < 1e-15
        detail = f"turned back {s.exit.turning_point - p.a4:.1e} m from a4"
    return StressResult(s.status.value, "zone turning point within 1e-15 of a4: either outcome, consistent with the "
                        "grazing limit", ok and not np.isnan(s.events.t).any(), detail)


def reference_grazes_zone_end() -> StressResult:
    # after the impact at a3 the zone arc about c = -F/K has R^2 = (a3 - c)^2 + (1 - b)^2 (x0^2 - a3^2); x0 (50
    # digits) makes it turn 1e-9 m beyond a4, so that one solve_ivp step can span the crossing and the turn
    p = Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.02, a2=0.05, a3=0.02, a4=-0.05)
    with mpmath.workdps(50):
        c, a3, a4 = -mpmath.mpf(p.F) / mpmath.mpf(p.K), mpmath.mpf(p.a3), mpmath.mpf(p.a4)
        radius = c - (a4 - mpmath.mpf(1e-9))
        x0 = float(mpmath.sqrt(a3 * a3 + (radius**2 - (a3 - c) ** 2) / (1 - mpmath.mpf(p.b)) ** 2))
    exact = solve_exact(p, x0, n_cycles=3)
    ref = solve_reference(p, x0, n_cycles=3, method="DOP853", rtol=1e-12)
    same = list(ref.events.kind) == list(exact.events.kind)
    ok = list(exact.events.kind[:2]) == [3, 4] and ref.status == exact.status and same
    return StressResult(ref.status.value, "zone arc turning 1e-9 m beyond a4 (closed form): the reference "
                        "(DOP853, rtol 1e-12) crosses a4 as the exact solver does", ok,
                        f"{len(ref.events)} events, the same kinds as the exact solver's: {'yes' if same else 'no'}")


def _error_against_50_digits(p: Parameters, s) -> float:
    """The largest relative error of the impact times and velocities of ``s``'s 20 cycles against 50 digits."""
    hp = solve_high_precision(p, 1.0, n_cycles=20).cycles
    errors = []
    for name in ("impact_time", "velocity_before_impact"):
        ref = np.array([float(v) for v in getattr(hp, name)])
        errors.append(float(np.max(np.abs(getattr(s.cycles, name) - ref) / np.abs(ref))))
    return max(errors)


def scales() -> StressResult:
    worst, outcomes, count = 0.0, {}, 0
    for K in (1e-3, 1.0, 1e3):
        for M in (1e-3, 1.0, 1e3):
            for F in (0.0, 1.0, 1e3):
                p = Parameters(M=M, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)
                s = solve_exact(p, 1.0, n_cycles=20, record_trajectory=False)
                outcomes[s.status.value] = outcomes.get(s.status.value, 0) + 1
                count += 1
                if s.status == Status.COMPLETED:
                    worst = max(worst, _error_against_50_digits(p, s))
    ok = worst < 1e-13 and outcomes.get("completed", 0) == count
    return StressResult("completed" if ok else str(outcomes), "K, M in 1e-3..1e3 N/m, kg; F in 0..1e3 N: 20 cycles "
                        "against 50 digits", ok, f"{count} runs, largest relative error {worst:.1e}")


def near_origin() -> StressResult:
    p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-1e-9, a2=1e-9)
    s = solve_exact(p, 1.0, n_cycles=20, record_trajectory=False)
    worst = _error_against_50_digits(p, s)
    return StressResult(s.status.value, "a1 = -1e-9 m, a2 = 1e-9 m: 20 cycles against 50 digits",
                        s.status == Status.COMPLETED and worst < 1e-13, f"largest relative error {worst:.1e}")


CASES = [
    StressCase("stop_below_a1", "the escapement stops: x0 below |a1|", stop_below_a1),
    StressCase("stop_energy_runs_out", "the escapement stops: too little energy for the next impact",
               stop_energy_runs_out),
    StressCase("turned_back_in_zone", "the mass turns back inside an impulse zone", turned_back_in_zone),
    StressCase("stiff_spring_paper_geometry", "stiff spring, K >> F/|a2|", stiff_spring_paper_geometry),
    StressCase("b_small", "b -> 0 (b = 1e-4)", b_small),
    StressCase("b_one", "b = 1: the mass stops at the impact position", b_one),
    StressCase("b_between_one_and_two", "1 < b < 2 (b = 1.5): the impact reverses the velocity",
               lambda: _chattering(1.5)),
    StressCase("b_near_two", "b -> 2 (b = 1.999)", lambda: _chattering(1.999)),
    StressCase("b_two_minus_1e9", "b = 2 - 1e-9: some 1e10 rebounds before they accumulate",
               lambda: _chattering(2.0 - 1e-9)),
    StressCase("b_two_minus_1e12", "b = 2 - 1e-12: some 1e13 rebounds before they accumulate",
               lambda: _chattering(2.0 - 1e-12)),
    StressCase("float_range_state", "floating-point range: an initial state whose energy overflows",  # 5e399 J
               _refusal("x0 = 1e200 m: 0.5 K x0**2 overflows; refused naming x0 and its range",
                        lambda: solve_exact(_paper(), 1e200, n_cycles=5), "x0", "1e-50, 1e+50")),
    StressCase("float_range_subnormal_mass", "floating-point range: a subnormal mass",
               _refusal("M = 1e-320 kg (subnormal): K/M overflows; refused naming M, not K", lambda: _paper(M=1e-320),
                        "M", "1e-50, 1e+50")),
    StressCase("ensemble_bad_row", "one validation: a bad row of the ensemble",  # the scalar rule, row by row
               _refusal("ensemble row 2 has b = True: refused naming the row and b", lambda: solve_ensemble(
                   1.0, 1.0, 1.0, [0.1, 0.2, True], -0.1, 0.05, n_cycles=5), "b", "a real number", row=2)),
    StressCase("memory_budget", "memory: a run too large to store, and its streamed form", memory_budget),
    StressCase("counts_refused", "one validation: cycle counts that are not positive integers", counts_refused),
    StressCase("graze_on_impact_position", "grazing: turning point exactly at an impact position",
               graze_on_impact_position),
    StressCase("graze_just_inside", "grazing: turning point 1e-17 m short of an impact position", graze_just_inside),
    StressCase("graze_just_beyond", "grazing: turning point 1e-17 m beyond an impact position", graze_just_beyond),
    StressCase("graze_zone_end", "grazing: zone turning point within 1e-15 of its end", graze_zone_end),
    StressCase("reference_grazes_zone_end", "grazing: the reference solver near a zone's end (1e-9 m)",
               reference_grazes_zone_end),
    StressCase("scales", "K and M from 1e-3 to 1e3, F from 0 to 1e3", scales),
    StressCase("near_origin", "positions near the origin", near_origin),
]


def row(case: StressCase, result: StressResult) -> dict:
    """The case's row of the summary table."""
    return {"case": case.name, "regime": case.regime, "outcome": result.outcome, "check": result.check,
            "passed": "yes" if result.passed else "no", "detail": result.detail}


def run_all() -> list[dict]:
    """Every case, a row each, in the order of :data:`CASES`; an exception is a bug, not a result: it propagates."""
    return [row(case, case.run()) for case in CASES]
