"""The checks of the step equations (10)-(15) as printed, each fed the simulated state before its step, and of
Eq. (14) under each convention of the paper, a grid of readings (:func:`conventions_verdict`).
"""

from __future__ import annotations

import numpy as np

from ..model.events import EventKind
from ..paper import corrected as derived
from ..paper import printed as pe
from ..paper.conventions import Trial, departure, second_half_trials
from ..paper.corrected import _sqrt
from .evidence import Evidence, Verdict, check, events_of, fig3_scenes, fmt, params_of, within


_IMPACT_LAW = "the impact law (A-2) the model is built on"
#: each step: the printed formula (velocity out from velocity in), where its input and output are among a cycle's
#: events (offset from the impact at a1, 4 the next a1; before or after the event), and the printed text as read
PRINTED_STEPS = {
    "10": (lambda v, p: (1 - p.b) * v, (0, "before"), (0, "after"), f"x1+ = (1 - b) x1, {_IMPACT_LAW}"),
    "11": (lambda v, p: _sqrt(v * v + (p.a1**2 - p.a2**2) * p.omega2 - 2 * (p.a1 - p.a2) * p.f),
           (0, "after"), (1, "before"), "x2 = sqrt(x1+^2 + (a1^2 - a2^2) w^2 - 2 (a1 - a2) f)"),
    "12": (lambda v, p: -_sqrt(v * v + (p.a2**2 - p.a3**2) * p.omega2),
           (1, "before"), (2, "before"), "x4 = -sqrt(x2^2 + (a2^2 - a3^2) w^2)"),
    "13": (lambda v, p: (1 - p.b) * v, (2, "before"), (2, "after"), f"x4+ = (1 - b) x4, {_IMPACT_LAW}"),
    "15": (lambda v, p: _sqrt(v * v + (p.a4**2 - p.a1**2) * p.omega2),
           (3, "before"), (4, "before"), "x1(k+1) = sqrt(x5^2 + (a4^2 - a1^2) w^2)"),
}


@check(scenes=fig3_scenes, args=("equation",))
def printed_step(claim, ev: Evidence) -> Verdict:
    """One step equation as printed, fed the simulated state before its step."""
    equation = str(claim["args"]["equation"])
    if equation not in PRINTED_STEPS:
        raise ValueError(f"no printed step equation ({equation}); known: {', '.join(PRINTED_STEPS)}")
    formula, (i_in, f_in), (i_out, f_out), text = PRINTED_STEPS[equation]
    worst, n = 0.0, 0
    for ds in ev.fig3.values():
        p, starts = params_of(ds), events_of(ds, EventKind.IMPACT_A1)
        starts = starts[starts + 4 < ds.sizes["event"]]
        v_in, v_out = (ds[f"event_velocity_{f}"].values[starts + i] for i, f in ((i_in, f_in), (i_out, f_out)))
        predicted = np.array([formula(float(v), p) for v in v_in])
        worst = max(worst, float(np.max(np.abs(predicted - v_out) / np.abs(v_out))))
        n += len(starts)
    return Verdict(f"max relative difference {fmt(worst, 3)} over {n} simulated steps (Fig. 3 {', '.join(ev.fig3)})",
                   within(worst, claim["tolerance"]), note=f"read as {text}, fed the simulated state before the step",
                   paper_value=f"Eq. ({equation})")


impact_step = check(scenes=fig3_scenes, args=("equation",), law="the impact law v+ = (1 - b) v- (Eq. (A-2))")(
    printed_step.function)


def describe(trials: list[Trial]) -> str:
    return "; ".join(f"{departure(t.reading)}: {fmt(t.value)} ({fmt(t.relative_difference, 2)})" for t in trials)


NO_FIGURE = "no figure tells the conventions apart: each changes how a formula reads, not the motion Figs. 3-5 print"


def conventions_verdict(trials: list[Trial], simulated: str, what: str) -> tuple[dict[str, bool], str]:
    """Whether the formula holds under each convention (its ``trials``), and a note naming those it holds under."""
    held = [departure(t.reading) for t in trials if t.reproduces]
    return {str(t.reading): t.reproduces for t in trials}, (
        f"{what} gives {simulated} under {len(held)} of the {len(trials)} conventions of the paper"
        + (f" ({', '.join(held)}), not under the others; {NO_FIGURE}" if 0 < len(held) < len(trials) else "")
        + f"; value (relative difference) under each: {describe(trials)}")


@check(scenes=fig3_scenes, args=("case",))
def eq14_conventions(claim, ev: Evidence) -> Verdict:
    """Eq. (14) at the last cycle under each convention, from the energy balance's velocity at a3."""
    case, ds = claim["args"]["case"], ev.fig3[claim["args"]["case"]]
    p, i = params_of(ds), events_of(ds, EventKind.IMPACT_A1)[-2]
    v1, v5 = float(ds["event_velocity_before"].values[i]), float(ds["event_velocity_before"].values[i + 3])
    trials = second_half_trials(p, derived.cycle_velocities(v1, p), v5, claim["tolerance"], pe.v5_14)
    holds, note = conventions_verdict(trials, f"the simulated velocity at a4, {fmt(v5)} m/s", "Eq. (14)")
    return Verdict(f"simulated velocity at a4 {fmt(v5)} m/s (case {case}, last cycle)", holds, note=note,
                   paper_value=f"{fmt(trials[0].value)} m/s as read")
