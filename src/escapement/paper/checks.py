"""The checks of the claims register on the paper's equations (Sec. 3), and what every check uses.

A check, marked with :func:`check` by its name in the register, computes the replicated value of
one kind of claim from the datasets (and the paper's closed forms where the claim is a formula) and
decides the status (one of :data:`escapement.paper.vocabulary.STATUSES`); tolerances and
the Fig. 3 case labels come from the register (``tolerance``, ``args``). Each check declares the
scenes it reads, so that a scene that left the escapement regime gets its defined verdict
(:func:`escapement.paper.claims.evaluate`); the checks on the runs of the checks dataset handle each
run's outcome themselves. The checks on the figures of Sec. 4 are in :mod:`.section4_checks`, those
on the period formulas in :mod:`.period_checks`, the further ones in :mod:`.register`,
:mod:`.existence`, :mod:`.figure_checks`, :mod:`.airy` and :mod:`.axis_claims`; every one of them
is named in the one list of :mod:`.registry`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from . import printed as pe
from .vocabulary import NOT, PARTIAL, REPRODUCED, STATUSES, UNDETERMINED, UNTESTABLE  # noqa: F401 (re-exported)

__all__ = ["STATUSES", "Candidates", "Check", "Evidence", "Verdict", "check", "fmt"]

COMPLETED = Status.COMPLETED.value


def fmt(x: float, digits: int = 10) -> str:
    """A number as text, to ``digits`` significant digits (enough to compare, stable across runs)."""
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "nan"
    return f"{float(x):.{digits}g}"


@dataclass(frozen=True)
class Candidates:
    """Every candidate reading of one printed panel, scored against the panel's printed axes.

    ``scores`` counts, per reading (by its name), the printed limits its values reproduce when
    autoscaled with the printed tick step imposed; ``default_scores`` the same with the plotting
    program's own choice of tick step; ``equivalent`` groups readings that plot the same values (a
    mirror image read at the mirrored section, for example), which no axis can tell apart.
    """

    out_of: int
    scores: Mapping[str, int]
    default_scores: Mapping[str, int] = field(default_factory=dict)
    equivalent: tuple[tuple[str, ...], ...] = ()

    def tied(self, default: bool = False) -> tuple[int, list[tuple[str, ...]]]:
        """The best score and the readings tied at it, as groups of equivalent readings (readings that
        plot the same values form one group; each other reading a group of its own), in the order of
        the scores; ``default`` for the scores with the plotting program's own tick step. More than one
        group: the axes cannot tell the readings apart."""
        scores = self.default_scores if default else self.scores
        if not scores:
            raise ValueError("the grid of candidate readings holds no score"
                             + (" with the default tick step" if default else ""))
        best = max(scores.values())
        tied = [name for name, score in scores.items() if score == best]
        group_of = {name: group for group in self.equivalent for name in group}
        groups: list[tuple[str, ...]] = []
        for name in tied:
            group = tuple(n for n in group_of.get(name, (name,)) if n in tied)
            if group not in groups:
                groups.append(group)
        return best, groups


@dataclass(frozen=True)
class Evidence:
    """The datasets the claims are checked against; ``fig3`` and ``fig5`` keyed by their configured labels."""

    fig3: Mapping[str, xr.Dataset]
    fig4: xr.Dataset
    fig5: Mapping[str, xr.Dataset]
    checks: xr.Dataset
    #: the limits each printed panel's axes get when the outputs are autoscaled with the printed
    #: tick step, ``{(figure, panel): {"x": (low, high), "y": (low, high)}}`` (scored axes only)
    axes: Mapping[tuple[str, str], Mapping[str, tuple[float, float]]] = field(default_factory=dict)
    #: every candidate reading of each printed panel with its score, ``{(figure, panel): Candidates}``
    readings: Mapping[tuple[str, str], Candidates] = field(default_factory=dict)


@dataclass(frozen=True)
class Verdict:
    replicated_value: str
    status: str
    note: str = ""
    paper_value: str | None = None  #: filled when the paper gives a formula rather than a number


Scenes = Callable[[Mapping, Evidence], dict[str, xr.Dataset]]


@dataclass(frozen=True)
class Check:
    """A registered check: its function, the scenes it reads and the ``args`` it needs from the register."""

    name: str
    function: Callable[[Mapping, Evidence], Verdict]
    scenes: Scenes
    args: tuple[str, ...] = ()


def check(name: str, *, scenes: Scenes, args: tuple[str, ...] = ()) -> Callable:
    """Mark the decorated function as the check ``name`` of the register.

    The function gets the attribute ``check``, its :class:`Check`; it counts in the register once
    :mod:`escapement.paper.registry` lists it. Nothing is registered on import.

    Parameters
    ----------
    name : str
        The name by which the register (``workflow/claims.yaml``) calls the check.
    scenes : callable
        ``scenes(claim, evidence)``: the datasets the check reads, by a name for the verdict.
    args : tuple of str
        The keys the check needs in the claim's ``args``.

    Returns
    -------
    callable
        The decorator; it returns the function itself.
    """

    def mark(function: Callable) -> Callable:
        function.check = Check(name, function, scenes, tuple(args))
        return function

    return mark


# --- the scenes a check reads ------------------------------------------------------------------


def fig3_labelled(ev: Evidence, label: str) -> xr.Dataset:
    if label not in ev.fig3:
        raise ValueError(f"the register names Fig. 3 case '{label}'; the evidence holds {', '.join(ev.fig3)}")
    return ev.fig3[label]


def fig3_case(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The Fig. 3 case of ``args: {case: ...}``."""
    label = str(claim["args"]["case"])
    return {f"Fig. 3 case {label}": fig3_labelled(ev, label)}


def fig3_all(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {f"Fig. 3 case {c}": ds for c, ds in ev.fig3.items()}


def runs_only(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """No scene dataset: the check reads the runs of the checks dataset, one outcome per run."""
    return {}


# --- helpers -----------------------------------------------------------------------------------


def params_of(ds: xr.Dataset) -> Parameters:
    return Parameters(**{k: float(ds[k]) for k in MODEL_KEYS})


def events_of(ds: xr.Dataset, kind: EventKind) -> np.ndarray:
    return np.flatnonzero(ds["event_kind"].values == int(kind))


def cycle_durations(ds: xr.Dataset) -> dict[str, np.ndarray]:
    """Simulated durations inside each complete cycle: a1 -> a2 -> a3 -> a4 -> a1."""
    t = ds["event_time"].values
    starts = events_of(ds, EventKind.IMPACT_A1)[:-1]
    return {
        "zone_right": t[starts + 1] - t[starts],
        "a2_to_a3": t[starts + 2] - t[starts + 1],
        "zone_left": t[starts + 3] - t[starts + 2],
        "a4_to_a1": t[starts + 4] - t[starts + 3],
    }


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def within(value: float, tolerance: float) -> str:
    return REPRODUCED if value <= tolerance else NOT


def group_runs(ev: Evidence, group: str) -> xr.Dataset:
    rows = np.flatnonzero(ev.checks["group"].values == group)
    if not len(rows):
        raise ValueError(f"the checks dataset holds no run of group '{group}'")
    return ev.checks.isel(case=rows)


def runs_left_regime(runs: xr.Dataset) -> Verdict | None:
    """The verdict when a run of the checks dataset left the escapement regime, else None."""
    left = np.flatnonzero(runs["outcome"].values != COMPLETED)
    if not len(left):
        return None
    labels, outcomes = runs["label"].values[left], runs["outcome"].values[left]
    messages = runs["outcome_message"].values[left]
    return Verdict(
        f"not evaluated: {len(left)} of {runs.sizes['case']} runs left the escapement regime",
        NOT,
        note="; ".join(f"{lab} ended with outcome '{o}': {m}" for lab, o, m in zip(labels, outcomes, messages)),
    )


# --- Sec. 3.3-3.4: the Poincare map and its fixed point ----------------------------------------


@check("map_eq16", scenes=fig3_all)
def map_eq16(claim, ev: Evidence) -> Verdict:
    worst = 0.0
    pairs = 0
    for ds in ev.fig3.values():
        p, v = params_of(ds), ds["velocity_before_impact"].values
        predicted = np.array([pe.poincare_map_16(x, p) for x in v[:-1]])
        worst = max(worst, float(np.max(np.abs(v[1:] - predicted) / predicted)))
        pairs += len(predicted)
    return Verdict(
        f"max relative difference {fmt(worst, 3)} over {pairs} simulated cycle pairs (Fig. 3 {', '.join(ev.fig3)})",
        within(worst, claim["tolerance"]),
        paper_value="g of Eq. (16)",
    )


@check("fixed_point", scenes=fig3_case, args=("case",))
def fixed_point(claim, ev: Evidence) -> Verdict:
    ds = ev.fig3[claim["args"]["case"]]
    formula = pe.fixed_point_19(params_of(ds))
    simulated = float(ds["velocity_before_impact"].values[-1])
    n = ds.sizes["cycle"]
    return Verdict(
        f"{fmt(simulated)} m/s at cycle {n}",
        within(rel(simulated, formula), claim["tolerance"]),
        note=f"relative difference {fmt(rel(simulated, formula), 2)}, the transient left after {n} cycles",
        paper_value=f"{fmt(formula)} m/s",
    )


@check("multiplier_paper_cases", scenes=runs_only)
def multiplier_paper_cases(claim, ev: Evidence) -> Verdict:
    paper = group_runs(ev, "paper")
    if (left := runs_left_regime(paper)) is not None:
        return left
    mu = paper["multiplier"].values
    worst = float(np.max(np.abs(mu - float(claim["paper_value"]))))
    return Verdict(
        ", ".join(f"{label}: {fmt(m)}" for label, m in zip(paper["label"].values, mu)),
        within(worst, claim["tolerance"]),
        note="central difference of the simulated return map at the measured fixed point",
    )


@check("stability_over_b", scenes=runs_only)
def stability_over_b(claim, ev: Evidence) -> Verdict:
    group = group_runs(ev, "b")
    outcome = group["outcome"].values
    # chattering (b > 1) is the finding of this claim; any other exit leaves the check without an answer
    if (left := runs_left_regime(group.isel(case=np.flatnonzero(outcome != "chattering")))) is not None:
        return left
    b, mu, mu21 = group["b"].values, group["multiplier"].values, group["multiplier_eq21"].values
    stable = outcome == COMPLETED
    deviation = float(np.max(np.abs(mu[stable] - mu21[stable]))) if stable.any() else math.nan
    replicated = (
        f"converges with mu2 = (1-b)^4 (within {fmt(deviation, 2)}) for b = {', '.join(fmt(x, 3) for x in b[stable])}"
    )
    if (~stable).any():
        chattering = ", ".join(fmt(x, 3) for x in b[~stable])
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


@check("multiplier_group", scenes=runs_only, args=("group",))
def multipliergroup_runs(claim, ev: Evidence) -> Verdict:
    group = group_runs(ev, claim["args"]["group"])
    if (left := runs_left_regime(group)) is not None:
        return left
    mu, mu21 = group["multiplier"].values, group["multiplier_eq21"].values
    worst = float(np.max(np.abs(mu - mu21)))
    forces = sorted(set(group["F"].values.tolist()))
    return Verdict(
        f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over {len(mu)} runs (F = {', '.join(fmt(f, 3) for f in forces)} N "
        f"and {len(mu) // len(forces)} geometries)",
        within(worst, claim["tolerance"]),
    )


@check("asymmetric_dependence", scenes=runs_only)
def asymmetric_dependence(claim, ev: Evidence) -> Verdict:
    group = group_runs(ev, "asymmetric")
    if (left := runs_left_regime(group)) is not None:
        return left
    mu, mu21 = group["multiplier"].values, group["multiplier_eq21"].values
    worst = float(np.max(np.abs(mu - mu21)))
    v = group["velocity"].values
    return Verdict(
        f"mu2 = (1-b)^4 within {fmt(worst, 2)} in all {len(mu)} asymmetric runs; fixed points "
        f"{fmt(np.min(v), 4)}-{fmt(np.max(v), 4)} m/s",
        NOT if worst <= claim["tolerance"] else REPRODUCED,
        note=(
            "Eq. (16) is linear in x1^2: g' = (1-b)^4 x1/g(x1) = (1-b)^4 at any fixed point, with or without "
            "symmetry; what depends on F and the positions is the fixed point and whether it exists "
            "(C > 0 in x1^2 = (1-b)^4 x1^2 + C), not the rate of convergence"
        ),
    )

