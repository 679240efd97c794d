"""What every check reads and answers: the datasets (:class:`Evidence`), the verdict under one reading
(:class:`Verdict`), a check's declaration (:func:`check`), and a run of the checks dataset by its name (:func:`run`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .rule import fmt as fmt  # the checks write their numbers by it (a document needs only .rule for it)
from .scores import Candidates

COMPLETED = Status.COMPLETED.value
OUTCOMES = tuple(s.value for s in Status)


@dataclass(frozen=True)
class Evidence:
    """The datasets the claims are checked against; ``fig3`` and ``fig5`` keyed by their configured labels."""

    fig3: Mapping[str, xr.Dataset]
    fig4: xr.Dataset
    fig5: Mapping[str, xr.Dataset]
    checks: xr.Dataset
    #: the autoscaled limits of each printed panel's scored axes, ``{(figure, panel): {"x": (low, high), ...}}``
    axes: Mapping[tuple[str, str], Mapping[str, tuple[float, float]]] = field(default_factory=dict)
    #: every candidate reading of each printed panel with its score, ``{(figure, panel): Candidates}``
    readings: Mapping[tuple[str, str], Candidates] = field(default_factory=dict)


@dataclass(frozen=True)
class Verdict:
    """What a check finds under one reading; ``holds`` is a bool, one per reading of a grid, or None (nothing to do)."""

    replicated_value: str
    holds: bool | None | Mapping[str, bool]
    note: str = ""
    paper_value: str | None = None


def no_scene(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {}


@dataclass(frozen=True)
class Check:
    """A check of the register and what it declares: ``law``, ``fitted`` and ``threshold`` give its kind of evidence
    (:func:`.rule.evidence_of`); ``answers`` are the outcomes besides ``completed`` that are not exits."""

    function: Callable[[Mapping, Evidence], Verdict]
    scenes: Callable[[Mapping, Evidence], dict[str, xr.Dataset]] = no_scene
    runs: tuple[str, ...] = ()
    args: tuple[str, ...] = ()
    law: str | None = None
    fitted: str | None = None
    threshold: str | None = None
    answers: tuple[str, ...] = ()

    def __call__(self, claim: Mapping, ev: Evidence) -> Verdict:
        return self.function(claim, ev)


def check(**declared) -> Callable[[Callable], Check]:
    """The decorated function as a :class:`Check` declaring what it reads and consumes (its fields) beside its code."""
    return lambda function: Check(function, **declared)


def fig3_scenes(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    """The Fig. 3 cases of ``args: {case: ...}``, or of ``{cases: [first, second]}`` in that order, else every case."""
    args = claim["args"]
    labels = ([str(args["case"])] if "case" in args else [str(c) for c in args["cases"]] if "cases" in args
              else list(ev.fig3))
    if "cases" in args and len(labels) != 2:
        raise ValueError(f"args 'cases' must name two Fig. 3 cases, not {labels}")
    if missing := [c for c in labels if c not in ev.fig3]:
        raise ValueError(f"the register names Fig. 3 case '{missing[0]}'; the evidence holds {', '.join(ev.fig3)}")
    return {f"Fig. 3 case {c}": ev.fig3[c] for c in labels}


def fig4_scene(claim: Mapping, ev: Evidence) -> dict[str, xr.Dataset]:
    return {"Fig. 4": ev.fig4}


def params_of(ds: xr.Dataset) -> Parameters:
    return Parameters(**{k: float(ds[k]) for k in MODEL_KEYS})


def events_of(ds: xr.Dataset, kind: EventKind) -> np.ndarray:
    return np.flatnonzero(ds["event_kind"].values == int(kind))


def cycle_durations(ds: xr.Dataset) -> dict[str, np.ndarray]:
    """Simulated durations inside each complete cycle: a1 -> a2 -> a3 -> a4 -> a1."""
    t, starts = ds["event_time"].values, events_of(ds, EventKind.IMPACT_A1)[:-1]
    return {name: t[starts + i + 1] - t[starts + i]
            for i, name in enumerate(("zone_right", "a2_to_a3", "zone_left", "a4_to_a1"))}


def successive_ratios(values: np.ndarray) -> np.ndarray:
    """``(u[k+2] - u[k+1]) / (u[k+1] - u[k])`` where both differences are well above rounding (1e-7 of u)."""
    d = np.diff(values)
    usable = (np.abs(d[:-1]) > 1e-7 * np.abs(values[-1])) & (np.abs(d[1:]) > 1e-7 * np.abs(values[-1]))
    return d[1:][usable] / d[:-1][usable]


def mu2_off(runs: xr.Dataset) -> float:
    """The largest ``|mu2 - (1 - b)^4|`` over the runs: the measured multiplier against Eq. (21)."""
    return float(np.max(np.abs(runs["multiplier"].values - runs["multiplier_eq21"].values)))


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def within(value: float, tolerance: float) -> bool:
    return bool(value <= tolerance)


def names(claim: Mapping, arg: str) -> list[str]:
    """The runs the claim's ``arg`` names."""
    value = claim["args"][arg]
    return [value] if isinstance(value, str) else list(value)


def run(ev: Evidence, name: str) -> xr.Dataset:
    """The runs the checks block names ``name``, on the dimension ``run``: a group of the table, or a measure's runs."""
    checks, dim = ev.checks, f"{name}_run"
    if dim in checks.dims:
        found = checks[[key for key, variable in checks.data_vars.variables.items() if dim in variable.dims]]
        return found.rename({key: key.removeprefix(f"{name}_") for key in (*found.data_vars, *found.dims)})
    rows = np.flatnonzero(checks["group"].values == name) if "group" in checks else []
    if not len(rows):
        raise ValueError(f"the checks dataset holds no run {name!r}: a run is named by the checks block of the "
                         "configuration")
    return checks[[key for key, variable in checks.data_vars.variables.items() if "case" in variable.dims]].isel(
        case=rows).rename(case="run")


def each(runs: xr.Dataset) -> list[xr.Dataset]:
    return [runs.isel(run=i) for i in range(runs.sizes["run"])]


@check(args=("reason",))
def untestable(claim, ev: Evidence) -> Verdict:
    """A claim the paper gives no evidence for: the reason is the register's."""
    return Verdict("nothing to compute", None, note=str(claim["args"]["reason"]), paper_value="no measurement given")
