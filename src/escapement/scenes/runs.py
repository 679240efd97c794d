"""The replication's own runs, each from its settings to its dataset: the runs of the claims register
(:func:`checks`) and the long run against 50 digits (:func:`long_run`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..model.automaton import CHOICES
from ..model.parameters import Parameters
from ..model.quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS
from ..paper.corrected import fixed_point
from ..solvers.exact import solve_exact
from ..studies.poincare import measure_cycle
from ..paper.printed import multiplier_21
from .probes import SETTINGS, named_runs
from .cf import CLASSIFICATION, MODEL_INPUT, MODEL_RESULT, QUALITY, assemble, global_attributes, parameter_variables, \
    scalar_variable, table_dataset
from .settings import LongRunScene, Release, positive_int

__all__ = ["CHECKS_COLUMNS", "checks", "long_run"]

#: the columns of the checks dataset: name: (units, or None for text; long name[, content type])
CHECKS_COLUMNS = {
    "label": (None, "the settings that tell the run apart from the others of its group", MODEL_INPUT),
    "group": (None, "name of the run in the checks block of the configuration", MODEL_INPUT),
    "outcome": (None, "how the run ended", CLASSIFICATION),
    "outcome_message": (None, "how the run ended, in words", CLASSIFICATION),
    "x0": (INITIAL_STATE["x0"].units, f"{INITIAL_STATE['x0'].long_name} (released from rest)", MODEL_INPUT),
    "velocity": ("m s-1", "velocity before impact at the last cycle"),
    "period": ("s", "period of the last cycle"),
    "largest_displacement": ("m", "largest displacement of the last cycle"),
    "multiplier": ("1", "multiplier mu_2 measured from the return map"),
    "multiplier_eq21": ("1", "multiplier (1 - b)**4 of Eq. (21)"),
    "fixed_point_eq16": ("m s-1", "fixed point of the map (16)"),
    "cycles_to_converge": ("1", "first cycle within 1e-9 (relative) of the last velocity; -1 if none"),
    "first_period": ("s", "period of the first cycle"),
    "largest_speed": ("m s-1", "largest |v| on the last cycle, exact from the harmonic arcs"),
    "floquet_major": ("1", "larger Floquet multiplier of the flow over the last period, measured"),
    "floquet_minor": ("1", "smaller Floquet multiplier of the flow over the last period, measured"),
    "continued_at": ("s", "time of the first accumulation of impacts (a Zeno point) the run went on past, from rest at "
                     "the impact position (past_accumulation: continue); NaN if none"),
    **{key: (*SETTINGS[key], MODEL_INPUT) for key in CHOICES},
    **{key: (PARAMETERS[key].units, PARAMETERS[key].long_name, MODEL_INPUT) for key in MODEL_KEYS},
}


def checks(cases: Sequence[Mapping], n_cycles: int, probes: Mapping | None = None) -> xr.Dataset:
    """The runs of the claims register: the table, one row per case run from rest ``n_cycles`` cycles, the Poincare
    map measured at the last; beside it, the runs ``probes`` names (:func:`~escapement.scenes.probes.named_runs`)."""
    n_cycles = positive_int("n_cycles", n_cycles, 100_000)
    runs = [(case, p, Release.from_mapping(case).x0) for case in cases for p in [Parameters.from_mapping(case)]]
    named = named_runs(probes or {})
    measured = [measure_cycle(p, x0, n_cycles) for _, p, x0 in runs]
    columns = {
        **{key: [c[key] for c, _, _ in runs] for key in ("label", "group")},
        "outcome": [m.outcome for m in measured],
        "outcome_message": [m.message for m in measured],
        "x0": [x0 for _, _, x0 in runs],
        **{name: [getattr(m, name) for m in measured] for name in ("velocity", "period", "largest_displacement",
                                                                   "multiplier", "first_period", "largest_speed")},
        "multiplier_eq21": [multiplier_21(p) for _, p, _ in runs],
        "fixed_point_eq16": [fixed_point(p) for _, p, _ in runs],
        "cycles_to_converge": np.array([m.cycles_to_converge for m in measured], dtype=np.int32),
        **{name: [m.floquet[i] for m in measured] for i, name in enumerate(("floquet_major", "floquet_minor"))},
        # b > 1 reverses the velocity at every impact: the first accumulation comes in the first cycle
        "continued_at": [solve_exact(p, x0, n_cycles=1, record_trajectory=False).exit.t_accumulation
                         if p.past_accumulation == "continue" and m.outcome == "completed" else np.nan
                         for (_, p, x0), m in zip(runs, measured)],
        **{key: [getattr(p, key) for _, p, _ in runs] for key in CHOICES},
        **{key: [getattr(p, key) for _, p, _ in runs] for key in MODEL_KEYS},
    }
    table = {name: (columns[name], *description) for name, description in CHECKS_COLUMNS.items()}
    summary = (
        "This file holds the runs of the claims register, each under its name in the checks block of the "
        "configuration. The table, one row per run (group, its name): each run, with the parameters of its row, "
        "starts from rest at x0 and lasts n_cycles cycles; its fixed point, period, largest displacement and "
        "multiplier are measured at the last cycle, beside the fixed point of Eq. (16) and the multiplier of "
        "Eq. (21); with the first cycle's period, the largest speed on the last cycle and both Floquet multipliers "
        "of the flow over the last period (central differences of the exact flow), the model's choices it ran "
        "(release_force, past_accumulation) and the first accumulation of impacts it went on past (continued_at). "
        "Beside the table, the runs of "
        "another measure (runs from rest and how they end, event tables, the slope of a return map, runs from the "
        "section, passages through impulse zones, crossings of the section per cycle), each with its settings and "
        "what it measures as variables <name>_<variable> on the dimension <name>_run.")
    return table_dataset(table, "Measured Poincare maps for the claims register", "checks", summary, solver="exact",
                         n_cycles=n_cycles).assign(named)


def long_run(settings: Mapping | LongRunScene) -> tuple[xr.Dataset, dict[str, float]]:
    """Each method's errors against 50 digits at the sampled cycles and, apart from them, its wall time."""
    from ..studies.long_run import long_run as errors_of

    scene = settings if isinstance(settings, LongRunScene) else LongRunScene.from_mapping(settings)
    r = errors_of(scene.params, scene.release.x0, scene.n_cycles, scene.ivp_method, scene.ivp_rtol, scene.ivp_cycles)
    coords = {"cycle": ("cycle", r["cycles"].astype(np.int32), {"long_name": "cycle number", "units": "1"})}
    names = {"error_time": ("1", "relative error of the impact time at a1"),
             "error_velocity": ("1", "relative error of the velocity before impact"),
             "drift": ("s", "impact time minus the 50-digit reference")}
    ivp_label = f"solve_ivp {scene.ivp_method} rtol={scene.ivp_rtol:g}"
    variables = {}
    for solver, label in (("exact", "exact solver"), ("closed_form", "per-cycle closed forms"), ("ivp", ivp_label)):
        for (name, (units, long_name)), values in zip(names.items(), r[solver]):
            variables[f"{name}_{solver}"] = xr.DataArray(values, dims="cycle", coords=coords, attrs={
                "units": units, "long_name": f"{long_name}, {label}", "coverage_content_type": QUALITY})
    scalars = (  # variable, key of the study's result, units, long name, content type
        ("max_velocity_deviation", "max_velocity_deviation", "1", "largest relative deviation of the velocity before "
         "impact from the fixed point once converged, exact solver", QUALITY),
        ("max_period_deviation", "max_period_deviation", "1", "largest relative deviation of the period from the limit "
         "cycle's once converged, exact solver", QUALITY),
        ("closed_form_difference", "check_max_relative_difference", "1", "largest relative difference between the "
         "per-cycle closed forms and the exact solver, over the impact time, velocity before impact, period and "
         "largest displacement of every cycle both ran", QUALITY),
        ("fixed_point_velocity", "fixed_point_velocity", "m s-1", "velocity before impact at a1 on the limit cycle, "
         "50-digit reference", MODEL_RESULT),
        ("fixed_point_period", "fixed_point_period", "s", "period of the limit cycle, 50-digit reference",
         MODEL_RESULT),
    )
    for name, key, units, long_name, content in scalars:
        variables[name] = scalar_variable(r[key], units, long_name, content)
    variables.update(parameter_variables({**scene.params.as_dict(), "x0": scene.release.x0}))
    attrs = global_attributes(
        "Long run of the escapement model: error against the number of cycles", "long_run",
        "This file holds the errors against a 50-digit reference of one run released from rest at x0, at cycles "
        "spaced evenly in log: the relative errors of the impact time at a1 and of the velocity before it, and "
        "the drift of the impact time, for the exact solver over check_cycles cycles, for the per-cycle closed "
        "forms (the return map of the squared velocity, Eq. (16), and each cycle's arcs) over n_cycles cycles "
        "and for solve_ivp over ivp_cycles cycles; the largest difference between the closed forms and the exact "
        "solver; the limit cycle of the reference; and the largest deviations of the exact solver from it after "
        "converged_after cycles (any_nan is 1 if the exact run gave a NaN).",
        solver="exact; closed-form cycles; " + ivp_label, ivp_label=ivp_label, n_cycles=scene.n_cycles,
        check_cycles=int(r["check_cycles"]), closed_form_method=r["series_method"], ivp_cycles=scene.ivp_cycles,
        converged_after=int(r["converged_after"]), any_nan=int(r["any_nan"]))
    return assemble(variables, attrs), {"exact_seconds": r["exact_wall_s"],
                                        "closed_form_seconds": r["closed_form_wall_s"], "ivp_seconds": r["ivp_wall_s"]}
