"""The checks of the claims register on the period formulas of Sec. 3.4, Eqs. (22)-(25): each
printed form against the simulated step durations and periods of Fig. 3 (listed in
:mod:`escapement.paper.registry`)."""

from __future__ import annotations

import math

from . import corrected as derived
from . import printed as pe
from .checks import (PARTIAL, REPRODUCED, Evidence, Verdict, check, cycle_durations, fig3_all, fig3_case, fmt,
                     params_of, rel, within)

__all__ = ["eq22_abcd", "eq22e", "eq23", "eq24", "eq25"]


# --- Sec. 3.4: the period formulas -------------------------------------------------------------


@check("eq22_abcd", scenes=fig3_all)
def eq22_abcd(claim, ev: Evidence) -> Verdict:
    worst = 0.0
    for ds in ev.fig3.values():
        p = params_of(ds)
        durations = cycle_durations(ds)
        v = ds["velocity_before_impact"].values
        for k in range(len(durations["zone_right"])):
            h0 = math.hypot(p.a1, v[k] / p.omega)
            times = pe.step_times_22(v[k], p, h0)
            worst = max(worst, rel(times["22b"], durations["zone_right"][k]))
            worst = max(worst, rel(times["22c"] + times["22d"], durations["a2_to_a3"][k]))
            if k > 0:  # step 1 ends at the impact of cycle k, after the left swing of cycle k - 1
                left = durations["a4_to_a1"][k - 1] - math.acos(-p.a4 / h0) / p.omega
                worst = max(worst, rel(times["22a"], left))
    return Verdict(
        f"max relative difference {fmt(worst, 2)} against the simulated step durations (Fig. 3 {', '.join(ev.fig3)})",
        within(worst, claim["tolerance"]),
        note="(22a) is compared with the time from the left turning point to a1",
        paper_value="Eqs. (22a)-(22d)",
    )


@check("eq22e", scenes=fig3_case, args=("case",))
def eq22e(claim, ev: Evidence) -> Verdict:
    case = claim["args"]["case"]
    ds = ev.fig3[case]
    v = float(ds["velocity_before_impact"].values[-1])
    printed = pe.step_times_22(v, params_of(ds), 1.0)["22e"]
    simulated = float(cycle_durations(ds)["zone_left"][-1])
    return Verdict(
        f"{fmt(simulated)} s (simulated, last cycle of case {case})",
        within(rel(printed, simulated), claim["tolerance"]),
        note="(22e) needs + acos((a4 + f/w^2)/h3) instead of -: as printed it is negative",
        paper_value=f"{fmt(printed)} s",
    )


@check("eq23", scenes=fig3_case, args=("case",))
def eq23(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    v = float(ds["velocity_before_impact"].values[-1])
    printed = pe.period_23(v, p)
    simulated = float(ds["period"].values[-1])
    corrected = derived.period(v, p)
    return Verdict(
        f"{fmt(simulated)} s (simulated)",
        within(rel(printed, simulated), claim["tolerance"]),
        note=(
            f"with acos(-a4/h5) + acos(-a1/h5) for the last two terms (the left swing passes x = -h5) the formula "
            f"gives {fmt(corrected)} s, relative difference {fmt(rel(corrected, simulated), 2)}"
        ),
        paper_value=f"{fmt(printed)} s (as printed, signed a1, a4)",
    )


@check("eq24", scenes=fig3_case, args=("case",))
def eq24(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    v = float(ds["velocity_before_impact"].values[-1])
    first = pe.period_perturbation_24(v, p)
    second = pe.period_perturbation_24_closed(v, p)
    corrected = derived.impact_phase_jump_closed(p.a1, v, p)
    return Verdict(
        f"first form {fmt(first)} s; second form as printed {fmt(second)} s",
        PARTIAL if rel(second, first) > claim["tolerance"] else REPRODUCED,
        note=(
            f"the first form is the phase delay of the impact (it enters the exact period decomposition, see "
            f"eq25); the second equals it only with the velocity before the impact, x1, in place of x1+: "
            f"{fmt(corrected)} s"
        ),
        paper_value="dT1, two equal forms",
    )


@check("eq25", scenes=fig3_case, args=("case",))
def eq25(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    v = pe.fixed_point_19(p)
    printed = p.natural_period + 2 * (pe.period_perturbation_24(v, p) + pe.period_perturbation_25(v, p))
    corrected = derived.period_from_perturbations(v, p)
    simulated = float(ds["period"].values[-1])
    return Verdict(
        f"{fmt(simulated)} s (simulated)",
        within(rel(printed, simulated), claim["tolerance"]),
        note=(
            f"with the phase taken as atan(position/velocity) in (25) (the sine phase, which advances at w in free "
            f"flight), 2 pi/w + 2 (dT1 + dT2) = {fmt(corrected)} s, relative difference "
            f"{fmt(rel(corrected, simulated), 2)}"
        ),
        paper_value=f"{fmt(printed)} s (as printed)",
    )
