"""The checks of the period formulas, Eqs. (22)-(25), against the simulated step durations and periods of Fig. 3;
(22e)-(25) under each convention of the paper, one equation read in one convention for all its forms.
"""

from __future__ import annotations

import math

from ..paper import corrected as derived
from ..paper import printed as pe
from ..paper.conventions import Reading, departure, second_half_trials, symbols, try_readings
from .sec3_steps import NO_FIGURE, conventions_verdict, describe
from .evidence import Evidence, Verdict, check, cycle_durations, fig3_scenes, fmt, params_of, rel, within


@check(scenes=fig3_scenes)
def eq22_abcd(claim, ev: Evidence) -> Verdict:
    worst = 0.0
    for ds in ev.fig3.values():
        p, durations, v = params_of(ds), cycle_durations(ds), ds["velocity_before_impact"].values
        for k in range(len(durations["zone_right"])):
            h0 = math.hypot(p.a1, v[k] / p.omega)
            times = pe.step_times_22(v[k], p, h0)
            worst = max(worst, rel(times["22b"], durations["zone_right"][k]),
                        rel(times["22c"] + times["22d"], durations["a2_to_a3"][k]))
            if k > 0:  # step 1 ends at the impact of cycle k, after the left swing of cycle k - 1
                worst = max(worst, rel(times["22a"], durations["a4_to_a1"][k - 1] - math.acos(-p.a4 / h0) / p.omega))
    return Verdict(
        f"max relative difference {fmt(worst, 2)} against the simulated step durations (Fig. 3 {', '.join(ev.fig3)})",
        within(worst, claim["tolerance"]), note="(22a) is compared with the time from the left turning point to a1",
        paper_value="Eqs. (22a)-(22d)")


def _last_cycle(claim, ev: Evidence) -> tuple:
    """The Fig. 3 case of ``args: {case}``, its model and its last velocity before the impact at a1."""
    ds = ev.fig3[claim["args"]["case"]]
    return ds, params_of(ds), float(ds["velocity_before_impact"].values[-1])


@check(scenes=fig3_scenes, args=("case",))
def eq22e(claim, ev: Evidence) -> Verdict:
    ds, p, v1 = _last_cycle(claim, ev)
    velocity, simulated = derived.cycle_velocities(v1, p), float(cycle_durations(ds)["zone_left"][-1])
    trials = second_half_trials(p, velocity, simulated, claim["tolerance"], pe.zone_left_time_22e)
    holds, note = conventions_verdict(trials, f"the simulated impulse time {fmt(simulated)} s", "Eq. (22e)")
    return Verdict(f"{fmt(simulated)} s (simulated, last cycle of case {claim['args']['case']})", holds,
                   note=f"{note}; as read, (22e) needs + acos((a4 + f/w^2)/h3) instead of -, the mirror image of (22b)",
                   paper_value=f"{fmt(trials[0].value)} s as read")


#: the steps whose times the terms of Eq. (23) give: whether of the second half, and the conventions in its terms
PERIOD_23_PARTS = {
    "zone_right": (False, ("positions",)),
    "a2_to_a3": (False, ("positions",)),
    "zone_left": (True, ("positions", "force", "half", "velocity")),
    "a4_to_a1": (True, ("positions", "half")),
}


def _terms_23(p, velocity, reading: Reading) -> dict[str, float]:
    """The terms of (23) under ``reading``: each step's terms with the symbols of its half period."""
    (first, _), (second, sign) = (symbols(p, reading, second_half=half) for half in (False, True))
    v = {"v1p": velocity["v1p"], "v2": velocity["v2"], "v5": sign * velocity["v5"],
         "v4p": sign * velocity["v4p" if reading.velocity == "after" else "v4"]}  # the second half's, with its sign
    terms = {half: pe.period_terms_23(v, s) for half, s in ((False, first), (True, second))}
    return {part: terms[half][part] for part, (half, _) in PERIOD_23_PARTS.items()}


@check(scenes=fig3_scenes, args=("case",))
def eq23(claim, ev: Evidence) -> Verdict:
    """Eq. (23) on the last cycle under each reading, and each step's terms against its time: where conventions part."""
    ds, p, v1 = _last_cycle(claim, ev)
    velocity, simulated, tolerance = derived.cycle_velocities(v1, p), float(ds["period"].values[-1]), claim["tolerance"]
    whole = try_readings(lambda r: math.fsum(_terms_23(p, velocity, r).values()), simulated, tolerance,
                         ("positions", "force", "half", "velocity"))
    holds, note = conventions_verdict(whole, f"the simulated period {fmt(simulated)} s", "Eq. (23)")
    durations = {k: float(v[-1]) for k, v in cycle_durations(ds).items()}
    working = {part: " or ".join(departure(t.reading) for t in try_readings(
        lambda r, part=part: _terms_23(p, velocity, r)[part], durations[part], tolerance, part_axes) if t.reproduces)
        for part, (_, part_axes) in PERIOD_23_PARTS.items()}
    described = "; ".join(f"{part}: {found or 'no reading'}" for part, found in working.items())
    return Verdict(f"{fmt(simulated)} s (simulated)", holds,
                   note=f"each step's terms are reproduced by: {described}; " + note,
                   paper_value=f"{fmt(whole[0].value)} s as read (signed a1 .. a4)")


@check(scenes=fig3_scenes, args=("case", "form"))
def eq24(claim, ev: Evidence) -> Verdict:
    """Eq. (24) at the last cycle against the simulated impact's phase jump; ``form: second`` holds where both do."""
    form = claim["args"]["form"]
    if form not in ("first", "second"):
        raise ValueError(f"form = {form!r} must be first or second")
    _, p, v1 = _last_cycle(claim, ev)
    v1p, measured, tolerance = (1 - p.b) * v1, derived.impact_phase_jump(p.a1, v1, p), claim["tolerance"]

    def forms(reading: Reading, plus: float, plain: float) -> tuple[float, float]:
        """Both forms with x1+ = ``plus`` and x1 = ``plain``."""
        s = symbols(p, reading, False)[0]
        return pe.phase_jump_24(plain, plus, s), pe.phase_jump_24_closed(plus, p.b, s)

    axes = ("positions",)  # the velocity is not a convention here: Eq. (10) defines x1+
    first, second = (try_readings(lambda r, i=i: forms(r, v1p, v1)[i], measured, tolerance, axes) for i in (0, 1))
    both = [a.reading for a, b in zip(first, second) if a.reproduces and b.reproduces]
    swapped = forms(first[0].reading, v1, v1p)
    holds = {str(a.reading): a.reproduces and (form == "first" or b.reproduces) for a, b in zip(first, second)}
    lead = ("both forms read with x1+ the velocity after the impact as Eq. (10) defines it, x1+(k) = (1 - b) x1(k), "
            "x1 the one before, and one convention of the positions for both")
    if form == "second":
        lead += ("; " + (f"both forms reproduce the phase delay with {' or '.join(map(departure, both))}" if both else
                         "the second form differs from the first in every convention: a misprint, x1+ printed where "
                         "atan(A) - atan(B) = atan((A - B)/(1 + A B)) gives x1, the velocity before the impact; Eq. "
                         "(10) fixes the equation's velocity, so it is judged form by form (this part, the misprint)"))
    return Verdict(
        f"phase delay of the impact {fmt(measured)} s; with x1+ after the impact: first form {fmt(first[0].value)} s, "
        f"second form {fmt(second[0].value)} s", holds,
        note=(f"{lead}; {NO_FIGURE}; the first form under each convention of the positions: {describe(first)}; the "
              f"second: {describe(second)}; with x1+ read as the velocity before the impact (x1 the one after), which "
              f"Eq. (10) excludes, the first form gives {fmt(swapped[0])} s and the second {fmt(swapped[1])} s: no one "
              "reading of x1+ gives both forms"),
        paper_value="dT1, first form" if form == "first" else "dT1, second form, equal to the first")


@check(scenes=fig3_scenes, args=("case",))
def eq25(claim, ev: Evidence) -> Verdict:
    """2 pi/w + 2 (dT1 + dT2) of Eqs. (24)-(25) at the last cycle under each reading, against the simulated period."""
    ds, p, v1 = _last_cycle(claim, ev)
    v1p, simulated = (1 - p.b) * v1, float(ds["period"].values[-1])

    def period(reading: Reading) -> float:
        s = symbols(p, reading, False)[0]
        entering = v1p if reading.velocity == "after" else v1
        return p.natural_period + 2 * (pe.phase_jump_24(v1, v1p, s) + pe.zone_change_25(entering, s))

    trials = try_readings(period, simulated, claim["tolerance"], ("positions", "velocity"))
    holds, note = conventions_verdict(trials, f"the simulated period {fmt(simulated)} s", "2 pi/w + 2 (dT1 + dT2)")
    corrected = derived.period_from_perturbations(v1, p)
    return Verdict(f"{fmt(simulated)} s (simulated)", holds, paper_value=f"{fmt(trials[0].value)} s as read", note=(
        f"{note}; with the phase taken as atan(position/velocity) in (25) (the sine phase, which advances at w in "
        f"free flight), 2 pi/w + 2 (dT1 + dT2) = {fmt(corrected)} s, relative difference "
        f"{fmt(rel(corrected, simulated), 2)}"))
