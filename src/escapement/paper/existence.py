"""Checks on where a limit cycle exists and where the solution is unique (Secs. 3.3, 4 and 5).

Each check reads the runs from rest its ``args`` in the register name, made by the checks scene (the
``release`` dimension of the checks dataset), and compares the outcomes with a closed form derived on paper;
the verdict comes from a pure function (``*_verdict``) of the measured numbers, so that the tests can give it
every case.

Closed forms used (derived here, from the map (16), which is right):

* the map is ``v1(k+1)**2 = (1 - b)**4 v1(k)**2 + C`` with
  ``M C = (b**2 - 2b) K (a1**2 - a3**2) + 2 F [(1 - b)**2 (a2 - a1) + (a3 - a4)]``; a fixed point
  (a limit cycle) needs ``C > 0``, i.e. ``F > F* = (2b - b**2) K (a1**2 - a3**2) / (2 [(1 - b)**2
  (a2 - a1) + (a3 - a4)])`` (the bracket is positive since a2 > a1, a3 > a4). In the symmetric case
  ``a1**2 = a3**2``, so ``F* = 0``: a limit cycle for every F > 0. Below F*, ``v1**2`` falls by at least
  ``|C|`` per cycle and the escapement stops after finitely many cycles;
* from rest at ``x0`` the free swing covers ``[-|x0|, |x0|]``: it meets an impact position only if
  ``|x0| > min(-a1, a3)``;
* grazing: released from rest at ``-A`` (``A > -a1``), the mass hits a1 with ``w**2 (A**2 - a1**2)`` as
  squared speed, and after the impulse its free swing turns at ``h2``, ``h2**2 = a1**2 + (1 - b)**2
  (A**2 - a1**2) + 2 f (a2 - a1) / w**2``. ``h2 = a3`` (the swing touches a3 at rest) for
  ``A**2 = a1**2 + (a3**2 - a1**2 - 2 f (a2 - a1) / w**2) / (1 - b)**2``. If that touch counts as an
  impact (with speed 0) the impulse -f then acts from a3 to a4 and the next impact at a1 comes with
  ``v1**2 = w**2 (a3**2 - a1**2) + 2 f (a3 - a4)``; if not, the mass swings freely for ever with
  amplitude a3.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .checks import Evidence, Verdict, check, fmt, probe, runs_only

__all__ = ["existence_threshold", "existence_verdict", "grazing_limit", "grazing_release", "grazing_verdict",
    "map_constant", "release_verdict"]


def _params(args: Mapping, F: float, positions: Sequence[float] | None = None) -> Parameters:
    a1, a2, a3, a4 = positions if positions is not None else args["positions"]
    return Parameters(M=float(args.get("M", 1.0)), K=float(args.get("K", 1.0)), F=float(F), b=float(args.get("b", 0.1)),
                      a1=float(a1), a2=float(a2), a3=float(a3), a4=float(a4))


def _run(ev: Evidence, p: Parameters, x0: float, n_cycles) -> dict:
    """The run from rest at ``x0`` with ``p`` over ``n_cycles`` of the checks dataset: its ``outcome``, complete
    ``cycles``, last ``velocity`` and ``next_velocity`` (before the second impact at a1)."""
    where = {**{f"release_{k}": getattr(p, k) for k in MODEL_KEYS}, "release_x0": x0, "release_n_cycles": int(n_cycles)}
    return {name: probe(ev, f"release_{name}", "release", **where).item()
            for name in ("outcome", "cycles", "velocity", "next_velocity")}


def map_constant(p: Parameters) -> float:
    """``C`` of ``v1(k+1)**2 = (1 - b)**4 v1(k)**2 + C``, written from the module's closed form."""
    b = p.b
    return ((b * b - 2 * b) * p.K * (p.a1**2 - p.a3**2)
            + 2 * p.F * ((1 - b) ** 2 * (p.a2 - p.a1) + (p.a3 - p.a4))) / p.M


def existence_threshold(p: Parameters) -> float:
    """``F*``: the force at which ``C`` changes sign (N); a limit cycle needs ``F > F*``."""
    b = p.b
    return (2 * b - b * b) * p.K * (p.a1**2 - p.a3**2) / (2 * ((1 - b) ** 2 * (p.a2 - p.a1) + (p.a3 - p.a4)))


# --- Sec. 5: whether a limit cycle exists depends on F and the positions ------------------------


def existence_verdict(rows: Sequence[Mapping], threshold: float, tolerance: float) -> Verdict:
    """``rows``: per force ``F``, the closed-form ``C`` and ``fixed_point`` and the run's ``outcome``,
    ``cycles`` and last ``velocity``. Holds when every run agrees with the sign of C (C > 0: converges to
    the fixed point; C < 0: stops) and the forces lie on both sides of F*."""
    agree = []
    for r in rows:
        if r["C"] > 0:
            ok = r["outcome"] == Status.COMPLETED.value and abs(r["velocity"] - r["fixed_point"]) <= (
                tolerance * r["fixed_point"])
        else:
            ok = r["outcome"] == Status.STOPPED.value
        agree.append(ok)
    parts = []
    for r in rows:
        if r["outcome"] == Status.COMPLETED.value:
            parts.append(f"F = {fmt(r['F'], 4)} N (C = {fmt(r['C'], 4)} m^2/s^2): converges, v1 = {fmt(r['velocity'])} "
                         f"m/s after {r['cycles']} cycles (closed form {fmt(r['fixed_point'])})")
        else:
            parts.append(f"F = {fmt(r['F'], 4)} N (C = {fmt(r['C'], 4)} m^2/s^2): {r['outcome']} after "
                         f"{r['cycles']} complete cycles")
    both_sides = any(r["C"] > 0 for r in rows) and any(r["C"] < 0 for r in rows)
    holds = all(agree) and both_sides
    why = ("the runs agree with the sign of C on both sides of F*" if holds else
           "a run disagrees with the sign of C" if not all(agree) else "the forces do not straddle F*")
    return Verdict("; ".join(parts), holds, note=(
        f"F* = (2b - b^2) K (a1^2 - a3^2) / (2 [(1-b)^2 (a2 - a1) + (a3 - a4)]) = {fmt(threshold, 6)} N (closed "
        f"form): C < 0 below it, no fixed point, v1^2 falls by |C| or more per cycle until the escapement stops; "
        f"in the symmetric case F* = 0; {why}"),
        paper_value="the limit cycle's existence depends on F and a1..a4")


@check("existence_sign_change", scenes=runs_only, args=("positions", "forces", "x0", "n_cycles"))
def existence_sign_change(claim, ev: Evidence) -> Verdict:
    args = claim["args"]
    rows = []
    for F in args["forces"]:
        p = _params(args, F)
        c = map_constant(p)
        run = _run(ev, p, float(args["x0"]), args["n_cycles"])
        rows.append({"F": p.F, "C": c, "fixed_point": math.sqrt(c / (1 - (1 - p.b) ** 4)) if c > 0 else math.nan,
                     "outcome": run["outcome"], "cycles": run["cycles"], "velocity": run["velocity"]})
    return existence_verdict(rows, existence_threshold(_params(args, 0.0)), claim["tolerance"])


# --- Sec. 4: "the initial amplitude has no effect on the convergence" ---------------------------


def release_verdict(rows: Sequence[Mapping], boundary: float, tolerance: float) -> Verdict:
    """``rows``: per release ``x0`` the run's ``outcome`` and last ``velocity``, and the closed-form
    ``fixed_point``. Holds when every release converges to the fixed point (the note says where the
    releases inside ``boundary`` stand)."""

    def converged(r) -> bool:
        return r["outcome"] == Status.COMPLETED.value and abs(r["velocity"] - r["fixed_point"]) <= (
            tolerance * r["fixed_point"])

    text = "; ".join(
        f"x0 = {fmt(r['x0'], 6)} m: " + (f"converges to {fmt(r['velocity'])} m/s" if converged(r) else r["outcome"])
        for r in rows)
    return Verdict(text, all(converged(r) for r in rows), note=(
        f"from rest at x0 the free swing covers [-|x0|, |x0|] and meets an impact position only if |x0| > "
        f"min(-a1, a3) = {fmt(boundary, 6)} m (closed form); beyond it every release converges to the same fixed "
        f"point (Eq. (19): {fmt(rows[0]['fixed_point'])} m/s), inside it (or exactly on it) the escapement never "
        "starts and the mass swings freely"),
        paper_value="convergence independent of the initial amplitude")


@check("release_boundary", scenes=runs_only, args=("positions", "F", "releases", "n_cycles"))
def release_boundary(claim, ev: Evidence) -> Verdict:
    args = claim["args"]
    p = _params(args, args["F"])
    star = math.sqrt(map_constant(p) / (1 - (1 - p.b) ** 4))
    rows = []
    for x0 in args["releases"]:
        run = _run(ev, p, float(x0), args["n_cycles"])
        rows.append({"x0": float(x0), "outcome": run["outcome"], "velocity": run["velocity"], "fixed_point": star})
    return release_verdict(rows, min(-p.a1, p.a3), claim["tolerance"])


# --- Secs. 3.3 and 5: existence and uniqueness -------------------------------------------------


def grazing_release(p: Parameters) -> float:
    """``A``: released from rest at ``-A`` the swing after the first impulse turns exactly at a3."""
    w2 = p.omega2
    a_sq = p.a1**2 + (p.a3**2 - p.a1**2 - 2 * p.f * (p.a2 - p.a1) / w2) / (1 - p.b) ** 2
    if a_sq <= p.a1**2:
        raise ValueError(f"a1..a4 = {p.a1}, {p.a2}, {p.a3}, {p.a4}, F = {p.F}: no release grazes a3 "
                         "(the first impulse alone carries the swing past it)")
    return math.sqrt(a_sq)


def grazing_limit(p: Parameters) -> float:
    """The velocity before the next impact at a1 if the touch at a3 counts as an impact with speed 0."""
    return math.sqrt(p.omega2 * (p.a3**2 - p.a1**2) + 2 * p.f * (p.a3 - p.a4))


def grazing_verdict(rows: Sequence[Mapping], limit: float, tolerance: float) -> Verdict:
    """``rows``: per offset ``delta`` of the release from the grazing one, ``above`` (released at
    ``-A (1 + delta)``: its ``outcome`` and ``v_next``, the velocity before its second impact at a1) and
    ``below`` (at ``-A (1 - delta)``: its ``outcome``). Holds when the run above at the smallest ``delta``
    continues to the closed-form continuation ``limit``: one continuation from the grazing state, the strict
    jump set x xdot < 0 counting a touch at rest as no impact."""
    smallest = min(rows, key=lambda r: r["delta"])
    error = abs(smallest["above"]["v_next"] - limit) / limit
    text = "; ".join(
        f"delta = {fmt(r['delta'], 2)}: from -A(1 + delta) {r['above']['outcome']}"
        + (f", next impact at a1 with {fmt(r['above']['v_next'])} m/s" if math.isfinite(r["above"]["v_next"]) else "")
        + f"; from -A(1 - delta) {r['below']['outcome']}" for r in rows)
    return Verdict(text + f"; the grazing release separates an impact and impulse (next v1 = {fmt(limit)} m/s, "
                   "closed form) from no impact (a free swing of amplitude a3 for ever)", bool(error <= tolerance),
                   note=(
        "with the strict jump set x xdot < 0 a touch of a3 at rest is no impact, in the solver as in the jump set, "
        "and the state has one continuation; the touch comes two swings after the release, on the edge of an "
        "impulse zone, where g of Eq. (3b) switches with the state: releases delta either side of the grazing one "
        "end an O(1) apart however small delta, so the solution does not depend continuously on the release there"),
        paper_value="exactly one solution")


@check("grazing_uniqueness", scenes=runs_only, args=("positions", "F", "deltas", "n_cycles"))
def grazing_uniqueness(claim, ev: Evidence) -> Verdict:
    args = claim["args"]
    p = _params(args, args["F"])
    release = grazing_release(p)

    def run(x0: float) -> dict:
        found = _run(ev, p, x0, args["n_cycles"])
        return {"outcome": found["outcome"], "v_next": found["next_velocity"]}

    rows = [{"delta": float(d), "above": run(-release * (1 + float(d))), "below": run(-release * (1 - float(d)))}
            for d in args["deltas"]]
    verdict = grazing_verdict(rows, grazing_limit(p), claim["tolerance"])
    return Verdict(f"grazing release A = {fmt(release)} m (closed form); " + verdict.replicated_value, verdict.holds,
                   note=verdict.note, paper_value=verdict.paper_value)
