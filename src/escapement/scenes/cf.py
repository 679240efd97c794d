"""CF-1.11 and ACDD-1.3 datasets from runs: :func:`run_dataset` holds one run, the scenes' are built of its parts.

The parameters and initial state are 0-d variables with units, never global attributes; counts and text (``solver``,
``outcome``, a scene's ``study``) are global attributes. No CF standard name exists for this model's quantities.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..model.quantities import quantity
from ..solvers.describe import CYCLE_COLUMNS, EVENT_COLUMNS
from ..solvers.result import Solution

__all__ = ["MODEL_SUMMARY", "assemble", "cycle_variables", "dataset", "described", "event_variables",
           "global_attributes", "impact_variables", "parameter_variables", "quantity_attrs", "run_dataset",
           "sample_variables", "scalar_variable", "table_dataset"]

#: The model and its impact law, in the ``summary`` of every file (each file adds what it holds).
MODEL_SUMMARY = (
    "The escapement model of Mao, Fu & Li (2013): a mass M on a linear spring of constant K moves freely, M x'' + K x "
    "= 0, between two impact positions a1 < 0 < a3. Moving right it strikes the escapement at x = a1, moving left at x "
    "= a3; the impact law v+ = (1 - b) v- gives the velocity just after each impact from the velocity just before it "
    "(impact coefficient b). After the impact at a1 a constant force F pushes the mass in +x over the impulse zone "
    "[a1, a2]; after the impact at a3 it pushes in -x over [a4, a3]. The motion is computed exactly from event to "
    "event (closed-form harmonic arcs between the impacts and the ends of the impulse zones), in SI units; cycle k "
    "starts at the k-th impact at a1."
)

DOI = "10.3233/SAV-130800"

#: ISO 19115-1 coverage content types (ACDD-1.3) used here
MODEL_RESULT = "modelResult"
MODEL_INPUT = "auxiliaryInformation"
CLASSIFICATION = "thematicClassification"
QUALITY = "qualityInformation"


def described(units: str | None, long_name: str, **attrs) -> dict:
    """A variable's ``units`` (none for text or flags: ``units`` None), ``long_name`` and further attributes."""
    return ({} if units is None else {"units": units}) | {"long_name": long_name, **attrs}


def quantity_attrs(name: str) -> dict:
    """The units and long name of the quantity ``name`` (:mod:`escapement.model.quantities`)."""
    q = quantity(name)
    return described(q.units, q.long_name)


def cycle_variables(solution: Solution) -> dict[str, xr.DataArray]:
    """The Poincare map per cycle on the coordinate ``cycle`` = 1 .. N, each column as the solvers describe it."""
    cycles = solution.cycles
    coords = {"cycle": ("cycle", cycles.cycle.astype(np.int32), described("1", "cycle number"))}
    return {name: xr.DataArray(getattr(cycles, name), dims="cycle", coords=coords, attrs=described(u, ln))
            for name, (u, ln) in CYCLE_COLUMNS.items()}


def sample_variables(solution: Solution, t: np.ndarray, acceleration: bool = False) -> dict[str, xr.DataArray]:
    """Displacement, velocity (and the smooth part of the acceleration) at times ``t``."""
    coords = {"t": ("t", np.asarray(t, dtype=float), quantity_attrs("t"))}
    names = ("displacement", "velocity", "acceleration")[:2 + acceleration]
    out = {name: xr.DataArray(values, dims="t", coords=coords, attrs=quantity_attrs(name))
           for name, values in zip(names, solution.sample(t))}
    if acceleration:
        out["acceleration"].attrs["comment"] = "the impulsive part at each impact is the variable impulse divided by M"
    return out


def impact_variables(solution: Solution, window: tuple[float, float] | None = None) -> dict[str, xr.DataArray]:
    """Every impact (optionally those inside ``window``) with its impulse and dissipated energy."""
    ev = solution.events
    keep = (ev.kind == int(EventKind.IMPACT_A1)) | (ev.kind == int(EventKind.IMPACT_A3))
    if window is not None:
        keep &= (ev.t >= window[0]) & (ev.t <= window[1])
    m, vb, va = solution.params.M, ev.v_before[keep], ev.v_after[keep]
    table = {
        "impact_time": (ev.t[keep], "s", "time of the impact"),
        "impact_position": (ev.x[keep], "m", "position of the impact (a1 or a3)"),
        "velocity_before": (vb, "m s-1", "velocity just before the impact"),
        "velocity_after": (va, "m s-1", "velocity just after the impact"),
        "impulse": (m * (va - vb), *quantity_attrs("impulse").values()),
        "energy_dissipated": (0.5 * m * (vb**2 - va**2), *quantity_attrs("energy_dissipated").values()),
    }
    return {name: xr.DataArray(values, dims="impact", attrs=described(u, ln))
            for name, (values, u, ln) in table.items()}


def event_variables(solution: Solution, window: tuple[float, float] | None = None) -> dict[str, xr.DataArray]:
    """Every event, optionally inside ``window``, each column as the solvers describe it; the kind as CF flags."""
    ev = solution.events
    keep = np.ones(len(ev), dtype=bool) if window is None else (ev.t >= window[0]) & (ev.t <= window[1])
    flags = {"flag_values": np.array([int(k) for k in EventKind], dtype=np.int8),
             "flag_meanings": " ".join(k.name.lower() for k in EventKind)}
    out = {}
    for name, (field, units, long_name) in EVENT_COLUMNS.items():
        values = getattr(ev, field)[keep]
        out[name] = xr.DataArray(values.astype(np.int8) if units is None else values, dims="event",
                                 attrs=described(units, long_name, **(flags if units is None else {})))
    return out


def scalar_variable(value, units: str, long_name: str, content: str = MODEL_RESULT, **attrs) -> xr.DataArray:
    """A 0-d variable with its units, long name and ACDD coverage content type."""
    return xr.DataArray(value, attrs=described(units, long_name, coverage_content_type=content, **attrs))


def parameter_variables(values: Mapping[str, float]) -> dict[str, xr.DataArray]:
    """One 0-d variable per model parameter or initial-state component in ``values``, by the paper's symbol."""
    return {name: scalar_variable(float(value), *quantity_attrs(name).values(), MODEL_INPUT)
            for name, value in values.items()}


def global_attributes(title: str, scene: str, summary: str, **extra) -> dict:
    """CF-1.11 and ACDD-1.3 global attributes; ``summary`` says what the file holds, ``extra`` adds counts or text."""
    return {
        "Conventions": "CF-1.11, ACDD-1.3",
        "title": title,
        "summary": f"{MODEL_SUMMARY} {summary}",
        "keywords": "vibro-impact, escapement mechanism, impact oscillator, impulsive differential equations, "
                    "Poincare map, non-smooth dynamics, replication",
        "license": "CC-BY-4.0",
        "creator_name": "escapement replication contributors",
        "creator_type": "group",
        "institution": "escapement replication project",
        "references": 'J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in escapement mechanism", '
                      f"Shock and Vibration 20 (2013) 1001-1010, doi:{DOI} (https://doi.org/{DOI})",
        "comment": "replication with new code: exact event-driven solution of the piecewise-linear model",
        "scene": scene,
        **extra,
    }


def assemble(variables: Mapping[str, xr.DataArray], attrs: dict, coords: Mapping | None = None) -> xr.Dataset:
    """The dataset of ``variables``, each with an ACDD ``coverage_content_type``: ``coordinate`` for the coordinates,
    ``thematicClassification`` for flags, and ``modelResult`` where a variable does not give its own."""
    ds = xr.Dataset(dict(variables), coords=coords, attrs=attrs)
    for name, variable in ds.variables.items():
        variable.attrs.setdefault("coverage_content_type", "coordinate" if name in ds.coords else
                                  CLASSIFICATION if "flag_values" in variable.attrs else MODEL_RESULT)
    return ds


def dataset(solution: Solution, variables: dict[str, xr.DataArray], title: str, scene: str, summary: str,
            **extra) -> xr.Dataset:
    """The dataset of a run's ``variables``, its parameters and initial state, and its outcome as attributes."""
    attrs = global_attributes(title, scene, summary, solver=solution.method, outcome=solution.status.value,
                              outcome_message=solution.message, **extra)
    state = {"x0": solution.x0, "v0": solution.v0}
    return assemble({**variables, **parameter_variables({**solution.params.as_dict(), **state})}, attrs)


def run_dataset(solution: Solution) -> xr.Dataset:
    """One run of any solver as a CF-1.11 / ACDD-1.3 dataset: the per-cycle table on ``cycle``, every event, the
    end time ``t_final`` and the numbers behind a regime exit (NaN where they do not apply), in doubles.

    Parameters
    ----------
    solution : Solution
        A run of any solver.

    Returns
    -------
    xarray.Dataset
        The dataset, in memory.

    Examples
    --------
    >>> from escapement import Parameters, solve_exact
    >>> from escapement.scenes import run_dataset
    >>> run = solve_exact(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), x0=1.0, n_cycles=3)
    >>> ds = run_dataset(run)
    >>> ds.sizes["cycle"], ds.sizes["event"], ds.attrs["outcome"]
    (3, 15, 'completed')
    >>> ds["period"].attrs["units"], bool(ds["period"][0] == run.cycles.period[0])
    ('s', True)
    """
    variables = {**cycle_variables(solution), **event_variables(solution)}
    variables = {name: da.astype(float) if da.dtype == object else da for name, da in variables.items()}
    variables["t_final"] = scalar_variable(
        float(solution.t_final), "s", "end of the computed trajectory (inf: the free oscillation goes on for ever)")
    exit_numbers = {
        "exit_turning_point": ("m", "where the motion turns at a regime exit (radius of the free swing when stopped)"),
        "exit_margin": ("m", "how far short of the awaited position the motion turns at a regime exit"),
        "exit_t_accumulation": ("s", "time at which the rebounds of a chattering run accumulate"),
    }
    for name, (units, long_name) in exit_numbers.items():
        value = float(getattr(solution.exit, name.removeprefix("exit_")))
        variables[name] = scalar_variable(value, units, f"{long_name}; NaN where it does not apply")
    return dataset(
        solution, variables, title=f"One run of the escapement model, solver {solution.method}", scene="run",
        summary="This file holds one run released at x0 with velocity v0: per cycle (the Poincare map on the section "
                "x = a1, v > 0), the time of the impact at a1, the velocity just before it, the period and the largest "
                "displacement; every event of the run (impacts and ends of the impulse zones); the end of the computed "
                "trajectory; and the numbers behind a regime exit, if the run left the escapement regime.",
        n_cycles=len(solution.cycles), n_events=len(solution.events))


def table_dataset(columns: dict[str, tuple], title: str, scene: str, summary: str, **extra) -> xr.Dataset:
    """A table with one row per case: ``columns`` maps a name to ``(values, units, long_name)`` or
    ``(values, units, long_name, coverage_content_type)``; ``units`` None marks a text column."""
    n = len(next(iter(columns.values()))[0])
    variables = {}
    for name, (values, units, long_name, *content) in columns.items():
        attrs = described(units, long_name, **({"coverage_content_type": content[0]} if content else {}))
        variables[name] = xr.DataArray(np.array(values, dtype=object if units is None else None), dims="case",
                                       attrs=attrs)
    coords = {"case": ("case", np.arange(n, dtype=np.int32), described("1", "case number"))}
    return assemble(variables, global_attributes(title, scene, summary, **extra), coords)
