"""The runs of the checks block measured otherwise than the table of :func:`escapement.scenes.runs.checks`, each written
under its name in the block (:func:`named_runs`): its settings beside what its ``measure`` gives (:data:`MEASURES`).
A check reads a run by its name (:func:`escapement.verdict.evidence.run`) and never runs one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS, PARAMETERS
from ..solvers.exact import solve_exact
from ..studies.poincare import RELATIVE_STEP, return_map, section_crossing_counts
from .cf import CLASSIFICATION, MODEL_INPUT, MODEL_RESULT
from .settings import positive_int

__all__ = ["MEASURES", "SETTINGS", "named_runs"]

#: the settings a run may have beside the model's keys: units (None for a text) and long name
SETTINGS = {
    "case": (None, "Fig. 3 case of the run"),
    "zone": (None, "name of the impulse zone [a1, a2] of the run"),
    "x0": ("m", "released from rest at"),
    "n_cycles": ("1", "cycles run"),
    "t_end": ("s", "end of the run"),
    "side": ("1", "side of the release: -1 left of the equilibrium, 1 right"),
    "offset": ("1", "relative offset of the release from the grazing one, A: released at -A (1 + offset)"),
    "velocity": ("m s-1", "velocity before the impact at a1 the run starts from on the section"),
    "perturbation": ("1", "relative perturbation of the speed at the section, from the converged speed"),
    "section_cycles": ("1", "cycles run from the section"),
    "samples_per_period": ("1", "samples of the trajectory per natural period"),
    "release_force": (None, "where the force acts before the first impact: after_impact, or eq5 (on S2 of Eq. (5))"),
    "past_accumulation": (None, "what follows an accumulation of impacts: stop, or continue from rest at the impact "
                          "position"),
}
#: the kind and the units of each column of an event table
EVENTS = (("time", "s", "time of the event"),
          ("kind", "1", "kind of the event: 1 impact at a1, 2 end of the impulse at a2, 3 impact at a3, 4 end of the "
                        "impulse at a4"),
          ("position", "m", "position of the event"), ("velocity_before", "m s-1", "velocity just before the event"),
          ("velocity_after", "m s-1", "velocity just after the event"))


def _variable(values, dims, units: str | None, long_name: str, content: str = MODEL_RESULT, **attrs) -> xr.DataArray:
    described = {"long_name": long_name, "coverage_content_type": content, **attrs}
    if units is not None:
        described["units"] = units
    return xr.DataArray(np.array(values, dtype=None if units is not None else object), dims=dims, attrs=described)


def _padded(rows: Sequence, dims: tuple[str, str], units: str, long_name: str, **attrs) -> xr.DataArray:
    """Rows of different lengths as one variable, NaN after the end of each."""
    table = np.full((len(rows), max(len(r) for r in rows)), np.nan)
    for row, values in zip(table, rows):
        row[:len(values)] = values
    return _variable(table, dims, units, long_name, **attrs)


def _release(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """Each run from rest at ``x0`` over ``n_cycles``: its outcome, cycles and last and second velocities at a1."""
    found = []
    for r, p in zip(runs, params):
        sol = solve_exact(p, float(r["x0"]), n_cycles=positive_int("n_cycles", r["n_cycles"], 100_000),
                          record_trajectory=False)
        v, impacts = sol.cycles.velocity_before_impact, sol.events.of_kind(EventKind.IMPACT_A1)
        found.append((sol.status.value, sol.message, len(sol.cycles), float(v[-1]) if len(v) else np.nan,
                      float(sol.events.v_before[impacts[1]]) if len(impacts) > 1 else np.nan))
    outcome, message, cycles, velocity, second = zip(*found)
    return {"outcome": _variable(outcome, "run", None, "how the run ended", CLASSIFICATION),
            "outcome_message": _variable(message, "run", None, "how the run ended, in words", CLASSIFICATION),
            "cycles": _variable(cycles, "run", "1", "complete cycles"),
            "velocity": _variable(velocity, "run", "m s-1", "velocity before the last impact at a1"),
            "next_velocity": _variable(second, "run", "m s-1", "velocity before the second impact at a1 (NaN if none)")}


def _events(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """Each run from rest at ``x0`` over ``n_cycles`` or to ``t_end``: its events, NaN after the last."""
    solved = [solve_exact(p, float(r["x0"]), t_end=r.get("t_end"), record_trajectory=False, n_cycles=positive_int(
        "n_cycles", r["n_cycles"], 1000) if "n_cycles" in r else None).events for r, p in zip(runs, params)]
    table = np.full((len(EVENTS), len(runs), max(len(e) for e in solved)), np.nan)
    for i, e in enumerate(solved):
        table[:, i, :len(e)] = e.t, e.kind, e.x, e.v_before, e.v_after
    return {f"event_{name}": _variable(values, ("run", "event"), units, f"{long_name} (NaN after the last)")
            for values, (name, units, long_name) in zip(table, EVENTS)}


def _return_map(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """The slope of the return map at each run's ``velocity``: central differences of one simulated cycle."""
    slopes = []
    for r, p in zip(runs, params):
        (lo_in, lo_out), (hi_in, hi_out) = (return_map(p, float(r["velocity"]) * (1 + side * RELATIVE_STEP))
                                            for side in (-1, 1))
        slopes.append((hi_out - lo_out) / (hi_in - lo_in))
    return {"slope": _variable(slopes, "run", "1", "slope of the simulated return map at the run's velocity, by "
                               "central differences", relative_step=RELATIVE_STEP)}


def _from_section(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """Each run from rest at ``x0``, then from the section at ``1 + perturbation`` times its converged speed: that
    speed, the times of the impacts at a1 from the section and the last speed before one."""
    found = []
    for r, p in zip(runs, params):
        release = solve_exact(p, float(r["x0"]), n_cycles=positive_int("n_cycles", r["n_cycles"], 1_000_000),
                              record_trajectory=False)
        star = float(release.cycles.velocity_before_impact[-1])
        run = solve_exact(p, p.a1, star * (1 + float(r["perturbation"])), record_trajectory=False,
                          n_cycles=positive_int("section_cycles", r["section_cycles"], 100_000))
        found.append((star, run.events.t[run.events.kind == int(EventKind.IMPACT_A1)],
                      float(run.cycles.velocity_before_impact[-1])))
    star, times, speed = zip(*found)
    return {"converged_speed": _variable(star, "run", "m s-1", "velocity before the last impact at a1 of the run "
                                         "from rest"),
            "impact_time": _padded(times, ("run", "impact"), "s", "time of each impact at a1 of the run from the "
                                   "section (NaN after the last)"),
            "speed": _variable(speed, "run", "m s-1", "velocity before the last impact at a1 of the run from the "
                               "section")}


def _zone_shift(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """``dT2`` of each run's first passage through the zone (a1, a2) from rest at ``x0``, less a free swing's (s)."""
    shifts = []
    for r, p in zip(runs, params):
        run = solve_exact(p, float(r["x0"]), n_cycles=1, record_trajectory=False)
        ev = run.events
        first = ev.of_kind(EventKind.IMPACT_A1)
        if not len(first) or first[0] + 1 >= len(ev) or ev.kind[first[0] + 1] != EventKind.ZONE_END_A2:
            raise ValueError(f"F = {p.F!r} N, zone ({p.a1}, {p.a2}): no passage through the zone ({run.message})")
        i, w = first[0], p.omega
        advance = math.atan2(ev.x[i + 1], ev.v_before[i + 1] / w) - math.atan2(ev.x[i], ev.v_after[i] / w)
        shifts.append(float(ev.t[i + 1] - ev.t[i]) - advance / w)
    return {"zone_shift": _variable(shifts, "run", "s", "time one passage through the zone [a1, a2] adds to the free "
                                    "swing")}


def _crossings(runs: Sequence[Mapping], params: Sequence[Parameters]) -> dict[str, xr.DataArray]:
    """Each run from rest at ``x0``, sampled: the crossings of the section x = a1 with xdot > 0 in each cycle."""
    counts = []
    for r, p in zip(runs, params):
        run = solve_exact(p, float(r["x0"]), n_cycles=positive_int("n_cycles", r["n_cycles"], 100_000))
        t = np.linspace(0.0, run.t_final, int(r["samples_per_period"] * run.t_final / p.natural_period))
        x, v, _ = run.sample(t)
        counts.append(section_crossing_counts(t, x, v, p.a1, run.events.t[run.events.of_kind(EventKind.IMPACT_A1)]))
    return {"crossings": _padded(counts, ("run", "cycle"), "1", "crossings of x = a1 with xdot > 0 from one impact at "
                                 "a1 to the next, on the sampled trajectory (NaN after the last)")}


#: each measure: what it makes of its runs and their models, and the settings every run of it needs
MEASURES: dict[str, tuple[Callable[..., dict[str, xr.DataArray]], tuple[str, ...]]] = {
    "release": (_release, ("x0", "n_cycles")),
    "events": (_events, ("x0",)),
    "return_map": (_return_map, ("velocity",)),
    "from_section": (_from_section, ("x0", "n_cycles", "perturbation", "section_cycles")),
    "zone_shift": (_zone_shift, ("x0",)),
    "crossings": (_crossings, ("x0", "n_cycles", "samples_per_period")),
}


def named_runs(probes: Mapping[str, Mapping]) -> dict[str, xr.DataArray]:
    """The variables of each run of ``probes`` (``{name: {measure, runs}}``), each ``<name>_<variable>`` on
    ``<name>_run``; every run is checked before any is made."""
    checked = {}
    for name, spec in probes.items():
        measure, runs = spec["measure"], list(spec["runs"])
        if measure not in MEASURES or not runs:
            raise ValueError(f"checks.{name}: measure = {measure!r} with {len(runs)} runs is invalid: a named run is "
                             f"one or more runs of a measure, one of {', '.join(MEASURES)}")
        if missing := [k for k in MEASURES[measure][1] for r in runs if k not in r]:
            raise ValueError(f"checks.{name}: a run has no {missing[0]}: the runs of measure {measure} need "
                             f"{', '.join(MEASURES[measure][1])}")
        checked[name] = (measure, runs, [Parameters.from_mapping(r) for r in runs])
    found: dict[str, xr.DataArray] = {}
    for name, (measure, runs, params) in checked.items():
        made = {"label": _variable([r["label"] for r in runs], "run", None, "the settings that tell the run apart",
                                   MODEL_INPUT),
                **{k: _variable([getattr(p, k) for p in params], "run", PARAMETERS[k].units, PARAMETERS[k].long_name,
                                MODEL_INPUT) for k in MODEL_KEYS},
                **{k: _variable([r[k] for r in runs], "run", *described, MODEL_INPUT) for k, described in
                   SETTINGS.items() if all(k in r for r in runs)},
                **MEASURES[measure][0](runs, params)}
        found.update({f"{name}_{key}": v.rename({d: f"{name}_{d}" for d in v.dims}) for key, v in made.items()})
    return found
