"""The runs behind single claims of the register, beside the table of the ``checks`` dataset
(:func:`escapement.scenes.runs.checks`): each Fig. 3 case's first swing from either side of its release, the
slope of the return map of a Fig. 3 case at given speeds, the runs from the section at the converged speed
and beside it, the releases from rest of the checks on where a limit cycle exists (Secs. 3.3, 4 and 5), and the
time one passage through an impulse zone adds to the swing (Airy's theorem, Sec. 5), and the events of short runs
of a Fig. 3 case at other springs and releases (Sec. 3.3); the crossings of the Poincare section per cycle of
Fig. 3's cases and the impacts of the runs of Fig. 4's grid of readings up to its printed windows.
Each group of variables has its own dimension; the checks find in it the run their ``args`` in the register name
(:mod:`escapement.paper`), and never run one.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS, PARAMETERS
from ..paper.corrected import grazing_release
from ..paper.printed_axes import panel
from ..solvers.exact import solve_exact
from ..studies.poincare import RELATIVE_STEP, return_map, section_crossing_counts
from .cf import CLASSIFICATION, MODEL_INPUT, MODEL_RESULT
from .settings import positive_int

__all__ = ["probe_variables"]


def _variable(values, dims, units: str | None, long_name: str, content: str = MODEL_RESULT, **attrs) -> xr.DataArray:
    described = {"long_name": long_name, "coverage_content_type": content, **attrs}
    if units is not None:
        described["units"] = units
    return xr.DataArray(np.array(values, dtype=None if units is not None else object), dims=dims, attrs=described)


def _first_swings(runs: list[Mapping]) -> dict[str, xr.DataArray]:
    """Each run (a Fig. 3 case's parameters, its ``label`` and a release ``x0``) released from rest for one cycle:
    the velocity before its first impact at a1."""
    first = [float(solve_exact(Parameters.from_mapping(r), float(r["x0"]), n_cycles=1, record_trajectory=False)
                   .cycles.velocity_before_impact[0]) for r in runs]
    dims = "first_swing"
    return {"first_swing_case": _variable([r["label"] for r in runs], dims, None, "Fig. 3 case of the run",
                                          MODEL_INPUT),
            "first_swing_x0": _variable([float(r["x0"]) for r in runs], dims, "m", "released from rest at",
                                        MODEL_INPUT),
            "first_swing_velocity": _variable(first, dims, "m s-1", "velocity before the first impact at a1")}


def _return_map(spec: Mapping) -> dict[str, xr.DataArray]:
    """The slope of the return map of the case ``spec`` (parameters and ``label``) at each of its ``velocities``:
    central differences of one simulated cycle from the section."""
    p, slopes = Parameters.from_mapping(spec), []
    for v in spec["velocities"]:
        lo_in, lo_out = return_map(p, float(v) * (1 - RELATIVE_STEP))
        hi_in, hi_out = return_map(p, float(v) * (1 + RELATIVE_STEP))
        slopes.append((hi_out - lo_out) / (hi_in - lo_in))
    speeds = _variable([float(v) for v in spec["velocities"]], "map_velocity", "m s-1",
                       "velocity before the impact at a1 where the return map's slope is measured", MODEL_INPUT)
    return {"map_velocity": speeds, "map_slope": _variable(
        slopes, "map_velocity", "1", f"slope of the simulated return map of Fig. 3 case {spec['label']}, by "
        "central differences", case=str(spec["label"]), relative_step=RELATIVE_STEP)}


def _phase_shift(spec: Mapping) -> dict[str, xr.DataArray]:
    """The case ``spec`` (parameters, ``label``, release ``x0``) run ``n_release`` cycles as Fig. 3 runs it, then
    from the section at its last speed before impact and at ``1 + perturbation`` times it over ``n_cycles``: the
    times of the impacts at a1 and the last speed before impact of each run."""
    p, n_cycles = Parameters.from_mapping(spec), positive_int("n_cycles", spec["n_cycles"], 100_000)
    release = solve_exact(p, float(spec["x0"]), n_cycles=positive_int("n_release", spec["n_release"], 100_000),
                          record_trajectory=False)
    star = float(release.cycles.velocity_before_impact[-1])
    perturbations = [0.0, float(spec["perturbation"])]
    runs = [solve_exact(p, p.a1, star * (1 + d), n_cycles=n_cycles, record_trajectory=False) for d in perturbations]
    times = [r.events.t[r.events.kind == int(EventKind.IMPACT_A1)] for r in runs]
    return {
        "perturbation": _variable(perturbations, "perturbation", "1", "relative perturbation of the speed at the "
                                  "section, from the converged speed", MODEL_INPUT),
        "perturbed_impact_time": _padded(times, ("perturbation", "impact"), "s", "time of each impact at a1 of Fig. 3 "
                                         f"case {spec['label']} started at the section (NaN after the last)",
                                         case=str(spec["label"]), n_cycles=n_cycles),
        "perturbed_speed": _variable([float(r.cycles.velocity_before_impact[-1]) for r in runs], "perturbation",
                                     "m s-1", "velocity before the last impact at a1 of the run from the section",
                                     converged_speed=star),
    }


def _releases(runs: list[Mapping], grazing: Mapping | None) -> dict[str, xr.DataArray]:
    """Each run (the model's keys, ``x0`` and ``n_cycles``) from rest, and from either side of the grazing
    release ``-A (1 +/- delta)`` of ``grazing`` (:func:`escapement.paper.corrected.grazing_release`) at each of its
    ``deltas``: how it ended, its complete cycles, its last velocity before impact at a1 and the one before its
    second impact at a1."""
    if grazing is not None:
        edge = grazing_release(Parameters.from_mapping(grazing))
        runs = [*runs, *({**grazing, "x0": x0} for d in grazing["deltas"]
                         for x0 in (-edge * (1 + float(d)), -edge * (1 - float(d))))]
    found = []
    for r in runs:
        sol = solve_exact(Parameters.from_mapping(r), float(r["x0"]), n_cycles=positive_int(
            "n_cycles", r["n_cycles"], 100_000), record_trajectory=False)
        v, impacts = sol.cycles.velocity_before_impact, sol.events.of_kind(EventKind.IMPACT_A1)
        found.append((sol.status.value, len(sol.cycles), float(v[-1]) if len(v) else np.nan,
                      float(sol.events.v_before[impacts[1]]) if len(impacts) > 1 else np.nan))
    dims, given = "release", ("released from rest", MODEL_INPUT)
    return {
        **{f"release_{k}": _variable([float(r[k]) for r in runs], dims, PARAMETERS[k].units, PARAMETERS[k].long_name,
                                     MODEL_INPUT) for k in MODEL_KEYS},
        "release_x0": _variable([float(r["x0"]) for r in runs], dims, "m", *given),
        "release_n_cycles": _variable([int(r["n_cycles"]) for r in runs], dims, "1", "cycles run", MODEL_INPUT),
        "release_outcome": _variable([f[0] for f in found], dims, None, "how the run ended", CLASSIFICATION),
        "release_cycles": _variable([f[1] for f in found], dims, "1", "complete cycles"),
        "release_velocity": _variable([f[2] for f in found], dims, "m s-1", "velocity before the last impact at a1"),
        "release_next_velocity": _variable([f[3] for f in found], dims, "m s-1",
                                           "velocity before the second impact at a1 (NaN if none)"),
    }


def zone_shift(p: Parameters, release: float) -> float:
    """``dT2`` of the first passage through the zone (a1, a2), from the exact solver's events, for a release
    from rest at ``-release`` (s): the time in the zone less the free swing's over the same phase."""
    run = solve_exact(p, -release, n_cycles=1, record_trajectory=False)
    ev = run.events
    first = ev.of_kind(EventKind.IMPACT_A1)
    if not len(first) or first[0] + 1 >= len(ev) or ev.kind[first[0] + 1] != EventKind.ZONE_END_A2:
        raise ValueError(f"F = {p.F!r} N, zone ({p.a1}, {p.a2}): no passage through the zone ({run.message})")
    i, w = first[0], p.omega
    advance = math.atan2(ev.x[i + 1], ev.v_before[i + 1] / w) - math.atan2(ev.x[i], ev.v_after[i] / w)
    return float(ev.t[i + 1] - ev.t[i]) - advance / w


def _airy(spec: Mapping) -> dict[str, xr.DataArray]:
    """``dT2`` (:func:`zone_shift`) of each zone ``[a1, a2]`` of ``spec`` at each of its ``forces``, on the model's
    M, K and b, released from rest at ``-release``."""
    zones, forces, release = list(spec["zones"].values()), [float(F) for F in spec["forces"]], float(spec["release"])
    given = {key: float(spec[key]) for key in ("M", "K", "b")}
    shifts = [[zone_shift(Parameters(F=F, a1=float(a), a2=float(c), **given), release) for F in forces]
              for a, c in zones]
    return {"airy_zone_start": _variable([float(a) for a, _ in zones], "airy_zone", "m", "start of the impulse zone",
                                         MODEL_INPUT),
            "airy_zone_end": _variable([float(c) for _, c in zones], "airy_zone", "m", "end of the impulse zone",
                                       MODEL_INPUT),
            "airy_force": _variable(forces, "airy_force", "N", "force over the impulse zone", MODEL_INPUT),
            "airy_zone_shift": _variable(shifts, ("airy_zone", "airy_force"), "s", "time one passage through the "
                                         "zone adds to the free swing, released from rest at -release",
                                         release=release, **given)}


def _short_runs(runs: list[Mapping]) -> dict[str, xr.DataArray]:
    """Each run (a Fig. 3 case at its own K and release ``x0``) from rest over ``n_cycles``: its events, NaN after
    the last."""
    solved = [solve_exact(Parameters.from_mapping(r), float(r["x0"]), n_cycles=positive_int(
        "n_cycles", r["n_cycles"], 1000), record_trajectory=False).events for r in runs]
    table = np.full((5, len(runs), max(len(e) for e in solved)), np.nan)
    for i, e in enumerate(solved):
        table[:, i, :len(e)] = e.t, e.kind, e.x, e.v_before, e.v_after
    dims, case = ("short_run", "short_event"), str(runs[0]["label"])
    return {"short_K": _variable([float(r["K"]) for r in runs], "short_run", "N m-1", "spring constant of the run",
                                 MODEL_INPUT, case=case, n_cycles=int(runs[0]["n_cycles"])),
            "short_x0": _variable([float(r["x0"]) for r in runs], "short_run", "m", "released from rest at",
                                  MODEL_INPUT),
            **{f"short_event_{name}": _variable(values, dims, units, long_name) for values, (name, units, long_name)
               in zip(table, (("time", "s", "time of the event"),
                              ("kind", "1", "kind of the event: 1 impact at a1, 2 end of the impulse at a2, 3 impact "
                                            "at a3, 4 end of the impulse at a4"),
                              ("position", "m", "position of the event"),
                              ("velocity_before", "m s-1", "velocity just before the event"),
                              ("velocity_after", "m s-1", "velocity just after the event")))}}


def _padded(rows: list, dims: tuple[str, str], units: str, long_name: str, **attrs) -> xr.DataArray:
    """Rows of different lengths as one variable, NaN after the end of each."""
    table = np.full((len(rows), max(len(r) for r in rows)), np.nan)
    for row, values in zip(table, rows):
        row[:len(values)] = values
    return _variable(table, dims, units, long_name, **attrs)


def _crossings(spec: Mapping) -> dict[str, xr.DataArray]:
    """Each Fig. 3 case of ``spec`` run as Fig. 3 runs it, sampled ``samples_per_period`` times per natural
    period: the crossings of the section x = a1 with xdot > 0 in each cycle
    (:func:`escapement.studies.poincare.section_crossing_counts`)."""
    counts = []
    for case in spec["cases"]:
        p = Parameters.from_mapping(case)
        run = solve_exact(p, float(case["x0"]), n_cycles=positive_int("n_cycles", case["n_cycles"], 100_000))
        t = np.linspace(0.0, run.t_final, int(spec["samples_per_period"] * run.t_final / p.natural_period))
        x, v, _ = run.sample(t)
        counts.append(section_crossing_counts(t, x, v, p.a1, run.events.t[run.events.kind == int(
            EventKind.IMPACT_A1)]))
    # the labels beside their dimension, not its coordinate: CF's coordinate variables are numbers
    return {"crossing_case_label": _variable([c["label"] for c in spec["cases"]], "crossing_case", None,
                                             "Fig. 3 case", MODEL_INPUT),
            "crossings": _padded(counts, ("crossing_case", "crossing_cycle"), "1", "crossings of x = a1 with xdot > "
                                 "0 from one impact at a1 to the next, on the sampled trajectory (NaN after the last)",
                                 samples_per_period=int(spec["samples_per_period"]))}


def _windows(runs: list[Mapping]) -> dict[str, xr.DataArray]:
    """Each run (the model's keys and ``x0``) from rest to the end of Fig. 4's later printed window: the times of
    its impacts at a1 and a3."""
    t_end = max(panel("4", name).x.high for name in ("velocity", "acceleration"))
    impacts = []
    for r in runs:
        e = solve_exact(Parameters.from_mapping(r), float(r["x0"]), t_end=t_end, record_trajectory=False).events
        impacts.append(e.t[(e.kind == int(EventKind.IMPACT_A1)) | (e.kind == int(EventKind.IMPACT_A3))])
    return {**{f"window_{k}": _variable([float(r[k]) for r in runs], "window_run", PARAMETERS[k].units,
                                        PARAMETERS[k].long_name, MODEL_INPUT) for k in ("F", "K")},
            "window_x0": _variable([float(r["x0"]) for r in runs], "window_run", "m", "released from rest at",
                                   MODEL_INPUT),
            "window_impact_time": _padded(impacts, ("window_run", "window_impact"), "s", "time of each impact at a1 "
                                          "or a3 (NaN after the last)", t_end=t_end)}


def probe_variables(probes: Mapping) -> dict[str, xr.DataArray]:
    """The variables of the runs ``probes`` names: ``first_swings``, ``releases``, ``short_runs`` and ``windows``
    (lists of runs), ``return_map``, ``phase_shift``, ``grazing``, ``airy`` and ``crossings`` (one each), whichever
    it holds."""
    found: dict[str, xr.DataArray] = {}
    if probes.get("first_swings"):
        found.update(_first_swings(list(probes["first_swings"])))
    if "return_map" in probes:
        found.update(_return_map(probes["return_map"]))
    if "phase_shift" in probes:
        found.update(_phase_shift(probes["phase_shift"]))
    if "airy" in probes:
        found.update(_airy(probes["airy"]))
    if "crossings" in probes:
        found.update(_crossings(probes["crossings"]))
    if probes.get("windows"):
        found.update(_windows(list(probes["windows"])))
    if probes.get("short_runs"):
        found.update(_short_runs(list(probes["short_runs"])))
    if probes.get("releases") or "grazing" in probes:
        found.update(_releases(list(probes.get("releases", [])), probes.get("grazing")))
    return found
