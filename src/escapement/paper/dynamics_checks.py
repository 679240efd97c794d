"""The checks of the claims register on the paper's statements about the dynamics that no equation
states: the period set by the spring and changed by the impacts and impulses (Sec. 2), the system
called linear (Sec. 3.3) and nonlinear (Sec. 5), the Floquet multipliers of the flow (Eq. (8)), the
amplitude determined by and growing with the force, and the period against the release (Sec. 4); each measured
from the simulation (the Fig. 3 datasets and the runs of the checks dataset).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import xarray as xr

from ..model.events import EventKind
from .checks import (Evidence, Verdict, check, events_of, fig3_all, fig3_case, fmt, group_runs, params_of,
                     runs_left_regime, runs_only, within)

__all__ = ["phase_shares"]


def phase_shares(ds: xr.Dataset) -> dict[str, float]:
    """The last cycle's period split by the sine phase ``phi = atan2(x, v/w)`` of the simulated states.

    In free flight ``phi`` advances at exactly ``w``; over one cycle of the limit cycle it advances by
    ``2 pi`` in all, so ``T = 2 pi/w + impacts + impulses + drift`` with ``impacts`` the phase lost at the two
    impacts over ``w`` (a delay), ``impulses`` each zone's time less its phase advance over ``w``, and
    ``drift`` the phase the cycle's end state lacks from its start state over ``w`` (0 on the limit
    cycle). Every term is read off the simulated events (positions, velocities before and after, times);
    ``residual`` is the simulated period less the sum, which measures how far the free flight of the
    simulation advances the phase at ``w``.
    """
    p = params_of(ds)
    w = p.omega
    t, x = ds["event_time"].values, ds["event_position"].values
    before, after = ds["event_velocity_before"].values, ds["event_velocity_after"].values
    start = events_of(ds, EventKind.IMPACT_A1)[-2]
    if list(ds["event_kind"].values[start:start + 5]) != [1, 2, 3, 4, 1]:
        raise ValueError("the last cycle's events must be a1, a2, a3, a4, a1")

    def phase(i: int, v: float) -> float:
        return math.atan2(x[i], v / w)

    def turned(a: float, b: float) -> float:
        """The phase from ``a`` to ``b``, in (-pi, pi]."""
        return math.pi - (math.pi - (b - a)) % (2 * math.pi)

    # an impact slows the motion at a fixed position: the phase steps back (a delay)
    impacts = sum(turned(phase(i, after[i]), phase(i, before[i])) for i in (start, start + 2)) / w
    impulses = sum((t[i + 1] - t[i]) - turned(phase(i, after[i]), phase(i + 1, before[i + 1])) / w
                   for i in (start, start + 2))
    end = start + 4
    drift = turned(phase(start, before[start]), phase(end, before[end])) / w
    period = t[end] - t[start]
    return {"period": period, "natural": p.natural_period, "impacts": float(impacts), "impulses": float(impulses),
            "drift": drift, "residual": period - (p.natural_period + impacts + impulses + drift)}


def _shares_text(s: dict, case: str) -> str:
    change = s["period"] - s["natural"]
    return (f"T = {fmt(s['period'])} s against 2 pi/w = {fmt(s['natural'])} s (case {case}, last cycle): "
            f"{fmt(change, 4)} s ({fmt(100 * change / s['natural'], 3)}%), of which the impacts "
            f"{fmt(s['impacts'], 4)} s and the impulses {fmt(s['impulses'], 4)} s")


@check("period_mainly_spring", scenes=fig3_case, args=("case",),
       threshold="'mainly determined' taken as a period within the tolerance of 2 pi sqrt(M/K)")
def period_mainly_spring(claim, ev: Evidence) -> Verdict:
    """Sec. 2: the period is mainly set by the spring: ``|T - 2 pi/w| / (2 pi/w)`` within the tolerance."""
    s = phase_shares(ev.fig3[claim["args"]["case"]])
    return Verdict(_shares_text(s, claim["args"]["case"]),
                   within(abs(s["period"] - s["natural"]) / s["natural"], claim["tolerance"]))


@check("period_shares", scenes=fig3_case, args=("case",))
def period_shares(claim, ev: Evidence) -> Verdict:
    """Sec. 2: the period is changed by the impacts and by the impulses, each by a share measured from the
    simulated phases, both far above what the measurement leaves unexplained."""
    s = phase_shares(ev.fig3[claim["args"]["case"]])
    both = bool(abs(s["impacts"]) > 1e3 * abs(s["residual"]) and abs(s["impulses"]) > 1e3 * abs(s["residual"]))
    return Verdict(
        _shares_text(s, claim["args"]["case"]), both,
        note=(
            "measured from the simulated events: the jump of the sine phase atan2(x, v/w) at each impact (a delay) "
            "and each zone's time less its phase advance (an advance); the free flight advances the phase at w, "
            f"so the shares and the cycle's phase drift {fmt(s['drift'], 2)} s sum to the simulated period within "
            f"{fmt(s['residual'], 2)} s"
        ),
    )


def _successive_ratios(values: np.ndarray) -> np.ndarray:
    """``(u[k+2] - u[k+1]) / (u[k+1] - u[k])`` where both differences are well above rounding (1e-7 of u)."""
    d = np.diff(values)
    usable = (np.abs(d[:-1]) > 1e-7 * np.abs(values[-1])) & (np.abs(d[1:]) > 1e-7 * np.abs(values[-1]))
    return d[1:][usable] / d[:-1][usable]


@check("piecewise_linear", scenes=fig3_all, args=("claim",))
def piecewise_linear(claim, ev: Evidence) -> Verdict:
    """The whole system is linear only if its return map is affine in v, whose successive differences then
    shrink by one constant ratio, its slope: the ratios measured on the Fig. 3 transients are compared, and a
    spread beyond the tolerance shows the whole is not linear. ``args: {claim: linear}`` holds when the spread is
    within the tolerance, ``nonlinear`` when it is beyond."""
    parts, spread = [], 0.0
    for label, ds in ev.fig3.items():
        v = ds["velocity_before_impact"].values
        in_v, in_v2 = _successive_ratios(v), _successive_ratios(v**2)
        if len(in_v) < 2:
            raise ValueError(f"Fig. 3 case {label} has fewer than three cycles of transient to measure the map's slope")
        spread = max(spread, float(np.ptp(in_v)))
        parts.append(f"case {label}: slope of the return map {fmt(in_v.min(), 5)} to {fmt(in_v.max(), 5)} over "
                     f"{len(in_v) + 2} transient cycles (ratio in v^2 {fmt(in_v2.min(), 6)} to {fmt(in_v2.max(), 6)})")
    linear = within(spread, claim["tolerance"])
    return Verdict(
        "; ".join(parts), linear if claim["args"]["claim"] == "linear" else not linear,
        note=(f"the return map's slope in v changes by {fmt(spread, 3)} along the transient (an affine map has one "
              "slope), while the map is affine in v^2: the system is piecewise linear, switched at events whose times "
              "depend on the state"),
    )


@check("trivial_multiplier", scenes=runs_only, args=("group",))
def trivial_multiplier(claim, ev: Evidence) -> Verdict:
    """Eq. (8): mu1 = 1. Both Floquet multipliers measured from the flow over one period (checks dataset,
    ``floquet_major``, ``floquet_minor``) against 1 and (1 - b)^4, independent of the return map."""
    runs = group_runs(ev, claim["args"]["group"])
    if (left := runs_left_regime(runs)) is not None:
        return left
    major, minor, mu21 = (runs[k].values for k in ("floquet_major", "floquet_minor", "multiplier_eq21"))
    worst = float(np.max(np.maximum(np.abs(major - 1.0), np.abs(minor - mu21))))
    if not math.isfinite(worst):
        worst = math.inf
    return Verdict(
        "; ".join(f"{lab}: {fmt(a, 12)} and {fmt(b, 12)}" for lab, a, b in zip(runs["label"].values, major, minor)),
        within(worst, claim["tolerance"]),
        note=(
            f"eigenvalues of the Jacobian of the flow over the last period, by central differences of the exact "
            f"solver from a state in free flight between a2 and a3; largest distance from 1 and (1-b)^4: "
            f"{fmt(worst, 2)}"
        ),
    )


def _families(runs: xr.Dataset, varying: str) -> dict[tuple, list[int]]:
    """The runs' indices grouped by every parameter and the release except ``varying``."""
    keys = [k for k in ("M", "K", "F", "b", "a1", "a2", "a3", "a4", "x0") if k != varying]
    families: dict[tuple, list[int]] = {}
    for i in range(runs.sizes["case"]):
        families.setdefault(tuple(float(runs[k].values[i]) for k in keys), []).append(i)
    return {key: rows for key, rows in families.items() if len(rows) > 1}


def amplitude_of(run, definition: str) -> float:
    """A run's converged amplitude: the largest displacement of its last cycle (``largest x``), or the Step-1
    amplitude ``h0 = sqrt(a1**2 + (v/w)**2)`` of the free arc that ends in the impact at a1 (``h0``)."""
    if definition == "largest x":
        return float(run["largest_displacement"])
    if definition == "h0":
        return float(np.hypot(float(run["a1"]), float(run["velocity"]) / np.sqrt(float(run["K"]) / float(run["M"]))))
    raise ValueError(f"no amplitude is defined as {definition!r}; known: largest x, h0")


@check("force_amplitude", scenes=runs_only, args=("groups", "definition"))
def force_amplitude(claim, ev: Evidence) -> Verdict:
    """Sec. 4, "the system with greater force has greater amplitude": within each family of runs that
    differ only in F, the converged amplitude grows with F."""
    holds, parts = [], []
    definition = claim["args"]["definition"]
    for group in claim["args"]["groups"]:
        runs = group_runs(ev, group)
        if (left := runs_left_regime(runs)) is not None:
            return left
        for rows in _families(runs, "F").values():
            order = sorted(rows, key=lambda i: float(runs["F"].values[i]))
            amplitude = [amplitude_of(runs.isel(case=i), definition) for i in order]
            holds.append(all(a < b for a, b in zip(amplitude, amplitude[1:])))
            parts.append(f"{group} (a1 = {fmt(runs['a1'].values[order[0]], 3)} m): " + ", ".join(
                f"F = {fmt(runs['F'].values[i], 3)} N: {fmt(a, 5)} m" for i, a in zip(order, amplitude)))
    if not holds:
        raise ValueError(f"the groups {claim['args']['groups']} hold no runs that differ only in F")
    return Verdict("; ".join(parts), all(holds), note=f"converged amplitude ({definition}) of runs that differ only "
                   "in the force")


@check("amplitude_by_force", scenes=runs_only, args=("by_force", "by_release", "definition"))
def amplitude_by_force(claim, ev: Evidence) -> Verdict:
    """Sec. 4, the converged amplitude "also determined by the external force": runs that differ only in F (groups
    ``by_force``) converge to amplitudes apart by more than the tolerance (relative), runs that differ only in the
    release (the groups ``by_release`` together) to amplitudes within it."""
    definition, parts, holds = claim["args"]["definition"], [], []
    tolerance = claim["tolerance"]
    for key, groups in (("F", claim["args"]["by_force"]), ("x0", claim["args"]["by_release"])):
        runs = xr.concat([group_runs(ev, g) for g in groups], dim="case")
        if (left := runs_left_regime(runs)) is not None:
            return left
        families = _families(runs, key)
        if not families:
            raise ValueError(f"the groups {groups} hold no runs that differ only in {key}")
        for rows in families.values():
            by = {float(runs[key].values[i]): amplitude_of(runs.isel(case=i), definition) for i in rows}
            values = np.array(list(by.values()))
            spread = float(np.ptp(values) / np.max(np.abs(values)))
            closest = min((abs(a - b) / max(abs(a), abs(b)) for a, b in itertools.combinations(values, 2)),
                          default=math.inf)
            holds.append(closest > tolerance if key == "F" else spread <= tolerance)
            first = runs.isel(case=rows[0])
            fixed = "x0" if key == "F" else "F"
            parts.append(f"{first['group'].values} (a1 = {fmt(first['a1'].values, 3)} m, {fixed} = "
                         f"{fmt(first[fixed].values, 3)}): {key} = "
                         + ", ".join(f"{fmt(k, 3)}: {fmt(a, 8)} m" for k, a in sorted(by.items()))
                         + (f" (closest relative difference {fmt(closest, 2)})" if key == "F" else
                            f" (spread {fmt(spread, 2)})"))
    return Verdict("; ".join(parts), all(holds), note=(
        f"converged amplitude ({definition}) of runs that differ only in the force, then only in the release: it "
        "changes with F and not with x0, at one escapement (it depends on the positions and on K too)"))


@check("release_transient", scenes=runs_only, args=("group",))
def release_transient(claim, ev: Evidence) -> Verdict:
    """Sec. 4: the period of every cycle, the first too, is independent of the release, among runs that differ
    only in x0: the first cycles' periods within the tolerance (s) of each other."""
    runs = group_runs(ev, claim["args"]["group"])
    if (left := runs_left_regime(runs)) is not None:
        return left
    families = _families(runs, "x0")
    if not families:
        raise ValueError(f"group '{claim['args']['group']}' holds no runs that differ only in x0")
    first_spread, parts = 0.0, []
    for rows in families.values():
        first, last = runs["first_period"].values[rows], runs["period"].values[rows]
        first_spread = max(first_spread, float(np.ptp(first)))
        parts.append(", ".join(f"x0 = {fmt(runs['x0'].values[i], 3)} m: first {fmt(a, 7)} s, last {fmt(b, 10)} s"
                               for i, a, b in zip(rows, first, last)))
    return Verdict(f"first periods spread {fmt(first_spread, 3)} s: " + "; ".join(parts),
                   within(first_spread, claim["tolerance"]),
                   note="periods of the first and the last cycle of runs at one force that differ only in the release")
