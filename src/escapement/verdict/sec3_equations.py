"""The checks of Eqs. (2)-(5) and of the words of Sec. 3.3 (the system called linear, the existence and uniqueness
of its solution), against the exact motion; the impact matrix, jump set, impulse set and modes restate the model's law.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..model.automaton import CENTRE_SIGN, Mode
from ..model.events import EventKind
from ..model.parameters import Parameters
from ..paper.corrected import grazing_limit, grazing_release
from .evidence import (COMPLETED, OUTCOMES, Evidence, Verdict, check, each, events_of, fig3_scenes, fmt, params_of,
                       run, successive_ratios, within)

A1, A2, A3, A4 = map(int, EventKind)  # the kinds of event, in the order of a cycle


def arc_invariant_error(p: Parameters, kind, x, v_after, v_before, stiffness: float, free_only: bool) -> float:
    """The largest relative change of ``v**2 + k (x - c)**2`` (``k`` the ``stiffness``) over the arcs between events."""
    sigma, worst = {A1: 1.0, A3: -1.0, A2: 0.0, A4: 0.0}, 0.0
    for i in range(len(kind) - 1):
        s = sigma[int(kind[i])]
        if free_only and s:
            continue
        c = s * p.f / stiffness
        start = v_after[i] ** 2 + stiffness * (x[i] - c) ** 2
        end = v_before[i + 1] ** 2 + stiffness * (x[i + 1] - c) ** 2
        worst = max(worst, abs(end - start) / start)
    return worst


def g_eq3b(p: Parameters, x, v) -> np.ndarray:
    """The second entry of g of Eq. (3b) at the states (x, v): sigma f on S2 of Eq. (5) read as regions, else 0."""
    x, v = np.asarray(x, dtype=float), np.asarray(v, dtype=float)
    mode = np.select([(v > 0) & (x > p.a1) & (x < p.a2), (v < 0) & (x > p.a4) & (x < p.a3)],
                     [int(Mode.ZONE_RIGHT), int(Mode.ZONE_LEFT)], int(Mode.FREE))
    return p.omega2 * np.take(CENTRE_SIGN, mode) * p.zone_offset


def lipschitz_quotients(p: Parameters, x0: float, v0: float, radius: float, n: int = 21) -> tuple[float, float]:
    """Over an ``n`` x ``n`` grid of half-width ``radius`` about (x0, v0): the largest ``|g(y1) - g(y2)|`` and the
    largest ``|h(y1) - h(y2)| / |y1 - y2|``, ``h(y) = A y + g(y)``, the differences taken from the offsets."""
    offset = np.linspace(-radius, radius, n)
    dx, dv = (a.ravel() for a in np.meshgrid(offset, offset))
    ddx, ddv, ddg = (a[:, None] - a[None, :] for a in (dx, dv, g_eq3b(p, x0 + dx, v0 + dv)))
    distance = np.hypot(ddx, ddv)
    apart = distance > 0
    quotient = np.hypot(ddv, -p.omega2 * ddx + ddg)[apart] / distance[apart]
    return float(np.max(np.abs(ddg))), float(np.max(quotient))


def _events(ds) -> tuple:
    """The Fig. 3 dataset's events: kinds, positions, velocities after and before."""
    kind, p = ds["event_kind"].values.astype(int), params_of(ds)
    x = np.select([kind == A1, kind == A2, kind == A3], [p.a1, p.a2, p.a3], p.a4)
    return kind, x, ds["event_velocity_after"].values, ds["event_velocity_before"].values


def _run_events(runs) -> list[dict[str, np.ndarray]]:
    """The events of each of ``runs`` (an event table), up to its last."""
    return [{k: r[f"event_{k}"].values[np.isfinite(r["event_time"].values)] for k in ("time", "kind", "position",
                                                                                   "velocity_before", "velocity_after")}
            for r in each(runs)]


@check(runs=("runs",), args=("entry",))
def state_matrix(claim, ev: Evidence) -> Verdict:
    """The free arcs of each run conserve ``v**2 + k x**2``, ``k`` the entry of A as printed (``omega``) or squared."""
    runs, entry, parts, worst = run(ev, claim["args"]["runs"]), claim["args"]["entry"], [], 0.0
    for r, e in zip(each(runs), _run_events(runs)):
        p = params_of(r)
        error = arc_invariant_error(p, e["kind"].astype(int), e["position"], e["velocity_after"],
                                    e["velocity_before"], p.omega if entry == "omega" else p.omega2, free_only=True)
        worst = max(worst, error)
        parts.append(f"K = {fmt(p.K, 3)} N/m (omega_n = {fmt(p.omega, 4)} rad/s): {fmt(error, 2)}")
    return Verdict(
        f"largest relative change of v^2 + k x^2 along the free arcs, k = omega_n{'' if entry == 'omega' else '^2'}: "
        + "; ".join(parts), within(worst, claim["tolerance"]), paper_value="A = [[0, 1], [-omega_n, 0]]",
        note="x'' = -omega_n^2 x (Eq. (A-1)) conserves v^2 + omega_n^2 x^2; -omega_n in A would give x'' = -omega_n x, "
             "the same motion only where omega_n = 1 rad/s (Fig. 3, K = 1 N/m)")


@check(scenes=fig3_scenes, law="the mode equations x'' + omega_n^2 x = sigma f, Eqs. (A-1), (A-3), (A-5)")
def modes_linear(claim, ev: Evidence) -> Verdict:
    """Each arc between events conserves the energy of its linear mode."""
    worst = max(arc_invariant_error(params_of(ds), *_events(ds), params_of(ds).omega2, free_only=False)
                for ds in ev.fig3.values())
    return Verdict(f"largest relative change of each mode's energy along its arcs {fmt(worst, 2)} (Fig. 3 "
                   f"{', '.join(ev.fig3)})", within(worst, claim["tolerance"]),
                   note="each mode is the linear equation the model integrates (by construction)")


@check(scenes=fig3_scenes, law="the impact law v+ = (1 - b) v- (Eq. (A-2))")
def impact_matrix(claim, ev: Evidence) -> Verdict:
    """The jump of the velocity at every impact is B y = (0, -b xdot)."""
    worst, n = 0.0, 0
    for ds in ev.fig3.values():
        kind, _, after, before = _events(ds)
        at = (kind == A1) | (kind == A3)
        worst = max(worst, float(np.max(np.abs(after[at] - (1 - params_of(ds).b) * before[at]) / np.abs(before[at]))))
        n += int(at.sum())
    return Verdict(f"max relative difference of the velocity jump from -b x' {fmt(worst, 3)} over {n} impacts "
                   f"(Fig. 3 {', '.join(ev.fig3)})", within(worst, claim["tolerance"]),
                   note="the position does not jump", paper_value="B = [[0, 0], [0, -b]]")


@check(scenes=fig3_scenes, law="the solver's impact surfaces, S")
def jump_set(claim, ev: Evidence) -> Verdict:
    """Every impact is on S = {x in {a1, a3}, x xdot < 0}: at a1 moving right (a1 < 0), at a3 moving left."""
    bad = n = 0
    for ds in ev.fig3.values():
        kind, x, _, before = _events(ds)
        at = (kind == A1) | (kind == A3)
        bad += int(np.count_nonzero(x[at] * before[at] >= 0))
        n += int(at.sum())
    return Verdict(f"{n - bad} of {n} impacts with x x' < 0 (Fig. 3 {', '.join(ev.fig3)})", bad == 0,
                   paper_value="S = {y : x in {a1, a3}, x x' < 0}")


@check(scenes=fig3_scenes, law="the impulse after the impact, the solver's reading of S2")
def impulse_sets(claim, ev: Evidence) -> Verdict:
    """The force acts in S2 read literally or after the impact only: the two coincide when events run a1, a2, a3, a4."""
    kinds = [ds["event_kind"].values.astype(int) for ds in ev.fig3.values()]
    # each case's events from its first on, the kinds 1 (a1) .. 4 (a4) in turn
    broken = sum(int(np.count_nonzero(k != (k[0] - 1 + np.arange(len(k))) % 4 + 1)) for k in kinds)
    n = sum(len(k) for k in kinds)
    return Verdict(f"{n - broken} of {n} events in the order a1, a2, a3, a4 (Fig. 3 {', '.join(ev.fig3)})",
                   broken == 0, note="each zone is entered only through its impact, so S2 read as a region of the "
                   "state space and read as 'after the impact' give the same motion in these runs",
                   paper_value="S2 = {x in (a1, a2), x' > 0} u {x in (a4, a3), x' < 0}")


@check(scenes=fig3_scenes)
def complement_sets(claim, ev: Evidence) -> Verdict:
    """Every state of the motion (the events' and the turning points) lies in S (4) or in S1 u S2 (5)."""
    missed = n = 0
    for ds in ev.fig3.values():
        p, (kind, x, _, v) = params_of(ds), _events(ds)
        in_s = ((x == p.a1) | (x == p.a3)) & (x * v < 0)
        in_s1 = ((v > 0) & ((x < p.a1) | (x > p.a2))) | ((v < 0) & ((x > p.a3) | (x < p.a4)))
        in_s2 = g_eq3b(p, x, v) != 0
        missed += int(np.count_nonzero(~(in_s | in_s1 | in_s2)))
        n += len(kind)
    turning = sum(2 * ds.sizes["cycle"] for ds in ev.fig3.values())
    return Verdict(f"{missed} of {n} event states in none of S, S1, S2 (the ends of the impulse zones, x = a2 moving "
                   f"right and x = a4 moving left), and the {turning} turning points (xdot = 0) of the cycles "
                   f"(Fig. 3 {', '.join(ev.fig3)})", missed == 0 and turning == 0,
                   note="S1 and S2 leave out x = a2 and x = a4 and every state at rest, so S u S1 u S2 is not the "
                        "state space", paper_value="S-bar = S1 u S2")


@check(runs=("runs",))
def autonomous(claim, ev: Evidence) -> Verdict:
    """g is a function of time alone when the runs (one system, two releases) switch the force on at the same times."""
    runs = run(ev, claim["args"]["runs"])
    starts = [e["time"][(e["kind"] == A1) | (e["kind"] == A3)][:4] for e in _run_events(runs)]
    worst = float(np.max(np.abs(starts[0] - starts[1])))
    switched = [f"{', '.join(fmt(t, 5) for t in s)} s (released at {fmt(x0, 3)} m)"
                for s, x0 in zip(starts, runs["x0"].values)]
    return Verdict("the force switches on at t = " + "; ".join(switched), within(worst, claim["tolerance"]),
                   note="the force acts where the state is (after the impact, in the zones), not at given times: g "
                        "depends on the state and the system is autonomous, as the theorem of Eq. (6) and mu1 = 1 need",
                   paper_value="A(t), g(t) functions of time")


@check(scenes=fig3_scenes, args=("at",),
       law="A of Eq. (3a) with omega_n^2 and g of Eq. (3b) on the sets of Eq. (5), which the model's modes restate")
def lipschitz_near(claim, ev: Evidence) -> Verdict:
    """A y + g is Lipschitz near y0 in each Fig. 3 case (g constant, the largest quotient ||A||), y0 the release
    (``at: release``) or the end of the zone (a1, a2) on the last cycle (``at: zone_end``, half-widths ``radii``)."""
    at, parts, holds = claim["args"]["at"], [], True
    if at not in ("release", "zone_end"):
        raise ValueError(f"at = {at!r} must be release or zone_end")
    for label, ds in ev.fig3.items():
        p = params_of(ds)
        norm = max(1.0, p.omega2)
        if at == "release":
            y0 = (float(ds["x0"]), 0.0)
            reach = min(max(lo - y0[0], y0[0] - hi, 0.0) for lo, hi in [(p.a1, p.a2), (p.a4, p.a3)])
            radii = [reach * (1 - 1e-9)] if reach > 0 else [1e-2, 1e-4, 1e-6]
        else:
            y0 = (p.a2, float(ds["event_velocity_before"].values[events_of(ds, EventKind.ZONE_END_A2)[-1]]))
            radii = [float(r) for r in claim["args"].get("radii", (1e-2, 1e-4, 1e-6))]
        found = [(r, *lipschitz_quotients(p, *y0, r)) for r in radii]
        holds &= all(jump == 0.0 and q <= norm * (1 + claim["tolerance"]) for _, jump, q in found)
        parts.append(f"case {label}, y0 = ({fmt(y0[0], 6)} m, {fmt(y0[1], 6)} m/s): " + "; ".join(
            f"half-width {fmt(r, 3)}: largest |g(y1) - g(y2)| {fmt(jump, 3)} m/s^2, largest quotient {fmt(q, 6)}"
            for r, jump, q in found) + f" (||A|| = {fmt(norm, 6)})")
    return Verdict("; ".join(parts), bool(holds), paper_value="A and g Lipschitz near (t0, y0)", note=(
        "at the end of a zone g jumps by f between states however close, so the quotient grows as 1/half-width: g of "
        "Eq. (3b), switched where x crosses a1 .. a4, is Lipschitz only off those edges" if at == "zone_end" else
        "at the release the state lies outside the impulse zones, so g = 0 on a neighbourhood reaching to them "
        "(closed form, checked on a grid) and A y + g is Lipschitz there with the constant ||A||: the cited theorem "
        "applies up to the first switching of g, which the solution meets only later"))


@check(scenes=fig3_scenes, args=("claim",))
def piecewise_linear(claim, ev: Evidence) -> Verdict:
    """``claim: linear`` holds when the return map is affine in v on the Fig. 3 transients, ``nonlinear`` if not."""
    parts, spread = [], 0.0
    for label, ds in ev.fig3.items():
        in_v, in_v2 = (successive_ratios(ds["velocity_before_impact"].values ** k) for k in (1, 2))
        if len(in_v) < 2:
            raise ValueError(f"Fig. 3 case {label} has fewer than three cycles of transient to measure the map's slope")
        spread = max(spread, float(np.ptp(in_v)))
        parts.append(f"case {label}: slope of the return map {fmt(in_v.min(), 5)} to {fmt(in_v.max(), 5)} over "
                     f"{len(in_v) + 2} transient cycles (ratio in v^2 {fmt(in_v2.min(), 6)} to {fmt(in_v2.max(), 6)})")
    linear = within(spread, claim["tolerance"])
    return Verdict("; ".join(parts), linear if claim["args"]["claim"] == "linear" else not linear, note=(
        f"the return map's slope in v changes by {fmt(spread, 3)} along the transient (an affine map has one slope), "
        "while the map is affine in v^2: the system is piecewise linear, switched at events whose times depend on the "
        "state"))


def grazing_verdict(rows: Sequence[Mapping], limit: float, tolerance: float) -> Verdict:
    """Holds when the run released ``delta`` above the grazing release, at the smallest ``delta``, goes to ``limit``."""
    error = abs(min(rows, key=lambda r: r["delta"])["above"]["v_next"] - limit) / limit  # at the smallest delta
    text = "; ".join(
        f"delta = {fmt(r['delta'], 2)}: from -A(1 + delta) {r['above']['outcome']}"
        + (f", next impact at a1 with {fmt(r['above']['v_next'])} m/s" if math.isfinite(r["above"]["v_next"]) else "")
        + f"; from -A(1 - delta) {r['below']['outcome']}" for r in rows)
    return Verdict(text + f"; the grazing release separates an impact and impulse (next v1 = {fmt(limit)} m/s, "
                   "closed form) from no impact (a free swing of amplitude a3 for ever)", bool(error <= tolerance),
                   paper_value="exactly one solution", note=(
        "with the strict jump set x xdot < 0 a touch of a3 at rest is no impact, in the solver as in the jump set, "
        "and the state has one continuation; the touch comes two swings after the release, on the edge of an "
        "impulse zone, where g of Eq. (3b) switches with the state: releases delta either side of the grazing one "
        "end an O(1) apart however small delta, so the solution does not depend continuously on the release there"))


@check(runs=("runs",), answers=OUTCOMES)
def grazing_uniqueness(claim, ev: Evidence) -> Verdict:
    """The runs released either side of the grazing release A, at -A (1 + offset), paired in the order of the runs."""
    runs = run(ev, claim["args"]["runs"])
    p, offset = params_of(each(runs)[0]), runs["offset"].values
    found = [{"outcome": o, "v_next": float(v)} for o, v in zip(runs["outcome"].values, runs["next_velocity"].values)]
    rows = [{"delta": float(offset[i]), "above": found[i], "below": found[j]}
            for i, j in zip(np.flatnonzero(offset > 0), np.flatnonzero(offset < 0))]
    verdict = grazing_verdict(rows, grazing_limit(p), claim["tolerance"])
    return Verdict(f"grazing release A = {fmt(grazing_release(p))} m (closed form); " + verdict.replicated_value,
                   verdict.holds, note=verdict.note, paper_value=verdict.paper_value)


@check(runs=("runs",), answers=OUTCOMES)
def runs_converge(claim, ev: Evidence) -> Verdict:
    """Every one of the runs reaches a limit cycle: it completes its cycles with |mu2| < 1."""
    group = run(ev, claim["args"]["runs"])
    mu, outcome = group["multiplier"].values, group["outcome"].values
    fine = (outcome == COMPLETED) & (np.abs(mu) < 1)
    failed = "".join(f"; {lab}: {o}" for lab, o in zip(group["label"].values[~fine], outcome[~fine]))
    return Verdict(f"{int(fine.sum())} of {len(fine)} runs converge to a limit cycle (mu2 = {fmt(np.nanmin(mu), 6)} "
                   f"to {fmt(np.nanmax(mu), 6)})" + failed, bool(fine.all()))
