"""The checks of the Poincare map and its stability, Eqs. (7), (8), (16)-(21) and Sec. 3.4, against the simulated
cycles and the runs of the checks dataset."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ..paper import printed as pe
from .evidence import (COMPLETED, Evidence, Verdict, check, each, fig3_scenes, fmt, mu2_off, names, params_of, rel,
                       run, within)


def _printed_map(claim, ev: Evidence, equation: str, formula, note: str = "") -> Verdict:
    """The printed map ``formula`` of Eq. (``equation``) fed each simulated velocity before the impact at a1."""
    worst, pairs = 0.0, 0
    for label, ds in ev.fig3.items():
        p, v = params_of(ds), ds["velocity_before_impact"].values
        if equation == "17" and not (p.a3 == -p.a1 and p.a4 == -p.a2):
            raise ValueError(f"Fig. 3 case {label} is not symmetric (a3 = -a1, a4 = -a2): Eq. (17) does not apply")
        predicted = np.array([formula(float(x), p) for x in v[:-1]])
        worst = max(worst, float(np.max(np.abs(v[1:] - predicted) / predicted)))
        pairs += len(predicted)
    return Verdict(
        f"max relative difference {fmt(worst, 3)} over {pairs} simulated cycle pairs (Fig. 3 {', '.join(ev.fig3)})",
        within(worst, claim["tolerance"]), note=note, paper_value=f"g of Eq. ({equation})")


@check(scenes=fig3_scenes)
def map_eq16(claim, ev: Evidence) -> Verdict:
    return _printed_map(claim, ev, "16", pe.poincare_map_16)


@check(scenes=fig3_scenes)
def map_eq17(claim, ev: Evidence) -> Verdict:
    return _printed_map(claim, ev, "17", pe.poincare_map_17, "read as x1(k+1) = sqrt((1-b)^4 x1(k)^2 + 2 (b^2 - 2b + "
                        "2)(a2 - a1) f), Eq. (16) with a3 = -a1, a4 = -a2")


@check(scenes=fig3_scenes, args=("case",))
def fixed_point(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    formula, simulated = pe.fixed_point_19(params_of(ds)), float(ds["velocity_before_impact"].values[-1])
    n = ds.sizes["cycle"]
    return Verdict(f"{fmt(simulated)} m/s at cycle {n}", within(rel(simulated, formula), claim["tolerance"]),
                   note=f"relative difference {fmt(rel(simulated, formula), 2)}, the transient left after {n} cycles",
                   paper_value=f"{fmt(formula)} m/s")


@check(runs=("runs",))
def multiplier_paper_cases(claim, ev: Evidence) -> Verdict:
    paper = run(ev, claim["args"]["runs"])
    mu = paper["multiplier"].values
    return Verdict(", ".join(f"{label}: {fmt(m)}" for label, m in zip(paper["label"].values, mu)),
                   within(float(np.max(np.abs(mu - float(claim["paper_value"])))), claim["tolerance"]),
                   note="central difference of the simulated return map at the measured fixed point")


@check(runs=("runs",), answers=("chattering",))
def stability_over_b(claim, ev: Evidence) -> Verdict:
    """Every b of the runs converges with mu2 = (1 - b)^4; a run continued past an accumulation is said apart."""
    group = run(ev, claim["args"]["runs"])
    b, stable = group["b"].values, group["outcome"].values == COMPLETED
    ran_on = stable & np.isfinite(group["continued_at"].values if "continued_at" in group else np.nan)
    deviation, said = (mu2_off(group.isel(run=stable)) if stable.any() else math.inf), []
    if (paper := stable & ~ran_on).any():
        said.append(f"converges with mu2 = (1-b)^4 (within {fmt(mu2_off(group.isel(run=paper)), 2)}) for b = "
                    + ", ".join(fmt(x, 3) for x in b[paper]))
    if ran_on.any():
        said.append("continued past the accumulation of impacts, from rest at the impact position, it reaches another "
                    "periodic orbit: " + ", ".join(f"b = {fmt(x, 3)}: {fmt(v, 7)} m/s, mu2 = {fmt(m, 3)} ((1-b)^4 = "
                                                   f"{fmt(q, 4)})" for x, v, m, q in zip(*(group[k].values[ran_on] for k
                                                   in ("b", "velocity", "multiplier", "multiplier_eq21")))))
    if (~stable).any():
        said.append(f"for b = {', '.join(fmt(x, 3) for x in b[~stable])} the impact reverses the velocity and the "
                    "impacts chatter (Zeno): the run stops at their accumulation")
    return Verdict("; ".join(said), bool(stable.all()) and within(deviation, claim["tolerance"]), note=(
        "for b > 1 the impact law v+ = (1-b) v- reverses the velocity; the map (16) squares the sign away, so "
        "|mu2| < 1 there says nothing about the motion, whose impacts accumulate in finite time"))


@check(runs=("runs",))
def multiplier_group(claim, ev: Evidence) -> Verdict:
    """mu2 = (1 - b)^4 in every one of the runs: the rate of convergence depends on nothing else."""
    group = run(ev, claim["args"]["runs"])
    worst, forces = mu2_off(group), sorted(set(group["F"].values.tolist()))
    return Verdict(f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over {group.sizes['run']} runs (F = "
                   f"{', '.join(fmt(f, 3) for f in forces)} N)", within(worst, claim["tolerance"]))


@check(runs=("runs",), answers=("chattering",))
def multiplier_only_b(claim, ev: Evidence) -> Verdict:
    """Sec. 3.4: mu2 = (1 - b)^4 in every run that converges, whatever else differs; every other chatters at b > 1."""
    runs = xr.concat([run(ev, name) for name in names(claim, "runs")], dim="run")
    b, done = runs["b"].values, runs["outcome"].values == COMPLETED
    worst = mu2_off(runs.isel(run=done)) if done.any() else math.inf  # no run converges: nothing follows b
    spans = "; ".join(f"{k} = {fmt(np.min(runs[k].values[done]), 3)} to {fmt(np.max(runs[k].values[done]), 3)}"
                      for k in ("F", "K", "a1", "a3", "x0", "b")) if done.any() else "none converges"
    chatter = sorted(set(b[~done].tolist()))
    return Verdict(
        f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over the {int(done.sum())} runs that converge ({spans}); "
        + (f"the runs at b = {', '.join(fmt(x, 3) for x in chatter)} chatter" if chatter else "none chatters"),
        within(worst, claim["tolerance"]) and bool(np.all(b[~done] > 1)) and not bool(np.any(b[done] > 1)),
        note="mu2 measured from each run's return map: it follows b alone over runs that differ in every other "
             "parameter and in the release; whether the limit cycle exists is another question (Sec. 5)")


@check(runs=("runs",))
def derivative_eq20(claim, ev: Evidence) -> Verdict:
    """The slope of the simulated return map at each run's velocity against Eq. (20) on the run's model."""
    runs = run(ev, claim["args"]["runs"])
    rows = [(float(r["velocity"]), float(r["slope"]), pe.map_derivative_20(float(r["velocity"]), params_of(r)))
            for r in each(runs)]
    worst = max(rel(measured, printed) for _, measured, printed in rows)
    return Verdict("slope of the simulated return map: " + "; ".join(
        f"at {fmt(v, 3)} m/s {fmt(m)} (Eq. (20): {fmt(q)})" for v, m, q in rows), within(worst, claim["tolerance"]),
        note=(f"central differences (relative step {runs['slope'].attrs['relative_step']:g}) of one simulated cycle "
              "from the section, away from the fixed point as well as near it; max relative difference "
              f"{fmt(worst, 2)}"), paper_value="g'(x1) = (1-b)^4 x1 / g(x1)")


@check(runs=("runs",))
def trivial_multiplier(claim, ev: Evidence) -> Verdict:
    """Eq. (8): mu1 = 1. Both Floquet multipliers of the flow over one period against 1 and (1 - b)^4."""
    runs = run(ev, claim["args"]["runs"])
    major, minor, mu21 = (runs[k].values for k in ("floquet_major", "floquet_minor", "multiplier_eq21"))
    worst = float(np.max(np.maximum(np.abs(major - 1.0), np.abs(minor - mu21))))
    worst = worst if math.isfinite(worst) else math.inf
    return Verdict(
        "; ".join(f"{lab}: {fmt(a, 12)} and {fmt(b, 12)}" for lab, a, b in zip(runs["label"].values, major, minor)),
        within(worst, claim["tolerance"]), note=(
            "eigenvalues of the Jacobian of the flow over the last period, by central differences of the exact solver "
            f"from a state in free flight between a2 and a3; largest distance from 1 and (1-b)^4: {fmt(worst, 2)}"))


@check(scenes=fig3_scenes, args=("case",))
def map8_eigenvalues(claim, ev: Evidence) -> Verdict:
    """One of the eigenvalues of the map (8) as printed, at the fixed point of (16), is 1 (within the tolerance)."""
    p = params_of(ev.fig3[claim["args"]["case"]])
    star, step = pe.fixed_point_19(p), 1e-5

    def P(y: np.ndarray) -> np.ndarray:
        return np.array([p.a1, pe.poincare_map_16(float(y[1]), p)])

    y = np.array([p.a1, star])
    jacobian = np.column_stack([(P(y + d) - P(y - d)) / (2 * step * star) for d in np.eye(2) * step * star])
    eigenvalues = np.sort(np.linalg.eigvals(jacobian).real)
    return Verdict(
        f"eigenvalues of the map (8) at the fixed point {fmt(star)} m/s: {', '.join(fmt(e, 8) for e in eigenvalues)}",
        bool(np.any(np.abs(eigenvalues - 1.0) <= claim["tolerance"])), paper_value="Therefore mu1 = 1", note=(
            "P(y) = (a1, g(y2)) does not depend on y1, so its Jacobian is [[0, 0], [0, g']]: the eigenvalues are 0 and "
            "g' = (1 - b)^4; mu1 = 1 is the flow's multiplier along the orbit, which the map on the section does not "
            "have"))


@check(runs=("runs",), args=("sense",))
def phase_shift(claim, ev: Evidence) -> Verdict:
    """Runs from v* and (1 + perturbation) v* end alike in speed (``orbital``) or in impact time (``lyapunov``)."""
    runs = run(ev, claim["args"]["runs"])
    times = [t[np.isfinite(t)] for t in runs["impact_time"].values[:2]]
    speeds, perturbation = runs["speed"].values[:2], float(runs["perturbation"].values[1])
    n = min(len(t) for t in times)
    shift, gap = float(times[1][n - 1] - times[0][n - 1]), abs(speeds[1] - speeds[0]) / speeds[0]
    return Verdict(
        f"after {n} impacts at a1: speeds {fmt(speeds[0])} and {fmt(speeds[1])} m/s (relative difference "
        f"{fmt(gap, 2)}), impact times {fmt(shift, 4)} s apart (first impact {fmt(times[1][0] - times[0][0], 4)} s)",
        within(gap if claim["args"]["sense"] == "orbital" else abs(shift), claim["tolerance"]),
        note=f"the speed at the section perturbed by {fmt(100 * perturbation, 3)} %: the motion returns to the limit "
             "cycle (orbital stability) but keeps a phase shift, as any autonomous oscillator does, so it does not "
             "return to the solution it started beside (no asymptotic stability in the sense of Lyapunov)",
        paper_value="the solution is asymptotically stable")


@check(runs=("runs",))
def section_crossings(claim, ev: Evidence) -> Verdict:
    runs = run(ev, claim["args"]["runs"])
    rows = [(str(r["case"].values), r["crossings"].values) for r in each(runs)]
    rows = [(label, counts[np.isfinite(counts)].astype(int)) for label, counts in rows]
    if any(not len(counts) for _, counts in rows):
        raise ValueError("a Fig. 3 run holds no complete cycle between two impacts at a1")
    return Verdict("; ".join(f"case {label}: {len(c)} cycles, crossings per cycle {int(c.min())}-{int(c.max())}"
                             for label, c in rows), all((counts == 1).all() for _, counts in rows),
                   note=("counted on the exact solver's trajectory of each Fig. 3 case, sampled "
                         f"{runs['samples_per_period'].values[0]} times per natural period (x rising through a1 with "
                         "xdot > 0), between successive impacts at a1; the one crossing is the impact itself, which "
                         "maps (a1, x1) to (a1, (1-b) x1): both states lie on Sigma, at one instant, and the map (8) "
                         "takes the state before it"), paper_value="one state on Sigma per cycle")
