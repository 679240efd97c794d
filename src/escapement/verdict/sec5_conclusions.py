"""The checks of the conclusions (Sec. 5) and of the abstract: the convergence depends on the force
and the positions when the geometry is asymmetric, where whether a limit cycle exists changes sign with F.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..model.status import Status
from ..paper.corrected import existence_threshold, fixed_point, map_constant
from ..model.parameters import Parameters
from .evidence import OUTCOMES, Evidence, Verdict, check, each, fmt, mu2_off, params_of, run, within


@check(runs=("runs",))
def asymmetric_dependence(claim, ev: Evidence) -> Verdict:
    """The rate of convergence (mu2) of the asymmetric runs depends on F or the positions: beyond the tolerance."""
    group = run(ev, claim["args"]["runs"])
    worst, v = mu2_off(group), group["velocity"].values
    return Verdict(f"mu2 = (1-b)^4 within {fmt(worst, 2)} in all {group.sizes['run']} asymmetric runs; fixed points "
                   f"{fmt(np.min(v), 4)}-{fmt(np.max(v), 4)} m/s", not within(worst, claim["tolerance"]), note=(
        "Eq. (16) is linear in x1^2: g' = (1-b)^4 x1/g(x1) = (1-b)^4 at any fixed point, with or without symmetry; "
        "what depends on F and the positions is the fixed point and whether it exists"))


def existence_verdict(rows: Sequence[Mapping], threshold: float, tolerance: float) -> Verdict:
    """Holds when every run agrees with the sign of C (> 0: converges to the fixed point; < 0: stops) across F*."""
    agree = [r["outcome"] == Status.COMPLETED.value and abs(r["velocity"] - r["fixed_point"]) <= (
        tolerance * r["fixed_point"]) if r["C"] > 0 else r["outcome"] == Status.STOPPED.value for r in rows]
    parts = [f"F = {fmt(r['F'], 4)} N (C = {fmt(r['C'], 4)} m^2/s^2): " + (
        f"converges, v1 = {fmt(r['velocity'])} m/s after {r['cycles']} cycles (closed form {fmt(r['fixed_point'])})"
        if r["outcome"] == Status.COMPLETED.value else f"{r['outcome']} after {r['cycles']} complete cycles")
        for r in rows]
    holds = all(agree) and any(r["C"] > 0 for r in rows) and any(r["C"] < 0 for r in rows)  # F* straddled
    why = ("the runs agree with the sign of C on both sides of F*" if holds else
           "a run disagrees with the sign of C" if not all(agree) else "the forces do not straddle F*")
    return Verdict("; ".join(parts), holds, paper_value="the limit cycle's existence depends on F and a1..a4", note=(
        f"F* = (2b - b^2) K (a1^2 - a3^2) / (2 [(1-b)^2 (a2 - a1) + (a3 - a4)]) = {fmt(threshold, 6)} N (closed "
        f"form): C < 0 below it, no fixed point, v1^2 falls by |C| or more per cycle until the escapement stops; "
        f"in the symmetric case F* = 0; {why}"))


@check(runs=("runs",), answers=OUTCOMES)
def existence_sign_change(claim, ev: Evidence) -> Verdict:
    """The runs from rest of one geometry at each force against the sign of the map's constant C."""
    rows = []
    for r in each(run(ev, claim["args"]["runs"])):
        p = params_of(r)
        rows.append({"F": p.F, "C": map_constant(p), "fixed_point": fixed_point(p),
                     "outcome": str(r["outcome"].values), "cycles": int(r["cycles"]), "velocity": float(r["velocity"])})
    return existence_verdict(rows, existence_threshold(Parameters(**{**p.as_dict(), "F": 0.0})), claim["tolerance"])
