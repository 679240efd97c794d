"""The checks of the claims register on the results of Sec. 4: the Poincare maps of Fig. 3, the
shock detail of Fig. 4 and the comparisons of Fig. 5's spring constants, each read off the datasets of
its figure (and the checks dataset where a claim concerns several runs), with the scenes each reads.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.events import EventKind
from . import corrected as derived
from .checks import (Evidence, Verdict, check, fig3_all, fig3_case, fig3_cases, fmt, group_runs, params_of, rel,
                     runs_left_regime, runs_only, within)
from .dynamics_checks import amplitude_of

__all__ = ["NOT_COMPARED", "common_force_runs", "converged_amplitudes", "energy_rate"]


# --- the scenes of the figure checks -----------------------------------------------------------


def fig4(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {"Fig. 4": ev.fig4}


# --- Sec. 4, Fig. 3 ----------------------------------------------------------------------------


@check("both_converge", scenes=fig3_all)
def both_converge(claim, ev: Evidence) -> Verdict:
    changes = {k: rel(ds["velocity_before_impact"].values[-1], ds["velocity_before_impact"].values[-2])
               for k, ds in ev.fig3.items()}
    return Verdict(
        "; ".join(f"case {k}: last change {fmt(c, 2)}" for k, c in changes.items()),
        within(max(changes.values()), claim["tolerance"]),
        note="relative change of the velocity before impact between the last two cycles",
    )


def converged_amplitudes(ds: xr.Dataset) -> dict[str, float]:
    """The last cycle's amplitude under each definition, from its events: the Step-1 amplitude ``h0`` of the
    free arc that ends in the impact at a1, the right turning point (the largest x) of the free arc after a2,
    and the left one (|x|) of the free arc after a4."""
    p = params_of(ds)
    kind, before = ds["event_kind"].values.astype(int), ds["event_velocity_before"].values
    v2 = before[np.flatnonzero(kind == int(EventKind.ZONE_END_A2))[-1]]
    v5 = before[np.flatnonzero(kind == int(EventKind.ZONE_END_A4))[-1]]
    return {"h0": float(np.hypot(p.a1, ds["velocity_before_impact"].values[-1] / p.omega)),
            "right turning point": float(np.hypot(p.a2, v2 / p.omega)),
            "left turning point": float(np.hypot(p.a4, v5 / p.omega))}


@check("compare_cases", scenes=fig3_cases, args=("cases", "quantity"))
def compare_cases(claim, ev: Evidence) -> Verdict:
    """The first case of ``cases`` converges to a greater ``quantity`` than the second: a variable of the Fig. 3
    datasets, or ``amplitude`` under the definition ``args: {definition}`` (:func:`converged_amplitudes`)."""
    first, second = (str(c) for c in claim["args"]["cases"])
    quantity = claim["args"]["quantity"]
    a, b = (converged_amplitudes(ds)[claim["args"]["definition"]] if quantity == "amplitude"
            else float(ds[quantity].values[-1]) for ds in (ev.fig3[first], ev.fig3[second]))
    return Verdict(f"{first}: {fmt(a)}, {second}: {fmt(b)}", bool(a > b))


def energy_rate(v: np.ndarray) -> float:
    """Rate of convergence of v^2 per cycle, from successive differences: for a map linear in v^2,
    (E[k+2] - E[k+1]) / (E[k+1] - E[k]) is the rate, with no need to know the limit. Only
    differences well above rounding (1e-7 of E) are used."""
    e = v**2
    d = np.diff(e)
    usable = np.flatnonzero((np.abs(d[:-1]) > 1e-7 * e[-1]) & (np.abs(d[1:]) > 1e-7 * e[-1]))
    return float(np.median(d[usable + 1] / d[usable]))


@check("convergence_rates", scenes=fig3_cases, args=("cases",))
def convergence_rates(claim, ev: Evidence) -> Verdict:
    """The asymptotic rates of convergence of x1^2 of the two cases differ beyond the tolerance."""
    rates = {str(k): energy_rate(ev.fig3[str(k)]["velocity_before_impact"].values) for k in claim["args"]["cases"]}
    first, second = rates.values()
    return Verdict(
        "rate of convergence of x1^2 per cycle: " + ", ".join(f"{k}: {fmt(r, 7)}" for k, r in rates.items()),
        not within(abs(first - second), claim["tolerance"]),
        note=("the map is linear in x1^2, so x1^2 approaches its limit by the factor (1-b)^4 per cycle whatever the "
              "force; x1 itself does not (its ratio of successive differences tends to (1-b)^4 only near the limit)"),
    )


@check("cycles_to_converge", scenes=runs_only, args=("group",),
       threshold="the convergence criterion by which the checks dataset counts the cycles to converge")
def cycles_to_converge(claim, ev: Evidence) -> Verdict:
    """Runs released alike that differ only in F take different numbers of cycles to converge."""
    runs = group_runs(ev, claim["args"]["group"])
    if (left := runs_left_regime(runs)) is not None:
        return left
    cycles = runs["cycles_to_converge"].values
    return Verdict(", ".join(f"F = {fmt(f, 3)} N: {int(c)} cycles" for f, c in zip(runs["F"].values, cycles))
                   + f" (released at x0 = {', '.join(sorted({fmt(x, 3) for x in runs['x0'].values}))} m)",
                   len(set(cycles.tolist())) > 1)


@check("converged_period", scenes=fig3_case, args=("case",))
def converged_period(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    simulated = float(ds["period"].values[-1])
    return Verdict(
        f"{fmt(simulated)} s",
        within(abs(simulated - float(claim["paper_value"])), claim["tolerance"]),
        note=(
            f"2 pi/w = {fmt(p.natural_period)} s; the two impacts delay each cycle and the two impulses advance it, "
            f"by {fmt(simulated - p.natural_period, 4)} s in all (Eqs. (24)-(25), corrected)"
        ),
    )


@check("period_difference", scenes=fig3_cases, args=("cases",))
def period_difference(claim, ev: Evidence) -> Verdict:
    first, second = (str(c) for c in claim["args"]["cases"])
    a, b = (float(ev.fig3[c]["period"].values[-1]) for c in (first, second))
    return Verdict(
        f"{fmt(abs(a - b), 6)} s ({first}: {fmt(a)} s, {second}: {fmt(b)} s)",
        within(abs(a - b), claim["tolerance"]),
        note="the period depends on the force through the perturbations of Eqs. (24)-(25)",
    )


@check("period_initial_condition", scenes=runs_only)
def period_initial_condition(claim, ev: Evidence) -> Verdict:
    paper, other = group_runs(ev, "paper"), group_runs(ev, "initial_condition")
    for runs in (paper, other):
        if (left := runs_left_regime(runs)) is not None:
            return left
    worst = 0.0
    parts = []
    for i in range(other.sizes["case"]):
        run = other.isel(case=i)
        same_force = np.flatnonzero(paper["F"].values == run["F"].values)
        if not len(same_force):
            continue
        ref = paper.isel(case=same_force[0])
        worst = max(worst, abs(float(run["period"]) - float(ref["period"])))
        parts.append(
            f"F = {fmt(run['F'], 3)} N from x0 = {fmt(run['x0'], 3)} m: "
            f"{fmt(run['period'])} s (from x0 = {fmt(ref['x0'], 3)} m: {fmt(ref['period'])} s)"
        )
    return Verdict("; ".join(parts), within(worst, claim["tolerance"]), note=f"largest difference {fmt(worst, 2)} s")


# --- Sec. 4, Fig. 4 ----------------------------------------------------------------------------


@check("shock_readout", scenes=fig4, law="the impact law v+ = (1 - b) v- (Eq. (A-2))",
       fitted="Fig. 4's force, spring and release")
def shock_readout(claim, ev: Evidence) -> Verdict:
    ds = ev.fig4
    m, b = float(ds["M"]), float(ds["b"])
    vb = ds["velocity_before"].values
    j, e = ds["impulse"].values, ds["energy_dissipated"].values
    if not len(j):
        return Verdict("no impact in the window", False, note="the shock detail holds no impact to read off",
                       paper_value="no number given")
    consistent = np.allclose(j, -b * m * vb, rtol=1e-12, atol=0) and np.allclose(
        e, 0.5 * m * vb**2 * (2 * b - b * b), rtol=1e-12, atol=0
    )
    return Verdict(
        f"{len(j)} impacts in the window: |impulse| {fmt(np.min(np.abs(j)), 4)}-{fmt(np.max(np.abs(j)), 4)} N s, "
        f"energy dissipated {fmt(np.min(e), 4)}-{fmt(np.max(e), 4)} J per impact",
        bool(consistent),
        note=(
            "read off the velocity jump: impulse M (v+ - v-) = -b M v-, energy M v-^2 (2b - b^2)/2; "
            "the figure labels both"
        ),
        paper_value="no number given",
    )


@check("impact_force_step", scenes=fig4, fitted="Fig. 4's force, spring and release")
def impact_force_step(claim, ev: Evidence) -> Verdict:
    """A finite impact force read off the acceleration graph: the step of the sampled acceleration at each impact
    is compared with F/M, the escape wheel's force switching on; the claim holds if some step is not F/M."""
    ds = ev.fig4
    t, a, f = ds["t"].values, ds["acceleration"].values, float(ds["F"]) / float(ds["M"])
    steps = []
    for time in ds["impact_time"].values:
        i = int(np.searchsorted(t, time))  # the sample at the impact; the one before is the largest float below
        steps.append((float(a[i - 1]), float(a[i])))
    worst = max((abs((after - before) - f) / f for before, after in steps), default=0.0)
    return Verdict(
        "; ".join(f"acceleration {fmt(b, 4)} -> {fmt(a_, 4)} m/s^2 at the impact" for b, a_ in steps)
        + f"; F/M = {fmt(f, 4)} m/s^2", bool(steps) and not within(worst, claim["tolerance"]),
        note="an impulsive model has no finite impact force: the impact is a jump of the velocity, and the step the "
             "acceleration graph shows at it is the escape wheel's force F switching on over the impulse zone",
        paper_value="the impact force evaluated from the graph")


# --- Sec. 4, Fig. 5's comparisons between spring constants, at one common force (the panels are run at
# different forces, so they are not compared with each other) -------------------------------------


def common_force_runs(ev: Evidence) -> tuple[dict[float, list[tuple[float, xr.Dataset]]], Verdict | None]:
    """The runs of group ``common_force`` by force, each list ordered by K; or the verdict if a run left
    the regime. The panels of Fig. 5 run at different forces: only runs at one force are compared."""
    runs = group_runs(ev, "common_force")
    if (left := runs_left_regime(runs)) is not None:
        return {}, left
    by_force: dict[float, list] = {}
    for i in range(runs.sizes["case"]):
        run = runs.isel(case=i)
        by_force.setdefault(float(run["F"]), []).append((float(run["K"]), run))
    if any(len(rows) < 2 for rows in by_force.values()):
        raise ValueError("the runs of group 'common_force' must give at least two spring constants at each force")
    return {f: sorted(rows, key=lambda kv: kv[0]) for f, rows in sorted(by_force.items())}, None


NOT_COMPARED = ("the panels of Fig. 5 run at different forces (the configuration's fig5.F), so they are not "
                "compared with each other; each spring constant is run at each force of the figure from the "
                "figure's release and compared at one force")


def _decreasing_in_K(ev: Evidence, value, digits: int, unit: str) -> tuple[bool, str] | Verdict:
    """Whether ``value(run)`` decreases with K at every common force, and the values in words; or the
    verdict on a run that left the regime."""
    by_force, left = common_force_runs(ev)
    if left is not None:
        return left
    holds, parts = [], []
    for force, rows in by_force.items():
        values = [value(run) for _, run in rows]
        holds.append(all(a > b for a, b in zip(values, values[1:])))
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(f"K = {fmt(k, 3)}: {fmt(x, digits)} {unit}"
                                                          for (k, _), x in zip(rows, values)))
    return all(holds), "; ".join(parts)


@check("fig5_amplitude_common_force", scenes=runs_only, args=("definition",))
def fig5_amplitude_common_force(claim, ev: Evidence) -> Verdict:
    """The converged amplitude (:func:`escapement.paper.dynamics_checks.amplitude_of`) decreases with K at each
    common force."""
    found = _decreasing_in_K(ev, lambda run: amplitude_of(run, claim["args"]["definition"]), 5, "m")
    if isinstance(found, Verdict):
        return found
    return Verdict("converged amplitude: " + found[1], found[0], note=NOT_COMPARED)


#: the speeds a "maximum velocity" may be: the columns of the checks dataset
SPEEDS = {"largest_speed": "largest |v| on the limit cycle (exact, from the closed forms of its arcs)",
          "velocity": "velocity before the impact at a1 on the limit cycle"}


@check("fig5_velocity_common_force", scenes=runs_only, args=("speed",))
def fig5_velocity_common_force(claim, ev: Evidence) -> Verdict:
    """The speed ``args: {speed}`` (a key of :data:`SPEEDS`) decreases with K at each common force."""
    speed = claim["args"]["speed"]
    found = _decreasing_in_K(ev, lambda run: float(run[speed]), 6, "m/s")
    if isinstance(found, Verdict):
        return found
    return Verdict(f"{SPEEDS[speed]}: " + found[1], found[0], note=NOT_COMPARED)


@check("fig5_recovery_common_force", scenes=runs_only, args=("measure",))
def fig5_recovery_common_force(claim, ev: Evidence) -> Verdict:
    """The recovery of the velocity before the impact at a1 (:func:`escapement.paper.corrected.velocity_recovery`
    at the converged velocity) is faster for smaller K at each common force, measured (``args: {measure}``) in
    ``seconds``, as a fraction of the ``period`` 2 pi/w, or by the distance covered as a fraction of the limit
    cycle's ``width`` (twice its amplitude)."""
    by_force, left = common_force_runs(ev)
    if left is not None:
        return left
    measure, holds, parts = claim["args"]["measure"], [], []
    unit = {"seconds": "s", "period": "of 2 pi/w", "width": "of the width"}[measure]
    for force, rows in by_force.items():
        values = []
        for k, run in rows:
            p = params_of(run)
            x, time = derived.velocity_recovery(float(run["velocity"]), p)
            values.append((k, {"seconds": time, "period": time / p.natural_period,
                               "width": (x - p.a1) / (2 * float(run["largest_displacement"]))}[measure]))
        holds.append(all(a < b for (_, a), (_, b) in zip(values, values[1:])))
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(f"K = {fmt(k, 3)}: {fmt(v, 4)} {unit}" for k, v in values))
    return Verdict("to regain the velocity before the impact at a1: " + "; ".join(parts), all(holds),
                   note=NOT_COMPARED)
