"""Checks of the model's definitions, Eqs. (3a)-(5), and of the paper's claim of accuracy (Abstract, Sec. 5).

The model is built from these equations, so a check on them can show consistency, not confirm
them (the register marks these rows ``by_construction``): the impact matrix (3c) and the jump set
(4) are what the solver implements, and the impulse sets (5) are read as "after the impact" (see
REPLICATION.md, Sec. 2), which the check shows to coincide with the literal reading in the runs.
The state matrix (3a) is printed as [[0, 1], [-omega_n, 0]]: dimensionally the entry must be
-omega_n**2, but at the paper's omega_n = 1 rad/s both give the same motion, so its numbers cannot
tell them apart (undetermined). The closing claim that the model "can describe the system properly"
has no measurement of an escapement to be compared with: untestable.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.events import EventKind
from .checks import (NOT, REPRODUCED, UNDETERMINED, UNTESTABLE, Evidence, Verdict, check, fig3_all, fmt, params_of,
                     runs_only)

__all__ = ["impact_matrix", "impulse_sets", "jump_set", "state_matrix", "untestable"]


@check("state_matrix", scenes=fig3_all)
def state_matrix(claim, ev: Evidence) -> Verdict:
    """Undetermined when omega_n = 1 in every scene (the printed -omega_n and -omega_n**2 coincide)."""
    omegas = sorted({params_of(ds).omega for ds in ev.fig3.values()})
    same = all(math.isclose(w, w * w, rel_tol=claim["tolerance"]) for w in omegas)
    return Verdict(
        f"omega_n = {', '.join(fmt(w) for w in omegas)} rad/s in the Fig. 3 scenes: -omega_n = "
        f"{', '.join(fmt(-w) for w in omegas)} s^-1, -omega_n^2 = {', '.join(fmt(-w * w) for w in omegas)} s^-2",
        UNDETERMINED if same else NOT,
        note=("x'' = -omega_n^2 x (Eq. (A-1)) needs -omega_n^2 in A; the printed -omega_n may be a superscript lost "
              "in the text extraction or in print. " + (
                  "With the paper's M = K = 1 both are -1 s^-2 numerically, so nothing the paper computes can tell "
                  "them apart" if same else "Here they differ, and only -omega_n^2 gives the motion of Eq. (A-1)")),
        paper_value="A = [[0, 1], [-omega_n, 0]]",
    )


def _impacts(ds) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    kind = ds["event_kind"].values
    at = np.flatnonzero((kind == int(EventKind.IMPACT_A1)) | (kind == int(EventKind.IMPACT_A3)))
    return kind[at], ds["event_velocity_before"].values[at], ds["event_velocity_after"].values[at]


@check("impact_matrix", scenes=fig3_all)
def impact_matrix(claim, ev: Evidence) -> Verdict:
    """The jump of the velocity at every impact is B y = (0, -b xdot)."""
    worst, n = 0.0, 0
    for ds in ev.fig3.values():
        b = params_of(ds).b
        _, before, after = _impacts(ds)
        worst = max(worst, float(np.max(np.abs((after - before) - (-b * before)) / np.abs(before))))
        n += len(before)
    return Verdict(
        f"max relative difference of the velocity jump from -b x' {fmt(worst, 3)} over {n} impacts (Fig. 3 "
        f"{', '.join(ev.fig3)})",
        REPRODUCED if worst <= claim["tolerance"] else NOT,
        note="the impact law the model is built on (equal by construction); the position does not jump",
        paper_value="B = [[0, 0], [0, -b]]",
    )


@check("jump_set", scenes=fig3_all)
def jump_set(claim, ev: Evidence) -> Verdict:
    """Every impact is on S = {x in {a1, a3}, x xdot < 0}: at a1 moving right (a1 < 0), at a3 moving left."""
    bad, n = 0, 0
    for ds in ev.fig3.values():
        p = params_of(ds)
        kind, before, _ = _impacts(ds)
        x = np.where(kind == int(EventKind.IMPACT_A1), p.a1, p.a3)
        bad += int(np.count_nonzero(x * before >= 0))
        n += len(kind)
    return Verdict(
        f"{n - bad} of {n} impacts with x x' < 0 (Fig. 3 {', '.join(ev.fig3)})",
        REPRODUCED if bad == 0 else NOT,
        note="the solver's impact surfaces are S (equal by construction)",
        paper_value="S = {y : x in {a1, a3}, x x' < 0}",
    )


@check("impulse_sets", scenes=fig3_all)
def impulse_sets(claim, ev: Evidence) -> Verdict:
    """The force acts in S2 read literally (wherever x is in (a1, a2) moving right, or in (a4, a3) moving
    left) or after the impact only: the two coincide when every entry into a zone is its impact, that is,
    when the events run a1, a2, a3, a4, a1, ... with no turn inside a zone (a completed run)."""
    order = [int(k) for k in (EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4)]
    broken, n = 0, 0
    for ds in ev.fig3.values():
        kind = ds["event_kind"].values.astype(int)
        start = order.index(int(kind[0]))
        expected = np.array([order[(start + i) % 4] for i in range(len(kind))])
        broken += int(np.count_nonzero(kind != expected))
        n += len(kind)
    return Verdict(
        f"{n - broken} of {n} events in the order a1, a2, a3, a4 (Fig. 3 {', '.join(ev.fig3)})",
        REPRODUCED if broken == 0 else NOT,
        note=("each zone is entered only through its impact, so the force of Eq. (3b) on S2 read as a region of the "
              "state space and read as 'after the impact' give the same motion in these runs (by construction "
              "of the solver, which implements the second)"),
        paper_value="S2 = {x in (a1, a2), x' > 0} u {x in (a4, a3), x' < 0}",
    )


@check("untestable", scenes=runs_only, args=("reason",))
def untestable(claim, ev: Evidence) -> Verdict:
    """A claim the paper gives no evidence for: the reason is the register's."""
    return Verdict("nothing to compute", UNTESTABLE, note=str(claim["args"]["reason"]),
                   paper_value="no measurement given")
