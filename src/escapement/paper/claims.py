"""The claims register: each of the paper's claims checked against the netCDF outputs.

``workflow/claims.yaml`` lists the claims; each names a check below, which computes the
replicated value from the datasets (and the paper's closed forms where the claim is a
formula) and decides the status: ``reproduced``, ``partially_reproduced`` or
``not_reproduced``.  Tolerances come from the register, never from here.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from ..io.atomic import write_csv
from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS
from . import corrected as derived
from . import printed as pe

__all__ = ["COLUMNS", "STATUSES", "Evidence", "Verdict", "load_claims", "evaluate", "write_claims_csv", "read_claims_csv"]

COLUMNS = ["claim_id", "source", "statement", "paper_value", "replicated_value", "tolerance", "status", "note"]
STATUSES = ("reproduced", "partially_reproduced", "not_reproduced")
REPRODUCED, PARTIAL, NOT = STATUSES


def fmt(x: float, digits: int = 10) -> str:
    """A number as text, to ``digits`` significant digits (enough to compare, stable across runs)."""
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "nan"
    return f"{float(x):.{digits}g}"


@dataclass(frozen=True)
class Evidence:
    """The datasets the claims are checked against."""

    fig3: Mapping[str, xr.Dataset]
    fig4: xr.Dataset
    fig5: Mapping[str, xr.Dataset]
    checks: xr.Dataset


@dataclass(frozen=True)
class Verdict:
    replicated_value: str
    status: str
    note: str = ""
    paper_value: str | None = None  #: filled when the paper gives a formula rather than a number


def params_of(ds: xr.Dataset) -> Parameters:
    return Parameters(**{k: float(ds.attrs[k]) for k in MODEL_KEYS})


def _events(ds: xr.Dataset, kind: EventKind) -> np.ndarray:
    return np.flatnonzero(ds["event_kind"].values == int(kind))


def _cycle_durations(ds: xr.Dataset) -> dict[str, np.ndarray]:
    """Simulated durations inside each complete cycle: a1 -> a2 -> a3 -> a4 -> a1."""
    t = ds["event_time"].values
    starts = _events(ds, EventKind.IMPACT_A1)[:-1]
    return {
        "zone_right": t[starts + 1] - t[starts],
        "a2_to_a3": t[starts + 2] - t[starts + 1],
        "zone_left": t[starts + 3] - t[starts + 2],
        "a4_to_a1": t[starts + 4] - t[starts + 3],
    }


def _rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def _within(value: float, tolerance: float) -> str:
    return REPRODUCED if value <= tolerance else NOT


# --- the checks --------------------------------------------------------------------------------


def check_map_eq16(claim, ev: Evidence) -> Verdict:
    worst = 0.0
    pairs = 0
    for ds in ev.fig3.values():
        p, v = params_of(ds), ds["velocity_before_impact"].values
        predicted = np.array([pe.poincare_map_16(x, p) for x in v[:-1]])
        worst = max(worst, float(np.max(np.abs(v[1:] - predicted) / predicted)))
        pairs += len(predicted)
    return Verdict(
        f"max relative difference {fmt(worst, 3)} over {pairs} simulated cycle pairs (Fig. 3 a, b)",
        _within(worst, claim["tolerance"]),
        paper_value="g of Eq. (16)",
    )


def check_eq14(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3["a"]
    p = params_of(ds)
    i = _events(ds, EventKind.IMPACT_A1)[-2]
    v1, v5_sim = ds["event_velocity_before"].values[i], ds["event_velocity_before"].values[i + 3]
    printed = pe.step_velocities(v1, p)["v5"]
    corrected = derived.cycle_velocities(v1, p)["v5"]
    return Verdict(
        f"simulated velocity at a4 {fmt(v5_sim)} m/s",
        _within(_rel(printed, v5_sim), claim["tolerance"]),
        note=(
            f"Eq. (14) as printed gives {fmt(printed)} m/s; with +2(a3 - a4) f (the work of the force -f on the "
            f"leftward motion) it gives {fmt(corrected)} m/s (relative difference {fmt(_rel(corrected, v5_sim), 2)}); "
            "Eq. (16) already has the right sign"
        ),
        paper_value=f"{fmt(printed)} m/s (case a, last cycle)",
    )


def check_fixed_point(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    formula = pe.fixed_point_19(p)
    simulated = float(ds["velocity_before_impact"].values[-1])
    n = ds.sizes["cycle"]
    return Verdict(
        f"{fmt(simulated)} m/s at cycle {n}",
        _within(_rel(simulated, formula), claim["tolerance"]),
        note=f"relative difference {fmt(_rel(simulated, formula), 2)}, the transient left after {n} cycles",
        paper_value=f"{fmt(formula)} m/s",
    )


def _group(ev: Evidence, group: str) -> xr.Dataset:
    return ev.checks.isel(case=np.flatnonzero(ev.checks["group"].values == group))


def check_multiplier_paper_cases(claim, ev: Evidence) -> Verdict:
    paper = _group(ev, "paper")
    mu = paper["multiplier"].values
    worst = float(np.max(np.abs(mu - float(claim["paper_value"]))))
    cases = ", ".join(f"{label}: {fmt(m)}" for label, m in zip(paper["label"].values, mu))
    return Verdict(
        cases,
        _within(worst, claim["tolerance"]),
        note="central difference of the simulated return map at the measured fixed point",
    )


def check_stability_over_b(claim, ev: Evidence) -> Verdict:
    group = _group(ev, "b")
    b, outcome = group["b"].values, group["outcome"].values
    mu, mu21 = group["multiplier"].values, group["multiplier_eq21"].values
    stable = outcome == "completed"
    deviation = float(np.max(np.abs(mu[stable] - mu21[stable]))) if stable.any() else math.nan
    converging = ", ".join(fmt(x, 3) for x in b[stable])
    chattering = ", ".join(fmt(x, 3) for x in b[~stable])
    replicated = f"converges with mu2 = (1-b)^4 (within {fmt(deviation, 2)}) for b = {converging}"
    if (~stable).any():
        replicated += f"; for b = {chattering} the impact reverses the velocity and the impacts chatter (Zeno)"
    if stable.all() and deviation <= claim["tolerance"]:
        status = REPRODUCED
    elif stable.any() and deviation <= claim["tolerance"] and (b[~stable] > 1).all():
        status = PARTIAL
    else:
        status = NOT
    return Verdict(
        replicated,
        status,
        note=(
            "for b > 1 the impact law v+ = (1-b) v- reverses the velocity; the map (16) squares the sign away, "
            "so |mu2| < 1 there says nothing about the motion, whose impacts accumulate in finite time"
        ),
    )


def check_multiplier_group(claim, ev: Evidence) -> Verdict:
    group = _group(ev, claim["args"]["group"])
    mu, mu21 = group["multiplier"].values, group["multiplier_eq21"].values
    completed = group["outcome"].values == "completed"
    worst = float(np.max(np.abs(mu - mu21)))
    forces = sorted(set(group["F"].values.tolist()))
    return Verdict(
        f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over {len(mu)} runs (F = {', '.join(fmt(f, 3) for f in forces)} N "
        f"and {len(mu) // max(len(forces), 1)} geometries)",
        REPRODUCED if completed.all() and worst <= claim["tolerance"] else NOT,
    )


def check_asymmetric_dependence(claim, ev: Evidence) -> Verdict:
    group = _group(ev, "asymmetric")
    mu, mu21 = group["multiplier"].values, group["multiplier_eq21"].values
    worst = float(np.max(np.abs(mu - mu21)))
    v = group["velocity"].values
    independent = worst <= claim["tolerance"]
    return Verdict(
        f"mu2 = (1-b)^4 within {fmt(worst, 2)} in all {len(mu)} asymmetric runs; fixed points "
        f"{fmt(np.min(v), 4)}-{fmt(np.max(v), 4)} m/s",
        NOT if independent else REPRODUCED,
        note=(
            "Eq. (16) is linear in x1^2: g' = (1-b)^4 x1/g(x1) = (1-b)^4 at any fixed point, with or without "
            "symmetry; what depends on F and the positions is the fixed point and whether it exists "
            "(C > 0 in x1^2 = (1-b)^4 x1^2 + C), not the rate of convergence"
        ),
    )


def check_eq22_abcd(claim, ev: Evidence) -> Verdict:
    worst = 0.0
    for ds in ev.fig3.values():
        p = params_of(ds)
        durations = _cycle_durations(ds)
        v = ds["velocity_before_impact"].values
        for k in range(len(durations["zone_right"])):
            h0 = math.hypot(p.a1, v[k] / p.omega)
            times = pe.step_times_22(v[k], p, h0)
            worst = max(worst, _rel(times["22b"], durations["zone_right"][k]))
            worst = max(worst, _rel(times["22c"] + times["22d"], durations["a2_to_a3"][k]))
            if k > 0:  # step 1 ends at the impact of cycle k, after the left swing of cycle k - 1
                left = durations["a4_to_a1"][k - 1] - math.acos(-p.a4 / h0) / p.omega
                worst = max(worst, _rel(times["22a"], left))
    return Verdict(
        f"max relative difference {fmt(worst, 2)} against the simulated step durations (Fig. 3 a, b)",
        _within(worst, claim["tolerance"]),
        note="(22a) is compared with the time from the left turning point to a1",
        paper_value="Eqs. (22a)-(22d)",
    )


def check_eq22e(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3["a"]
    p = params_of(ds)
    v = float(ds["velocity_before_impact"].values[-1])
    printed = pe.step_times_22(v, p, 1.0)["22e"]
    simulated = float(_cycle_durations(ds)["zone_left"][-1])
    return Verdict(
        f"{fmt(simulated)} s (simulated, last cycle of case a)",
        _within(_rel(printed, simulated), claim["tolerance"]),
        note="(22e) needs + acos((a4 + f/w^2)/h3) instead of -: as printed it is negative",
        paper_value=f"{fmt(printed)} s",
    )


def check_eq23(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3["a"]
    p = params_of(ds)
    v = float(ds["velocity_before_impact"].values[-1])
    printed = pe.period_23(v, p)
    simulated = float(ds["period"].values[-1])
    corrected = derived.period(v, p)
    return Verdict(
        f"{fmt(simulated)} s (simulated)",
        _within(_rel(printed, simulated), claim["tolerance"]),
        note=(
            f"with acos(-a4/h5) + acos(-a1/h5) for the last two terms (the left swing passes x = -h5) the formula "
            f"gives {fmt(corrected)} s, relative difference {fmt(_rel(corrected, simulated), 2)}"
        ),
        paper_value=f"{fmt(printed)} s (as printed, signed a1, a4)",
    )


def check_eq24(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3["a"]
    p = params_of(ds)
    v = float(ds["velocity_before_impact"].values[-1])
    first = pe.period_perturbation_24(v, p)
    second = pe.period_perturbation_24_closed(v, p)
    corrected = derived.impact_phase_jump_closed(p.a1, v, p)
    status = PARTIAL if _rel(second, first) > claim["tolerance"] else REPRODUCED
    return Verdict(
        f"first form {fmt(first)} s; second form as printed {fmt(second)} s",
        status,
        note=(
            f"the first form is the phase delay of the impact (it enters the exact period decomposition, see "
            f"eq25); the second equals it only with the velocity before the impact, x1, in place of x1+: "
            f"{fmt(corrected)} s"
        ),
        paper_value="dT1, two equal forms",
    )


def check_eq25(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3["a"]
    p = params_of(ds)
    v = pe.fixed_point_19(p)
    printed = p.natural_period + 2 * (pe.period_perturbation_24(v, p) + pe.period_perturbation_25(v, p))
    corrected = derived.period_from_perturbations(v, p)
    simulated = float(ds["period"].values[-1])
    return Verdict(
        f"{fmt(simulated)} s (simulated)",
        _within(_rel(printed, simulated), claim["tolerance"]),
        note=(
            f"with the phase taken as atan(position/velocity) in (25) (the sine phase, which advances at w in free "
            f"flight), 2 pi/w + 2 (dT1 + dT2) = {fmt(corrected)} s, relative difference "
            f"{fmt(_rel(corrected, simulated), 2)}"
        ),
        paper_value=f"{fmt(printed)} s (as printed)",
    )


def check_both_converge(claim, ev: Evidence) -> Verdict:
    changes = {k: _rel(ds["velocity_before_impact"].values[-1], ds["velocity_before_impact"].values[-2])
               for k, ds in ev.fig3.items()}
    worst = max(changes.values())
    return Verdict(
        "; ".join(f"case {k}: last change {fmt(c, 2)}" for k, c in changes.items()),
        _within(worst, claim["tolerance"]),
        note="relative change of the velocity before impact between the last two cycles",
    )


def check_compare_cases(claim, ev: Evidence) -> Verdict:
    q = claim["args"]["quantity"]
    a, b = (float(ev.fig3[c][q].values[-1]) for c in ("a", "b"))
    return Verdict(f"a: {fmt(a)}, b: {fmt(b)}", REPRODUCED if a > b else NOT)


def _energy_rate(v: np.ndarray) -> float:
    """Rate of convergence of v^2 per cycle, from successive differences: for a map linear in v^2,
    (E[k+2] - E[k+1]) / (E[k+1] - E[k]) is the rate, with no need to know the limit. Only
    differences well above rounding (1e-7 of E) are used."""
    e = v**2
    d = np.diff(e)
    usable = np.flatnonzero((np.abs(d[:-1]) > 1e-7 * e[-1]) & (np.abs(d[1:]) > 1e-7 * e[-1]))
    return float(np.median(d[usable + 1] / d[usable]))


def check_convergence_rates(claim, ev: Evidence) -> Verdict:
    rates = {}
    converged = {}
    for k, ds in ev.fig3.items():
        v = ds["velocity_before_impact"].values
        rates[k] = _energy_rate(v)
        close = np.abs(v - v[-1]) <= 1e-6 * abs(v[-1])
        converged[k] = int(close.argmax()) + 1
    equal = abs(rates["a"] - rates["b"]) <= claim["tolerance"]
    return Verdict(
        "rate of convergence of x1^2 per cycle: "
        + ", ".join(f"{k}: {fmt(r, 7)}" for k, r in rates.items())
        + "; cycles to within 1e-6: "
        + ", ".join(f"{k}: {n}" for k, n in converged.items()),
        NOT if equal else REPRODUCED,
        note=(
            "the map is linear in x1^2, so x1^2 approaches its limit by the factor (1-b)^4 per cycle whatever the "
            "force; the curves differ only in how far they start from the limit"
        ),
    )


def check_converged_period(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p = params_of(ds)
    simulated = float(ds["period"].values[-1])
    return Verdict(
        f"{fmt(simulated)} s",
        _within(abs(simulated - float(claim["paper_value"])), claim["tolerance"]),
        note=(
            f"2 pi/w = {fmt(p.natural_period)} s; the two impacts delay each cycle and the two impulses advance it, "
            f"by {fmt(simulated - p.natural_period, 4)} s in all (Eqs. (24)-(25), corrected)"
        ),
    )


def check_period_difference(claim, ev: Evidence) -> Verdict:
    a, b = (float(ev.fig3[c]["period"].values[-1]) for c in ("a", "b"))
    return Verdict(
        f"{fmt(abs(a - b), 6)} s (a: {fmt(a)} s, b: {fmt(b)} s)",
        _within(abs(a - b), claim["tolerance"]),
        note="the period depends on the force through the perturbations of Eqs. (24)-(25)",
    )


def check_period_initial_condition(claim, ev: Evidence) -> Verdict:
    checks = ev.checks
    paper = _group(ev, "paper")
    worst = 0.0
    parts = []
    for i in np.flatnonzero(checks["group"].values == "initial_condition"):
        same_force = np.flatnonzero(paper["F"].values == checks["F"].values[i])
        if not len(same_force):
            continue
        ref = paper.isel(case=same_force[0])
        diff = abs(float(checks["period"].values[i]) - float(ref["period"]))
        worst = max(worst, diff)
        parts.append(
            f"F = {fmt(checks['F'].values[i], 3)} N from x0 = {fmt(checks['x0'].values[i], 3)} m: "
            f"{fmt(checks['period'].values[i])} s (from x0 = {fmt(ref['x0'], 3)} m: {fmt(ref['period'])} s)"
        )
    return Verdict("; ".join(parts), _within(worst, claim["tolerance"]), note=f"largest difference {fmt(worst, 2)} s")


def check_axis_range(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    values = ds[claim["args"]["quantity"]].values
    lo, hi = claim["paper_value"]
    vmin, vmax = float(np.min(values)), float(np.max(values))
    inside = lo <= vmin and vmax <= hi
    return Verdict(f"[{fmt(vmin, 6)}, {fmt(vmax, 6)}]", REPRODUCED if inside else NOT,
                   note="range of the simulated curve over the plotted cycles")


def check_shock_readout(claim, ev: Evidence) -> Verdict:
    ds = ev.fig4
    m, b = float(ds.attrs["M"]), float(ds.attrs["b"])
    vb = ds["velocity_before"].values
    j, e = ds["impulse"].values, ds["energy_dissipated"].values
    consistent = np.allclose(j, -b * m * vb, rtol=1e-12) and np.allclose(e, 0.5 * m * vb**2 * (2 * b - b * b), rtol=1e-12)
    return Verdict(
        f"{len(j)} impacts in the window: |impulse| {fmt(np.min(np.abs(j)), 4)}-{fmt(np.max(np.abs(j)), 4)} N s, "
        f"energy dissipated {fmt(np.min(e), 4)}-{fmt(np.max(e), 4)} J per impact",
        REPRODUCED if consistent and len(j) else NOT,
        note="read off the velocity jump: impulse M (v+ - v-) = -b M v-, energy M v-^2 (2b - b^2)/2; the figure labels both",
        paper_value="no number given",
    )


def check_shock_axis(claim, ev: Evidence) -> Verdict:
    ds = ev.fig4
    lo_t, hi_t = ds.attrs[claim["args"]["window"]]
    sel = ds.sel(t=slice(lo_t, hi_t))[claim["args"]["quantity"]].values
    lo, hi = claim["paper_value"]
    vmin, vmax = float(np.nanmin(sel)), float(np.nanmax(sel))
    return Verdict(
        f"[{fmt(vmin, 4)}, {fmt(vmax, 4)}]",
        REPRODUCED if lo <= vmin and vmax <= hi else NOT,
        note=(
            f"F = {fmt(ds.attrs['F'], 3)} N, x0 = {fmt(ds.attrs['x0'], 3)} m; in any steady motion the velocity and "
            f"the acceleration swing about 0 within a period (about {fmt(params_of(ds).natural_period, 2)} s), so no "
            f"case fits an axis from {fmt(lo, 2)} to {fmt(hi, 2)} over this window: the printed panel seems to show "
            "part of the swing only"
        ),
    )


def _fig5_sorted(ev: Evidence) -> list[tuple[float, xr.Dataset]]:
    return sorted(((float(ds.attrs["K"]), ds) for ds in ev.fig5.values()), key=lambda kv: kv[0])


def check_fig5_converge(claim, ev: Evidence) -> Verdict:
    changes = [(k, _rel(ds["velocity_before_impact"].values[-1], ds["velocity_before_impact"].values[-2]))
               for k, ds in _fig5_sorted(ev)]
    worst = max(c for _, c in changes)
    return Verdict(
        "; ".join(f"K = {fmt(k, 3)}: last change {fmt(c, 2)}" for k, c in changes),
        _within(worst, claim["tolerance"]),
    )


def check_fig5_amplitude_order(claim, ev: Evidence) -> Verdict:
    amps = [(k, float(ds["amplitude"].values[-1])) for k, ds in _fig5_sorted(ev)]
    decreasing = all(a1 > a2 for (_, a1), (_, a2) in zip(amps, amps[1:]))
    return Verdict("; ".join(f"K = {fmt(k, 3)}: {fmt(a, 5)} m" for k, a in amps), REPRODUCED if decreasing else NOT)


def check_fig5_velocity_order(claim, ev: Evidence) -> Verdict:
    rows = []
    for k, ds in _fig5_sorted(ev):
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


def check_fig5_recovery(claim, ev: Evidence) -> Verdict:
    rows = []
    for k, ds in _fig5_sorted(ev):
        p = params_of(ds)
        _, time = derived.velocity_recovery(float(ds["velocity_before_impact"].values[-1]), p)
        rows.append((k, time, time / p.natural_period))
    absolute = all(r1[1] < r2[1] for r1, r2 in zip(rows, rows[1:]))
    relative = all(r1[2] < r2[2] for r1, r2 in zip(rows, rows[1:]))
    status = REPRODUCED if absolute and relative else PARTIAL if absolute or relative else NOT
    return Verdict(
        "time to regain the velocity before the impact at a1: "
        + "; ".join(f"K = {fmt(k, 3)}: {fmt(t, 4)} s ({fmt(100 * r, 3)}% of 2 pi/w)" for k, t, r in rows),
        status,
        note="in absolute time the stiffer spring recovers faster; as a fraction of its cycle the softer one does",
    )


CHECKS: dict[str, Callable[[Mapping, Evidence], Verdict]] = {
    name.removeprefix("check_"): fn for name, fn in globals().items() if name.startswith("check_")
}


# --- the register ------------------------------------------------------------------------------


def load_claims(path: str | os.PathLike) -> list[dict]:
    """Read and check the register: unique ids, the required keys, a known check."""
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
    return claims


def evaluate(claims: list[dict], evidence: Evidence) -> list[dict[str, str]]:
    """One row per claim, with exactly the columns of ``COLUMNS``."""
    rows = []
    for claim in claims:
        try:
            verdict = CHECKS[claim["check"]](claim, evidence)
        except (IndexError, KeyError, ValueError, ZeroDivisionError) as err:
            # the data cannot answer the claim (for example a scene that left the escapement regime)
            verdict = Verdict("could not be evaluated", NOT, note=f"{type(err).__name__}: {err}; see the scene's outcome")
        if verdict.status not in STATUSES:
            raise ValueError(f"check {claim['check']} returned an unknown status {verdict.status!r}")
        paper = claim["paper_value"]
        if paper is None:
            paper = verdict.paper_value or ""
        elif isinstance(paper, list):
            paper = "[" + ", ".join(fmt(x) for x in paper) + "]"
        rows.append(
            {
                "claim_id": claim["id"],
                "source": claim["source"],
                "statement": claim["statement"],
                "paper_value": fmt(paper) if not isinstance(paper, str) else paper,
                "replicated_value": verdict.replicated_value,
                "tolerance": "" if claim["tolerance"] is None else fmt(claim["tolerance"]),
                "status": verdict.status,
                "note": verdict.note,
            }
        )
    return rows


def write_claims_csv(rows: list[dict[str, str]], path: str | os.PathLike) -> None:
    """Write the table atomically."""
    write_csv(rows, COLUMNS, path)


def read_claims_csv(path: str | os.PathLike) -> list[dict[str, str]]:
    with open(path, newline="") as handle:
        reader = csv.DictReader(handle)
        if reader.fieldnames != COLUMNS:
            raise ValueError(f"{path}: columns {reader.fieldnames} are not {COLUMNS}")
        return list(reader)
