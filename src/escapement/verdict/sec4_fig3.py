"""The checks of Sec. 4 on Fig. 3 and of its sentences that name no figure, read off the Fig. 3 datasets and the
runs of the checks dataset."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..paper.corrected import map_constant
from .evidence import (COMPLETED, OUTCOMES, Evidence, Verdict, check, each, events_of, fig3_scenes, fmt, names,
                       params_of, rel, run, successive_ratios, within)


@check(scenes=fig3_scenes)
def both_converge(claim, ev: Evidence) -> Verdict:
    """Each motion contracts: every change of x1^2 from one cycle to the next is smaller than the one before it."""
    parts = []
    for k, ds in ev.fig3.items():
        u = ds["velocity_before_impact"].values ** 2
        if len(u) < 3:
            raise ValueError(f"Fig. 3 case {k} has {len(u)} cycles: a contraction needs 3 or more (fig3: n_cycles)")
        d = np.abs(np.diff(u))
        ratio = np.divide(d[1:], d[:-1], out=np.full(len(d) - 1, np.inf), where=d[:-1] > 0)
        parts.append((bool(ratio.max() < 1), f"case {k}: ratio of successive changes of x1^2 {fmt(ratio.min(), 7)} to "
                      f"{fmt(ratio.max(), 7)} over {len(u)} cycles ((1 - b)^4 = {fmt((1 - params_of(ds).b) ** 4, 7)}), "
                      f"the smallest change {fmt(d.min() / u.max(), 2)} of the largest x1^2"))
    return Verdict("; ".join(text for _, text in parts), all(h for h, _ in parts), note=(
        "converging read as contracting, |d(k+1)/d(k)| < 1 at every cycle: no threshold of the project's; the map "
        "(16) is linear in x1^2, so the ratio is (1 - b)^4 (Eq. (21)) at every cycle; a double rounds at 1e-16"))


def converged_amplitudes(ds: xr.Dataset) -> dict[str, float]:
    """The last cycle's amplitude from its events: the Step-1 ``h0`` and the right and left turning points."""
    p, before = params_of(ds), ds["event_velocity_before"].values
    v2, v5 = (before[events_of(ds, kind)[-1]] for kind in (EventKind.ZONE_END_A2, EventKind.ZONE_END_A4))
    return {"h0": float(np.hypot(p.a1, ds["velocity_before_impact"].values[-1] / p.omega)),
            "right turning point": float(np.hypot(p.a2, v2 / p.omega)),
            "left turning point": float(np.hypot(p.a4, v5 / p.omega))}


@check(scenes=fig3_scenes, args=("cases", "quantity"))
def compare_cases(claim, ev: Evidence) -> Verdict:
    """The first case of ``cases`` converges to a greater ``quantity`` (or ``amplitude``) than the second."""
    first, second = (str(c) for c in claim["args"]["cases"])
    quantity = claim["args"]["quantity"]
    a, b = (converged_amplitudes(ds)[claim["args"]["definition"]] if quantity == "amplitude"
            else float(ds[quantity].values[-1]) for ds in (ev.fig3[first], ev.fig3[second]))
    return Verdict(f"{first}: {fmt(a)}, {second}: {fmt(b)}", bool(a > b))


@check(scenes=fig3_scenes, args=("cases",))
def convergence_rates(claim, ev: Evidence) -> Verdict:
    """The asymptotic rates of convergence of x1^2 (median ratios of successive differences) of the two cases differ."""
    rates = {str(k): float(np.median(successive_ratios(ev.fig3[str(k)]["velocity_before_impact"].values ** 2)))
             for k in claim["args"]["cases"]}
    first, second = rates.values()
    return Verdict("rate of convergence of x1^2 per cycle: " + ", ".join(f"{k}: {fmt(r, 7)}" for k, r in rates.items()),
                   not within(abs(first - second), claim["tolerance"]), note=(
        "the map is linear in x1^2, so x1^2 approaches its limit by the factor (1-b)^4 per cycle whatever the force; "
        "x1 itself does not (its ratio of successive differences tends to (1-b)^4 only near the limit)"))


@check(runs=("runs",), threshold="the convergence criterion by which the checks dataset counts the cycles to converge")
def cycles_to_converge(claim, ev: Evidence) -> Verdict:
    """Runs released alike that differ only in F take different numbers of cycles to converge."""
    runs = run(ev, claim["args"]["runs"])
    cycles = runs["cycles_to_converge"].values
    return Verdict(", ".join(f"F = {fmt(f, 3)} N: {int(c)} cycles" for f, c in zip(runs["F"].values, cycles))
                   + f" (released at x0 = {', '.join(sorted({fmt(x, 3) for x in runs['x0'].values}))} m)",
                   len(set(cycles.tolist())) > 1)


@check(scenes=fig3_scenes, args=("case",))
def converged_period(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    p, simulated = params_of(ds), float(ds["period"].values[-1])
    return Verdict(f"{fmt(simulated)} s", within(abs(simulated - float(claim["paper_value"])), claim["tolerance"]),
                   note=f"2 pi/w = {fmt(p.natural_period)} s; the two impacts delay each cycle and the two impulses "
                        f"advance it, by {fmt(simulated - p.natural_period, 4)} s in all (Eqs. (24)-(25), corrected)")


@check(scenes=fig3_scenes, args=("cases",))
def period_difference(claim, ev: Evidence) -> Verdict:
    first, second = (str(c) for c in claim["args"]["cases"])
    a, b = (float(ev.fig3[c]["period"].values[-1]) for c in (first, second))
    return Verdict(f"{fmt(abs(a - b), 6)} s ({first}: {fmt(a)} s, {second}: {fmt(b)} s)",
                   within(abs(a - b), claim["tolerance"]),
                   note="the period depends on the force through the perturbations of Eqs. (24)-(25)")


@check(runs=("runs", "reference"))
def period_initial_condition(claim, ev: Evidence) -> Verdict:
    """Each of the runs at a force of the ``reference`` runs has the period of that one, from another release."""
    paper, worst, parts = run(ev, claim["args"]["reference"]), 0.0, []
    for other in each(run(ev, claim["args"]["runs"])):
        same_force = np.flatnonzero(paper["F"].values == other["F"].values)
        if not len(same_force):
            continue
        ref = paper.isel(run=same_force[0])
        worst = max(worst, abs(float(other["period"]) - float(ref["period"])))
        parts.append(f"F = {fmt(other['F'], 3)} N from x0 = {fmt(other['x0'], 3)} m: {fmt(other['period'])} s (from "
                     f"x0 = {fmt(ref['x0'], 3)} m: {fmt(ref['period'])} s)")
    return Verdict("; ".join(parts), within(worst, claim["tolerance"]), note=f"largest difference {fmt(worst, 2)} s")


@check(scenes=fig3_scenes)
def natural_period(claim, ev: Evidence) -> Verdict:
    rows = [(label, float(ds["period"].values[-1]), 2 * math.pi * math.sqrt(float(ds["M"]) / float(ds["K"])))
            for label, ds in ev.fig3.items()]
    worst, t0 = max(abs(t - t0) for _, t, t0 in rows), rows[0][2]
    return Verdict("; ".join(f"{label}: {fmt(t)} s ({fmt(t - t0, 4)} s above)" for label, t, t0 in rows)
                   + f"; 2 pi sqrt(M/K) = {fmt(t0)} s", within(worst, claim["tolerance"]),
                   note=("the printed 6.2832 s is 2 pi sqrt(M/K) to its digits; the converged period exceeds it "
                         "because each impact delays the cycle (Eq. (24)) by more than the impulse advances it "
                         "(Eq. (25))"), paper_value=f"2 pi sqrt(M/K) = {fmt(t0)} s")


@check(runs=("runs",), args=("cases", "side"))
def initial_order(claim, ev: Evidence) -> Verdict:
    """The first case of ``cases`` has the smaller first velocity at a1, both released at ``side`` (-1 or +1) |x0|."""
    (a, xa, va), (b, xb, vb) = ((c, float(r["x0"]), float(r["velocity"])) for c in claim["args"]["cases"]
                                for r in each(run(ev, claim["args"]["runs"]))
                                if r["case"] == c and r["side"] == claim["args"]["side"])
    return Verdict(f"first velocity before impact released at {fmt(xa, 3)} m ({a}): {fmt(va, 6)} m/s, at "
                   f"{fmt(xb, 3)} m ({b}): {fmt(vb, 6)} m/s", bool(va < vb),
                   note="the smaller initial amplitude gives the smaller first swing",
                   paper_value=f"({a}) smaller at the beginning")


@check(runs=("runs",))
def stable_velocity_scaling(claim, ev: Evidence) -> Verdict:
    """v* of Eq. (19) in every run: v*/sqrt(F) depends on the geometry, b and M only, not on x0."""
    worst, per_geometry, per_release = 0.0, {}, {}
    for group in (run(ev, name) for name in names(claim, "runs")):
        for i in range(group.sizes["run"]):
            r = {k: float(group[k].values[i]) for k in ("M", "F", "b", "a1", "a2", "a3", "a4", "x0", "velocity")}
            if r["a3"] != -r["a1"] or r["a4"] != -r["a2"]:
                raise ValueError(f"run {group['label'].values[i]} is not symmetric: Eq. (19) does not apply")
            closed = math.sqrt(2 * (r["a2"] - r["a1"]) * r["F"] / (r["M"] * (2 * r["b"] - r["b"] ** 2)))
            worst = max(worst, rel(r["velocity"], closed))
            geometry = (r["a1"], r["a2"], r["b"], r["M"])
            per_geometry.setdefault(geometry, []).append(r["velocity"] / math.sqrt(r["F"]))
            per_release.setdefault((*geometry, r["F"]), []).append((r["x0"], r["velocity"]))
    spread = max(max(v) - min(v) for v in per_geometry.values()) if per_geometry else math.nan
    releases = [f"F = {fmt(key[-1], 3)} N from x0 = " + ", ".join(fmt(x, 3) for x, _ in vs) + " m: "
                + ", ".join(fmt(v) for _, v in vs) + " m/s" for key, vs in per_release.items() if len(vs) > 1]
    return Verdict(
        "v*/sqrt(F): " + "; ".join(
            f"(a1, a2) = ({fmt(g[0], 3)}, {fmt(g[1], 3)}) m: {fmt(min(v), 8)}-{fmt(max(v), 8)} over {len(v)} runs"
            for g, v in per_geometry.items()) + ("; " + "; ".join(releases) if releases else ""),
        within(worst, claim["tolerance"]), paper_value="v* proportional to sqrt(F), independent of x0",
        note=(f"Eq. (19): v* = sqrt(2 (a2 - a1) F / (M (2b - b^2))), proportional to sqrt(F) at fixed geometry and b "
              f"and independent of x0; max relative difference from it {fmt(worst, 2)}, spread of v*/sqrt(F) per "
              f"geometry {fmt(spread, 2)}; it grows as sqrt(a2 - a1) too: 'mainly the force' holds for a given "
              "escapement"))


def _families(runs: xr.Dataset, varying: str) -> dict[tuple, list[int]]:
    """The runs' indices grouped by every parameter and the release except ``varying``."""
    keys, families = [k for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4", "x0") if k != varying], {}
    for i in range(runs.sizes["run"]):
        families.setdefault(tuple(float(runs[k].values[i]) for k in keys), []).append(i)
    return {key: rows for key, rows in families.items() if len(rows) > 1}


def amplitude_of(run, definition: str) -> float:
    """A run's converged amplitude: its last cycle's ``largest x``, or ``h0 = sqrt(a1**2 + (v/w)**2)`` (Step 1)."""
    if definition == "largest x":
        return float(run["largest_displacement"])
    if definition == "h0":
        return float(np.hypot(float(run["a1"]), float(run["velocity"]) / np.sqrt(float(run["K"]) / float(run["M"]))))
    raise ValueError(f"no amplitude is defined as {definition!r}; known: largest x, h0")


@check(runs=("runs",), args=("definition",))
def force_amplitude(claim, ev: Evidence) -> Verdict:
    """Within each family of runs that differ only in F, the converged amplitude grows with F."""
    holds, parts, definition = [], [], claim["args"]["definition"]
    for group in names(claim, "runs"):
        runs = run(ev, group)
        for rows in _families(runs, "F").values():
            order = sorted(rows, key=lambda i: float(runs["F"].values[i]))
            amplitude = [amplitude_of(runs.isel(run=i), definition) for i in order]
            holds.append(all(a < b for a, b in zip(amplitude, amplitude[1:])))
            parts.append(f"{group} (a1 = {fmt(runs['a1'].values[order[0]], 3)} m): " + ", ".join(
                f"F = {fmt(runs['F'].values[i], 3)} N: {fmt(a, 5)} m" for i, a in zip(order, amplitude)))
    if not holds:
        raise ValueError(f"the runs {claim['args']['runs']} hold none that differ only in F")
    return Verdict("; ".join(parts), all(holds),
                   note=f"converged amplitude ({definition}) of runs that differ only in the force")


@check(runs=("by_force", "by_release"), args=("definition",))
def amplitude_by_force(claim, ev: Evidence) -> Verdict:
    """Runs that differ only in F converge to amplitudes apart by more than the tolerance, in x0 to ones within it."""
    definition, parts, holds, tolerance = claim["args"]["definition"], [], [], claim["tolerance"]
    for key, groups in (("F", claim["args"]["by_force"]), ("x0", claim["args"]["by_release"])):
        runs = xr.concat([run(ev, g) for g in groups], dim="run")
        families = _families(runs, key)
        if not families:
            raise ValueError(f"the groups {groups} hold no runs that differ only in {key}")
        for rows in families.values():
            by = {float(runs[key].values[i]): amplitude_of(runs.isel(run=i), definition) for i in rows}
            values = np.array(list(by.values()))
            spread = float(np.ptp(values) / np.max(np.abs(values)))
            closest = min((abs(a - b) / max(abs(a), abs(b)) for a, b in itertools.combinations(values, 2)),
                          default=math.inf)
            holds.append(closest > tolerance if key == "F" else spread <= tolerance)
            first, fixed = runs.isel(run=rows[0]), "x0" if key == "F" else "F"
            parts.append(f"{first['group'].values} (a1 = {fmt(first['a1'].values, 3)} m, {fixed} = "
                         f"{fmt(first[fixed].values, 3)}): {key} = "
                         + ", ".join(f"{fmt(k, 3)}: {fmt(a, 8)} m" for k, a in sorted(by.items()))
                         + (f" (closest relative difference {fmt(closest, 2)})" if key == "F" else
                            f" (spread {fmt(spread, 2)})"))
    return Verdict("; ".join(parts), all(holds), note=(
        f"converged amplitude ({definition}) of runs that differ only in the force, then only in the release: it "
        "changes with F and not with x0, at one escapement (it depends on the positions and on K too)"))


@check(runs=("runs",))
def release_transient(claim, ev: Evidence) -> Verdict:
    """Among runs that differ only in x0, the first cycles' periods within the tolerance (s) of each other."""
    runs = run(ev, claim["args"]["runs"])
    families = _families(runs, "x0")
    if not families:
        raise ValueError(f"the runs {claim['args']['runs']!r} hold none that differ only in x0")
    first_spread, parts = 0.0, []
    for rows in families.values():
        first, last = runs["first_period"].values[rows], runs["period"].values[rows]
        first_spread = max(first_spread, float(np.ptp(first)))
        parts.append(", ".join(f"x0 = {fmt(runs['x0'].values[i], 3)} m: first {fmt(a, 7)} s, last {fmt(b, 10)} s"
                               for i, a, b in zip(rows, first, last)))
    return Verdict(f"first periods spread {fmt(first_spread, 3)} s: " + "; ".join(parts),
                   within(first_spread, claim["tolerance"]),
                   note="periods of the first and the last cycle of runs at one force that differ only in the release")


def release_verdict(rows: Sequence[Mapping], boundary: float, tolerance: float) -> Verdict:
    """Holds when every release (``rows``: ``x0``, ``outcome``, last ``velocity``) converges to its ``fixed_point``."""

    def converged(r) -> bool:
        return r["outcome"] == COMPLETED and abs(r["velocity"] - r["fixed_point"]) <= tolerance * r["fixed_point"]

    text = "; ".join(
        f"x0 = {fmt(r['x0'], 6)} m: " + (f"converges to {fmt(r['velocity'])} m/s" if converged(r) else r["outcome"])
        for r in rows)
    return Verdict(text, all(converged(r) for r in rows), note=(
        f"from rest at x0 the free swing covers [-|x0|, |x0|] and meets an impact position only if |x0| > "
        f"min(-a1, a3) = {fmt(boundary, 6)} m (closed form); beyond it every release converges to the same fixed "
        f"point (Eq. (19): {fmt(rows[0]['fixed_point'])} m/s), inside it (or exactly on it) the escapement never "
        "starts and the mass swings freely"),
        paper_value="convergence independent of the initial amplitude")


@check(runs=("runs",), answers=OUTCOMES)
def release_boundary(claim, ev: Evidence) -> Verdict:
    """The runs from rest at each release of one model against the closed-form fixed point."""
    runs = run(ev, claim["args"]["runs"])
    p = params_of(each(runs)[0])
    star = math.sqrt(map_constant(p) / (1 - (1 - p.b) ** 4))
    rows = [{"x0": float(r["x0"]), "fixed_point": star, "outcome": str(r["outcome"].values),
             "velocity": float(r["velocity"])} for r in each(runs)]
    found = release_verdict(rows, min(-p.a1, p.a3), claim["tolerance"])
    if "release_force" in runs and set(runs["release_force"].values) == {"eq5"}:  # a release in S2 starts in its zone
        return Verdict(found.replicated_value, found.holds, paper_value=found.paper_value, note=(
            "the force acts on S2 of Eq. (5) as printed from the release on: released at rest inside an impulse zone, "
            "the spring moving it in the zone's direction, the mass starts under the force, elsewhere it swings "
            f"freely to its first impact; the fixed point of Eq. (19) is {fmt(star)} m/s"))
    return found
