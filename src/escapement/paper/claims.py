"""The claims register: each of the paper's claims checked against the netCDF outputs.

``workflow/claims.yaml`` lists the claims; each names a registered check (those on the paper's
equations are in :mod:`escapement.paper.checks`, those on its figures below), which computes the
replicated value and decides the status.  :func:`evaluate` gives one row per claim:

* a claim whose scene left the escapement regime (its ``outcome`` is not ``completed``) gets
  ``not_reproduced`` with the scene's outcome message, and its check is not run;
* a check that raises is a defect of the code or of its inputs, never a verdict:
  :func:`evaluate` raises :class:`ClaimError` naming the claim, chained to the original error.

Tolerances and the Fig. 3 case labels come from the register, never from here.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from . import axis_claims  # noqa: F401  (registers the axis claims' check)
from . import corrected as derived
from .checks import (
    CHECKS,
    COMPLETED,
    NOT,
    PARTIAL,
    REPRODUCED,
    STATUSES,
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

__all__ = ["COLUMNS", "STATUSES", "CHECKS", "ClaimError", "Evidence", "Verdict", "evaluate", "fmt", "load_claims"]

COLUMNS = ["claim_id", "source", "statement", "paper_value", "replicated_value", "tolerance", "status", "note"]


class ClaimError(RuntimeError):
    """A check could not compute its verdict on a claim; the message names the claim."""


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
    """The first case of ``cases`` converges to a greater ``quantity`` than the second."""
    first, second = _two_cases(claim)
    a, b = (float(ev.fig3[c][claim["args"]["quantity"]].values[-1]) for c in (first, second))
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
    consistent = np.allclose(j, -b * m * vb, rtol=1e-12) and np.allclose(
        e, 0.5 * m * vb**2 * (2 * b - b * b), rtol=1e-12
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


@check("fig5_amplitude_order", scenes=fig5_all)
def fig5_amplitude_order(claim, ev: Evidence) -> Verdict:
    amps = [(k, float(ds["amplitude"].values[-1])) for k, ds in _fig5_by_K(ev)]
    decreasing = all(a1 > a2 for (_, a1), (_, a2) in zip(amps, amps[1:]))
    return Verdict("; ".join(f"K = {fmt(k, 3)}: {fmt(a, 5)} m" for k, a in amps), REPRODUCED if decreasing else NOT)


@check("fig5_velocity_order", scenes=fig5_all)
def fig5_velocity_order(claim, ev: Evidence) -> Verdict:
    rows = []
    for k, ds in _fig5_by_K(ev):
        start = float(ds["impact_time"].values[-1] - ds["period"].values[-1])
        last = ds["velocity"].values[ds["t"].values >= start]
        rows.append((k, float(np.nanmax(np.abs(last))), float(np.nanmax(np.abs(ds["velocity"].values)))))
    decreasing = all(r1[1] > r2[1] for r1, r2 in zip(rows, rows[1:]))
    return Verdict(
        "max |v| on the limit cycle: " + "; ".join(f"K = {fmt(k, 3)}: {fmt(v, 4)} m/s" for k, v, _ in rows)
        + "; over the whole run: " + "; ".join(f"K = {fmt(k, 3)}: {fmt(w, 4)} m/s" for k, _, w in rows),
        REPRODUCED if decreasing else NOT,
        note="sampled at the configured resolution; the order holds neither on the limit cycle nor over the run",
    )


@check("fig5_recovery", scenes=fig5_all)
def fig5_recovery(claim, ev: Evidence) -> Verdict:
    rows = []
    for k, ds in _fig5_by_K(ev):
        p = params_of(ds)
        _, time = derived.velocity_recovery(float(ds["velocity_before_impact"].values[-1]), p)
        rows.append((k, time, time / p.natural_period))
    absolute = all(r1[1] < r2[1] for r1, r2 in zip(rows, rows[1:]))
    relative = all(r1[2] < r2[2] for r1, r2 in zip(rows, rows[1:]))
    return Verdict(
        "time to regain the velocity before the impact at a1: "
        + "; ".join(f"K = {fmt(k, 3)}: {fmt(t, 4)} s ({fmt(100 * r, 3)}% of 2 pi/w)" for k, t, r in rows),
        REPRODUCED if absolute and relative else PARTIAL if absolute or relative else NOT,
        note="in absolute time the stiffer spring recovers faster; as a fraction of its cycle the softer one does",
    )


# --- the register ------------------------------------------------------------------------------


def load_claims(path: str | os.PathLike) -> list[dict]:
    """Read and check the register: unique ids, the required keys, a registered check and its args."""
    data = yaml.safe_load(Path(path).read_text())
    claims = data.get("claims") if isinstance(data, dict) else None
    if not isinstance(claims, list) or not claims:
        raise ValueError(f"{path}: expected a mapping with a non-empty list 'claims'")
    seen = set()
    for i, claim in enumerate(claims):
        for key in ("id", "source", "statement", "paper_value", "tolerance", "check"):
            if key not in claim:
                raise ValueError(f"{path}: claim {i} lacks '{key}'")
        if claim["id"] in seen:
            raise ValueError(f"{path}: claim id '{claim['id']}' appears twice")
        seen.add(claim["id"])
        if claim["check"] not in CHECKS:
            raise ValueError(f"{path}: claim '{claim['id']}' names an unknown check '{claim['check']}'")
        claim.setdefault("args", {})
        missing = [a for a in CHECKS[claim["check"]].args if a not in claim["args"]]
        if missing:
            raise ValueError(f"{path}: claim '{claim['id']}' lacks the args {', '.join(missing)} of its check")
    return claims


def left_regime(scene: str, ds: xr.Dataset) -> Verdict:
    """The verdict on a claim whose scene left the escapement regime."""
    outcome, message = ds.attrs["outcome"], ds.attrs["outcome_message"]
    return Verdict(
        f"not evaluated: {scene} left the escapement regime ({outcome})",
        NOT,
        note=f"{scene} ended with outcome '{outcome}': {message}; the claim concerns the escapement regime",
    )


def verdict(claim: Mapping, evidence: Evidence) -> Verdict:
    """The verdict of the claim's check; :class:`ClaimError` naming the claim if the check fails."""
    if claim["check"] not in CHECKS:
        raise ClaimError(f"claim '{claim['id']}' names an unknown check '{claim['check']}'")
    registered = CHECKS[claim["check"]]
    try:
        scenes = registered.scenes(claim, evidence)
        left = [(name, ds) for name, ds in scenes.items() if ds.attrs["outcome"] != COMPLETED]
        result = left_regime(*left[0]) if left else registered.function(claim, evidence)
    except Exception as err:  # re-raised naming the claim: a failing check is never a verdict
        raise ClaimError(
            f"claim '{claim['id']}': check '{registered.name}' failed: {type(err).__name__}: {err}"
        ) from err
    if result.status not in STATUSES:
        raise ClaimError(f"claim '{claim['id']}': check '{registered.name}' returned the status {result.status!r}")
    return result


def evaluate(claims: list[dict], evidence: Evidence) -> list[dict[str, str]]:
    """One row per claim, with exactly the columns of ``COLUMNS``; raises :class:`ClaimError` on a failing check."""
    rows = []
    for claim in claims:
        result = verdict(claim, evidence)
        paper = claim["paper_value"]
        if paper is None:
            paper = result.paper_value or ""
        elif isinstance(paper, list):
            paper = "[" + ", ".join(fmt(x) for x in paper) + "]"
        rows.append(
            {
                "claim_id": claim["id"],
                "source": claim["source"],
                "statement": claim["statement"],
                "paper_value": fmt(paper) if not isinstance(paper, str) else paper,
                "replicated_value": result.replicated_value,
                "tolerance": "" if claim["tolerance"] is None else fmt(claim["tolerance"]),
                "status": result.status,
                "note": result.note,
            }
        )
    return rows
