"""The checks of the claims register on the results of Sec. 4: the Poincare maps of Fig. 3, the
shock detail of Fig. 4 and the phase diagrams of Fig. 5, each read off the datasets of its figure
(and the checks dataset where a claim concerns several runs), with the scenes each reads.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from . import corrected as derived
from .checks import (
    NOT,
    PARTIAL,
    REPRODUCED,
    Evidence,
    Verdict,
    check,
    fig3_all,
    fig3_case,
    fig3_labelled,
    fmt,
    group_runs,
    params_of,
    rel,
    runs_left_regime,
    runs_only,
    within,
)

__all__ = [
    "both_converge",
    "compare_cases",
    "converged_period",
    "convergence_rates",
    "energy_rate",
    "fig5_amplitude_common_force",
    "fig5_converge",
    "fig5_recovery_common_force",
    "fig5_velocity_common_force",
    "period_difference",
    "period_initial_condition",
    "shock_readout",
]


# --- the scenes of the figure checks -----------------------------------------------------------


def fig3_cases(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The two Fig. 3 cases of ``args: {cases: [first, second]}``, in that order."""
    labels = [str(c) for c in claim["args"]["cases"]]
    if len(labels) != 2:
        raise ValueError(f"args 'cases' must name two Fig. 3 cases, not {labels}")
    return {f"Fig. 3 case {c}": fig3_labelled(ev, c) for c in labels}


def fig4(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {"Fig. 4": ev.fig4}


def fig5_all(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {f"Fig. 5 K = {label}": ds for label, ds in ev.fig5.items()}


def _two_cases(claim: Mapping) -> tuple[str, str]:
    first, second = (str(c) for c in claim["args"]["cases"])
    return first, second


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


@check("compare_cases", scenes=fig3_cases, args=("cases", "quantity"))
def compare_cases(claim, ev: Evidence) -> Verdict:
    """The first case of ``cases`` converges to a greater ``quantity`` than the second (``amplitude``: the
    amplitude the Fig. 3 datasets hold, named by their ``amplitude_variable``)."""
    first, second = _two_cases(claim)
    quantity = claim["args"]["quantity"]
    a, b = (float(ds[ds.attrs["amplitude_variable"] if quantity == "amplitude" else quantity].values[-1])
            for ds in (ev.fig3[first], ev.fig3[second]))
    return Verdict(f"{first}: {fmt(a)}, {second}: {fmt(b)}", REPRODUCED if a > b else NOT)


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
    rates, converged = {}, {}
    for k in _two_cases(claim):
        v = ev.fig3[k]["velocity_before_impact"].values
        rates[k] = energy_rate(v)
        converged[k] = int((np.abs(v - v[-1]) <= 1e-6 * abs(v[-1])).argmax()) + 1
    first, second = rates.values()
    return Verdict(
        "rate of convergence of x1^2 per cycle: "
        + ", ".join(f"{k}: {fmt(r, 7)}" for k, r in rates.items())
        + "; cycles to within 1e-6: "
        + ", ".join(f"{k}: {n}" for k, n in converged.items()),
        NOT if abs(first - second) <= claim["tolerance"] else REPRODUCED,
        note=(
            "the map is linear in x1^2, so x1^2 approaches its limit by the factor (1-b)^4 per cycle whatever the "
            "force; the curves differ only in how far they start from the limit"
        ),
    )


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
    first, second = _two_cases(claim)
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


@check("shock_readout", scenes=fig4)
def shock_readout(claim, ev: Evidence) -> Verdict:
    ds = ev.fig4
    m, b = float(ds["M"]), float(ds["b"])
    vb = ds["velocity_before"].values
    j, e = ds["impulse"].values, ds["energy_dissipated"].values
    if not len(j):
        return Verdict("no impact in the window", NOT, note="the shock detail holds no impact to read off",
                       paper_value="no number given")
    consistent = np.allclose(j, -b * m * vb, rtol=1e-12, atol=0) and np.allclose(
        e, 0.5 * m * vb**2 * (2 * b - b * b), rtol=1e-12, atol=0
    )
    return Verdict(
        f"{len(j)} impacts in the window: |impulse| {fmt(np.min(np.abs(j)), 4)}-{fmt(np.max(np.abs(j)), 4)} N s, "
        f"energy dissipated {fmt(np.min(e), 4)}-{fmt(np.max(e), 4)} J per impact",
        REPRODUCED if consistent else NOT,
        note=(
            "read off the velocity jump: impulse M (v+ - v-) = -b M v-, energy M v-^2 (2b - b^2)/2; "
            "the figure labels both"
        ),
        paper_value="no number given",
    )


# --- Sec. 4, Fig. 5 ----------------------------------------------------------------------------


def _fig5_by_K(ev: Evidence) -> list[tuple[float, xr.Dataset]]:
    return sorted(((float(ds["K"]), ds) for ds in ev.fig5.values()), key=lambda kv: kv[0])


@check("fig5_converge", scenes=fig5_all)
def fig5_converge(claim, ev: Evidence) -> Verdict:
    changes = [(k, rel(ds["velocity_before_impact"].values[-1], ds["velocity_before_impact"].values[-2]))
               for k, ds in _fig5_by_K(ev)]
    return Verdict(
        "; ".join(f"K = {fmt(k, 3)}: last change {fmt(c, 2)}" for k, c in changes),
        within(max(c for _, c in changes), claim["tolerance"]),
    )


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


def _order_status(holds: list[bool]) -> str:
    """Reproduced if the order holds at every common force, partially if at some, not if at none."""
    return REPRODUCED if all(holds) else PARTIAL if any(holds) else NOT


NOT_COMPARED = ("the panels of Fig. 5 run at different forces (the configuration's fig5.F), so they are not "
                 "compared with each other; each spring constant is run at each force of the figure from the "
                 "figure's release and compared at one force")


def _decreasing_in_K(ev: Evidence, column: str, digits: int, unit: str) -> tuple[str, str] | Verdict:
    """Whether the runs' ``column`` decreases with K at every common force (a status) and the values in
    words; or the verdict on a run that left the regime."""
    by_force, left = common_force_runs(ev)
    if left is not None:
        return left
    holds, parts = [], []
    for force, rows in by_force.items():
        values = [float(run[column]) for _, run in rows]
        holds.append(all(a > b for a, b in zip(values, values[1:])))
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(f"K = {fmt(k, 3)}: {fmt(x, digits)} {unit}"
                                                          for (k, _), x in zip(rows, values)))
    return _order_status(holds), "; ".join(parts)


@check("fig5_amplitude_common_force", scenes=runs_only)
def fig5_amplitude_common_force(claim, ev: Evidence) -> Verdict:
    """The converged amplitude (the largest displacement of the last cycle) decreases with K at each
    common force."""
    found = _decreasing_in_K(ev, "largest_displacement", 5, "m")
    if isinstance(found, Verdict):
        return found
    status, values = found
    return Verdict("converged amplitude: " + values, status, note=NOT_COMPARED)


@check("fig5_velocity_common_force", scenes=runs_only)
def fig5_velocity_common_force(claim, ev: Evidence) -> Verdict:
    """The largest |v| on the limit cycle (exact, from the arcs) decreases with K at each common force."""
    found = _decreasing_in_K(ev, "largest_speed", 6, "m/s")
    if isinstance(found, Verdict):
        return found
    status, values = found
    return Verdict(
        "largest |v| on the limit cycle: " + values,
        status,
        note=NOT_COMPARED + "; the largest speed is exact, from the closed forms of the last cycle's arcs",
    )


@check("fig5_recovery_common_force", scenes=runs_only)
def fig5_recovery_common_force(claim, ev: Evidence) -> Verdict:
    """The time to regain the velocity before the impact at a1 (:func:`escapement.paper.corrected.velocity_recovery`
    at the converged velocity) grows with K at each common force, in seconds and as a fraction of 2 pi/w."""
    by_force, left = common_force_runs(ev)
    if left is not None:
        return left
    absolute, relative, parts = [], [], []
    for force, rows in by_force.items():
        times = []
        for k, run in rows:
            p = params_of(run)
            _, time = derived.velocity_recovery(float(run["velocity"]), p)
            times.append((k, time, time / p.natural_period))
        absolute.append(all(a[1] < b[1] for a, b in zip(times, times[1:])))
        relative.append(all(a[2] < b[2] for a, b in zip(times, times[1:])))
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(
            f"K = {fmt(k, 3)}: {fmt(t, 4)} s ({fmt(100 * r, 3)}% of 2 pi/w)" for k, t, r in times))
    in_seconds, in_cycles = _order_status(absolute), _order_status(relative)
    statuses = {in_seconds, in_cycles}
    status = REPRODUCED if statuses == {REPRODUCED} else NOT if statuses == {NOT} else PARTIAL
    return Verdict(
        "time to regain the velocity before the impact at a1: " + "; ".join(parts),
        status,
        note=(
            f"{NOT_COMPARED}; smaller K faster in seconds: {in_seconds}, as a fraction of its cycle: {in_cycles}"
        ),
    )
