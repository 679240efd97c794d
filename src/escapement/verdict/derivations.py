"""The paper's derivations checked on the printed formulas alone: an equation a sentence says it obtained from
others is recomputed from them and compared with the printed result, one outcome per convention where it matters.
"""

from __future__ import annotations

import math
from dataclasses import replace

from scipy import optimize

from ..model.parameters import Parameters
from ..paper import printed as pe
from ..paper.conventions import departure, readings, symbols
from .evidence import Evidence, Verdict, check, fig3_scenes, fmt, params_of

#: models besides the paper's Fig. 3 cases: a stiffer spring, and an asymmetric geometry with a larger b
OTHERS = (Parameters(M=1.0, K=10.0, F=0.5, b=0.1, a1=-0.1, a2=0.05),
          Parameters(M=0.7, K=3.0, F=0.4, b=0.3, a1=-0.12, a2=0.02, a3=0.09, a4=-0.04))
#: the velocities before the impact at a1 (m/s) each derivation is compared at
VELOCITIES = (1.0, 2.0, 5.0)
#: each step equation: the Appendix A equation the sentence cites, its sign of f (x'' + w^2 x = sign f), the
#: velocities of :func:`escapement.paper.printed.step_velocities` and positions at the step's start and end, a note
STEPS = {"11": ("A-3", 1, ("v1p", "a1"), ("v2", "a2"), ""), "12": ("A-1", 0, ("v2", "a2"), ("v4", "a3"), ""),
         "14": ("A-5", -1, ("v4p", "a3"), ("v5", "a4"), ""),
         "15": ("A-5", -1, ("v5", "a4"), ("v1_next", "a1"), "; (15) has no term in f: it is the integral of (A-1), "
                "the equation of step 8 from a4 to a1 (Appendix A), not of the (A-5) the sentence cites")}


def largest(ev: Evidence, difference) -> float:
    """The largest ``difference(p, v)`` over the models and :data:`VELOCITIES`."""
    return max(difference(p, v) for p in [*(params_of(ds) for ds in ev.fig3.values()), *OTHERS] for v in VELOCITIES)


def by_convention(ev: Evidence, difference, tolerance: float, what: str, note: str = "") -> Verdict:
    """One outcome per convention: the largest relative ``difference(p, v, reading)`` at most ``tolerance``."""
    worst = {departure(r): largest(ev, lambda p, v, r=r: difference(p, v, r))
             for r in readings(("positions", "force", "half"))}
    holds = {name: w <= tolerance for name, w in worst.items()}
    return Verdict(f"largest relative difference of {what}: " + "; ".join(
        f"{name} {fmt(w, 2)}" for name, w in worst.items()), holds, paper_value="the printed forms agree",
        note=f"holds with {', '.join(n for n, h in holds.items() if h) or 'no convention'}{note}")


def step_energy_change(equation: str, p: Parameters, v1: float, reading) -> float:
    """The relative change over the step of ``v^2 + w^2 x^2 - 2 F x``, the integral of the cited ``x'' + w^2 x = F``."""
    _, sign, start, end, _ = STEPS[equation]
    (first, _), (second, frame) = symbols(p, reading, False), symbols(p, reading, True)
    v = pe.step_velocities(v1, p, first, second)
    s, force = (first, sign * p.f) if equation == "11" else (second, sign * frame * p.f)
    energy = [v[k] ** 2 + s.w**2 * getattr(s, a) ** 2 - 2 * force * getattr(s, a) for k, a in (start, end)]
    return abs(energy[1] - energy[0]) / v[end[0]] ** 2


@check(scenes=fig3_scenes, args=("equation",))
def appendix_step(claim, ev: Evidence) -> Verdict:
    """A step equation (11), (12), (14), (15) keeps the energy integral of the Appendix A equation it cites."""
    equation = str(claim["args"]["equation"])
    if equation not in STEPS:
        raise ValueError(f"equation = {equation!r} must be one of {', '.join(STEPS)}")
    cited, *_, note = STEPS[equation]
    return by_convention(ev, lambda p, v, r: step_energy_change(equation, p, v, r), claim["tolerance"],
                         f"the energy integral of ({cited}) over ({equation})", note)


def substitution_difference(p: Parameters, v1: float, reading) -> float:
    """Eqs. (10)-(15) composed against Eq. (16), both as printed, relative."""
    (first, _), (second, _) = symbols(p, reading, False), symbols(p, reading, True)
    composed, printed = pe.step_velocities(v1, p, first, second)["v1_next"], pe.poincare_map_16(v1, p, first)
    return abs(composed - printed) / printed


@check(scenes=fig3_scenes)
def map_substitution(claim, ev: Evidence) -> Verdict:
    """(16) is (10)-(14) substituted into (15), under each convention."""
    return by_convention(ev, substitution_difference, claim["tolerance"], "(10)-(15) composed from (16)")


def fixed_point_17(p: Parameters, v: float) -> float:
    """The fixed point g(x) = x (Eq. (18)) of the printed map (17), iterated from ``v``."""
    return float(optimize.fixed_point(lambda x: pe.poincare_map_17(x, p), v, xtol=1e-15))


#: each equation of the symmetric map: what the sentence derives it from ((20): central differences of relative
#: step 1e-5, as the slope of the return map is measured), and the printed form, at (p, v)
SYMMETRIC = {
    "17": (lambda p, v: pe.poincare_map_16(v, p), lambda p, v: pe.poincare_map_17(v, p)),
    "19": (fixed_point_17, lambda p, v: pe.fixed_point_19(p)),
    "20": (lambda p, v: (pe.poincare_map_17(v * (1 + 1e-5), p) - pe.poincare_map_17(v * (1 - 1e-5), p)) / (2e-5 * v),
           lambda p, v: pe.map_derivative_20(v, p)),
    "21": (lambda p, v: pe.map_derivative_20(pe.fixed_point_19(p), p), lambda p, v: pe.multiplier_21(p)),
}


def symmetric_difference(equation: str, p: Parameters, v: float) -> float:
    """The printed equation against what it is derived from, relative, with a3 = -a1, a4 = -a2."""
    derived, printed = (f(replace(p, a3=-p.a1, a4=-p.a2), v) for f in SYMMETRIC[equation])
    return abs(derived - printed) / abs(printed)


@check(scenes=fig3_scenes, args=("equation",))
def symmetric_map(claim, ev: Evidence) -> Verdict:
    """(17), (19), (20) or (21) against what its sentence derives it from, with a3 = -a1, a4 = -a2: one outcome."""
    equation = str(claim["args"]["equation"])
    if equation not in SYMMETRIC:
        raise ValueError(f"equation = {equation!r} must be one of {', '.join(SYMMETRIC)}")
    worst = largest(ev, lambda p, v: symmetric_difference(equation, p, v))
    return Verdict(f"largest relative difference of ({equation}) from its derivation {fmt(worst, 2)} at v1 = "
                   f"{', '.join(fmt(v) for v in VELOCITIES)} m/s",
                   bool(worst <= claim["tolerance"]), paper_value=f"Eq. ({equation})")


def _state(x0: float, v0: float, t: float, w: float, force: float) -> tuple[float, float]:
    """``(x, v)`` at ``t`` of ``x'' + w^2 x = force`` from ``(x0, v0)``: the solution of a step's equation."""
    c, phase = force / w**2, w * t
    return (c + (x0 - c) * math.cos(phase) + v0 / w * math.sin(phase),
            v0 * math.cos(phase) - (x0 - c) * w * math.sin(phase))


def interval_errors(p: Parameters, v1: float) -> dict[str, float]:
    """Each printed interval run from its step's start under the step's equation, against the step's end, relative."""
    w, v = p.omega, pe.step_velocities(v1, p)
    h0, h2 = math.hypot(p.a1, v1 / w), math.hypot(p.a2, v["v2"] / w)
    t = pe.step_times_22(v1, p, h0)
    x_a, x_b = _state(-h0, 0.0, t["22a"], w, 0.0)[0], _state(p.a1, v["v1p"], t["22b"], w, p.f)[0]
    v_c, x_d = _state(p.a2, v["v2"], t["22c"], w, 0.0)[1], _state(h2, 0.0, t["22d"], w, 0.0)[0]
    return {"22a": abs(x_a - p.a1) / abs(p.a1), "22b": abs(x_b - p.a2) / abs(p.a2), "22c": abs(v_c / v["v2"]),
            "22d": abs(x_d - p.a3) / abs(p.a3)}


@check(scenes=fig3_scenes)
def step_intervals(claim, ev: Evidence) -> Verdict:
    """(22a)-(22d) end where their steps end, under the equations of steps 1, 3, 4 and 5."""
    worst = {k: largest(ev, lambda p, v, k=k: interval_errors(p, v)[k]) for k in ("22a", "22b", "22c", "22d")}
    return Verdict("largest relative distance from the step's end: " + "; ".join(
        f"({k}) {fmt(e, 2)}" for k, e in worst.items()), bool(max(worst.values()) <= claim["tolerance"]),
        paper_value="Eqs. (22a)-(22d)", note="the positions signed, as (22a)'s -a1 reads them")
