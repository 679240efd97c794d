"""The checks of the claims register: what every check is and uses, and the checks on the paper's map,
fixed point and multipliers (Sec. 3).

A check, registered by :func:`check` under its name in the register, computes the replicated value of
one kind of claim under one reading (its ``args``) from the datasets, and says whether the claim holds
(:class:`Verdict`); the status follows by the register's one rule (:mod:`.vocabulary`). Tolerances and
the Fig. 3 case labels come from the register. Each check declares the scenes it reads, so that a scene
that left the escapement regime gets its defined verdict (:func:`escapement.paper.claims.evaluate`), and
what it consumes besides the simulation (a law of the model, a fitted reading, a threshold). The
other checks are in the modules :mod:`escapement.paper.claims` imports.
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

__all__ = ["CHECKS", "Candidates", "Check", "Evidence", "Verdict", "check", "fmt"]

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
    """What a check finds under one reading: the replicated value, whether the claim ``holds`` (True or False;
    a mapping of each reading of a grid the check walks to its outcome; None when nothing can be computed),
    a note, and the paper's value where the paper gives a formula rather than a number."""

    replicated_value: str
    holds: bool | None | Mapping[str, bool]
    note: str = ""
    paper_value: str | None = None


Scenes = Callable[[Mapping, Evidence], dict[str, xr.Dataset]]


@dataclass(frozen=True)
class Check:
    """A registered check: its function, the scenes it reads, the ``args`` it needs from the register, and what
    it consumes besides the simulation, from which the kind of its evidence follows
    (:func:`escapement.paper.vocabulary.evidence_of`): the model's ``law`` it restates, what it reads that was
    ``fitted`` to the printed axes, the ``threshold`` on the claim's words the register's tolerance sets."""

    name: str
    function: Callable[[Mapping, Evidence], Verdict]
    scenes: Scenes
    args: tuple[str, ...] = ()
    law: str | None = None
    fitted: str | None = None
    threshold: str | None = None


#: every check of the register by its name, filled by :func:`check` as the modules of the checks are imported
CHECKS: dict[str, Check] = {}


def check(name: str, *, scenes: Scenes, args: tuple[str, ...] = (), law: str | None = None,
          fitted: str | None = None, threshold: str | None = None) -> Callable:
    """Register the decorated function as the check ``name`` of the register (see :class:`Check`); a
    function may be registered under several names. A name registered twice is refused."""

    def mark(function: Callable) -> Callable:
        if name in CHECKS:
            raise ValueError(f"two checks are named '{name}'")
        CHECKS[name] = Check(name, function, scenes, tuple(args), law, fitted, threshold)
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


def fig3_cases(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The two Fig. 3 cases of ``args: {cases: [first, second]}``, in that order."""
    labels = [str(c) for c in claim["args"]["cases"]]
    if len(labels) != 2:
        raise ValueError(f"args 'cases' must name two Fig. 3 cases, not {labels}")
    return {f"Fig. 3 case {c}": fig3_labelled(ev, c) for c in labels}


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


def within(value: float, tolerance: float) -> bool:
    return bool(value <= tolerance)


def group_runs(ev: Evidence, group: str) -> xr.Dataset:
    rows = np.flatnonzero(ev.checks["group"].values == group)
    if not len(rows):
        raise ValueError(f"the checks dataset holds no run of group '{group}'")
    table = [name for name, variable in ev.checks.data_vars.items() if "case" in variable.dims]
    return ev.checks[table].isel(case=rows)  # the table alone: the runs behind single claims have their own dims


def probe(ev: Evidence, name: str, dim: str, **where) -> xr.DataArray:
    """The variable ``name`` of the checks dataset at the one index of ``dim`` where every variable of ``where``
    has its value: the run a claim's ``args`` name, which the checks scene made (config ``checks`` block)."""
    if name not in ev.checks:
        raise ValueError(f"the checks dataset has no variable {name} (the checks block of the configuration)")
    match = np.ones(ev.checks.sizes[dim], dtype=bool)
    for key, value in where.items():
        match &= ev.checks[key].values == value
    if match.sum() != 1:
        raise ValueError(f"the checks dataset holds {int(match.sum())} runs of {name} at "
                         + ", ".join(f"{k} = {v!r}" for k, v in where.items()) + ", not one")
    return ev.checks[name].isel({dim: int(np.flatnonzero(match)[0])})


def runs_left_regime(runs: xr.Dataset) -> Verdict | None:
    """The verdict when a run of the checks dataset left the escapement regime, else None."""
    left = np.flatnonzero(runs["outcome"].values != COMPLETED)
    if not len(left):
        return None
    labels, outcomes = runs["label"].values[left], runs["outcome"].values[left]
    messages = runs["outcome_message"].values[left]
    return Verdict(
        f"not evaluated: {len(left)} of {runs.sizes['case']} runs left the escapement regime",
        False,
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
    return Verdict(
        ", ".join(f"{label}: {fmt(m)}" for label, m in zip(paper["label"].values, mu)),
        within(float(np.max(np.abs(mu - float(claim["paper_value"])))), claim["tolerance"]),
        note="central difference of the simulated return map at the measured fixed point",
    )


@check("stability_over_b", scenes=runs_only)
def stability_over_b(claim, ev: Evidence) -> Verdict:
    """Every b of the group converges with mu2 = (1 - b)^4: the motion's own return map, for 0 < b < 2."""
    group = group_runs(ev, "b")
    outcome = group["outcome"].values
    # chattering (b > 1) is an answer of this check; any other exit leaves it without one
    if (left := runs_left_regime(group.isel(case=np.flatnonzero(outcome != "chattering")))) is not None:
        return left
    b, mu, mu21 = group["b"].values, group["multiplier"].values, group["multiplier_eq21"].values
    stable = outcome == COMPLETED
    deviation = float(np.max(np.abs(mu[stable] - mu21[stable]))) if stable.any() else math.inf
    replicated = (f"converges with mu2 = (1-b)^4 (within {fmt(deviation, 2)}) for b = "
                  + ", ".join(fmt(x, 3) for x in b[stable]))
    if (~stable).any():
        replicated += (f"; for b = {', '.join(fmt(x, 3) for x in b[~stable])} the impact reverses the velocity and "
                       "the impacts chatter (Zeno): no periodic motion")
    return Verdict(replicated, bool(stable.all()) and within(deviation, claim["tolerance"]), note=(
        "for b > 1 the impact law v+ = (1-b) v- reverses the velocity; the map (16) squares the sign away, so "
        "|mu2| < 1 there says nothing about the motion, whose impacts accumulate in finite time"))


@check("multiplier_group", scenes=runs_only, args=("group",))
def multiplier_group(claim, ev: Evidence) -> Verdict:
    """mu2 = (1 - b)^4 in every run of the group: the rate of convergence depends on nothing else."""
    group = group_runs(ev, claim["args"]["group"])
    if (left := runs_left_regime(group)) is not None:
        return left
    worst = float(np.max(np.abs(group["multiplier"].values - group["multiplier_eq21"].values)))
    forces = sorted(set(group["F"].values.tolist()))
    return Verdict(f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over {group.sizes['case']} runs (F = "
                   f"{', '.join(fmt(f, 3) for f in forces)} N)", within(worst, claim["tolerance"]))


@check("multiplier_only_b", scenes=runs_only)
def multiplier_only_b(claim, ev: Evidence) -> Verdict:
    """Sec. 3.4, the stability determined only by b: mu2 = (1 - b)^4 in every run of the checks dataset that
    converges, whatever its force, spring, positions or release, and the runs that do not converge chatter, every
    one at b > 1, where the impact reverses the velocity; any other exit leaves the check without an answer."""
    runs = ev.checks
    outcome, b = runs["outcome"].values, runs["b"].values
    if (left := runs_left_regime(runs.isel(case=np.flatnonzero(outcome != "chattering")))) is not None:
        return left
    done = outcome == COMPLETED
    worst = float(np.max(np.abs(runs["multiplier"].values[done] - runs["multiplier_eq21"].values[done])))
    spans = "; ".join(f"{k} = {fmt(np.min(runs[k].values[done]), 3)} to {fmt(np.max(runs[k].values[done]), 3)}"
                      for k in ("F", "K", "a1", "a3", "x0", "b"))
    chatter = sorted(set(b[~done].tolist()))
    return Verdict(
        f"max |mu2 - (1-b)^4| = {fmt(worst, 2)} over the {int(done.sum())} runs that converge ({spans}); "
        + (f"the runs at b = {', '.join(fmt(x, 3) for x in chatter)} chatter" if chatter else "none chatters"),
        within(worst, claim["tolerance"]) and bool(np.all(b[~done] > 1)) and not bool(np.any(b[done] > 1)),
        note="mu2 measured from each run's return map: it follows b alone over runs that differ in every other "
             "parameter and in the release; whether the limit cycle exists is another question (Sec. 5)")


@check("runs_converge", scenes=runs_only, args=("group",))
def runs_converge(claim, ev: Evidence) -> Verdict:
    """Every run of the group reaches a limit cycle: it completes its cycles with |mu2| < 1."""
    group = group_runs(ev, claim["args"]["group"])
    mu, outcome = group["multiplier"].values, group["outcome"].values
    fine = (outcome == COMPLETED) & (np.abs(mu) < 1)
    return Verdict(
        f"{int(fine.sum())} of {len(fine)} runs converge to a limit cycle (mu2 = {fmt(np.nanmin(mu), 6)} to "
        f"{fmt(np.nanmax(mu), 6)})" + "".join(f"; {lab}: {o}" for lab, o in zip(group["label"].values[~fine],
                                                                               outcome[~fine])),
        bool(fine.all()))


@check("asymmetric_dependence", scenes=runs_only)
def asymmetric_dependence(claim, ev: Evidence) -> Verdict:
    """The rate of convergence (mu2) of the asymmetric runs depends on F or the positions: beyond the tolerance."""
    group = group_runs(ev, "asymmetric")
    if (left := runs_left_regime(group)) is not None:
        return left
    worst = float(np.max(np.abs(group["multiplier"].values - group["multiplier_eq21"].values)))
    v = group["velocity"].values
    return Verdict(
        f"mu2 = (1-b)^4 within {fmt(worst, 2)} in all {group.sizes['case']} asymmetric runs; fixed points "
        f"{fmt(np.min(v), 4)}-{fmt(np.max(v), 4)} m/s",
        not within(worst, claim["tolerance"]),
        note=("Eq. (16) is linear in x1^2: g' = (1-b)^4 x1/g(x1) = (1-b)^4 at any fixed point, with or without "
              "symmetry; what depends on F and the positions is the fixed point and whether it exists"),
    )
