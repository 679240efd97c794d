"""The scenes of the paper's kinds of figure (the Poincare map of Fig. 3, the shock detail of Fig. 4, a phase
diagram of Fig. 5), each from its settings to its dataset in one function."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..paper.printed import fixed_point_19
from ..solvers.exact import solve_exact
from .cf import MODEL_INPUT, cycle_variables, dataset, described, event_variables, impact_variables, \
    quantity_attrs, sample_variables, scalar_variable
from .settings import PhaseScene, PoincareScene, ShockScene

__all__ = ["phase_diagram", "poincare_map", "sample_times", "shock_detail"]


def sample_times(grid: np.ndarray, jumps: np.ndarray) -> np.ndarray:
    """The times ``grid`` and, for each jump time inside ``(grid[0], grid[-1]]``, the jump and the largest
    float below it: one sample on each side. The result increases strictly, as CF requires of a coordinate."""
    grid, jumps = (np.asarray(a, dtype=float) for a in (grid, jumps))
    jumps = jumps[(jumps > grid[0]) & (jumps <= grid[-1])]
    return np.union1d(grid, np.concatenate([np.nextafter(jumps, -np.inf), jumps]))


def poincare_map(settings: Mapping | PoincareScene) -> xr.Dataset:
    """The Poincare map of one release per cycle, the amplitude its settings name (on ``amplitude_cycle``: the Step-1
    amplitude has one more value than there are cycles), every event, and Eq. (19)'s fixed point as printed."""
    from ..studies.readings import AMPLITUDES  # the definitions of the amplitude, with the readings

    scene = settings if isinstance(settings, PoincareScene) else PoincareScene.from_mapping(settings)
    run = solve_exact(scene.params, scene.release.x0, scene.release.v0, n_cycles=scene.n_cycles,
                      record_trajectory=scene.amplitude == "largest_abs_displacement")
    variables = {**cycle_variables(run), **event_variables(run)}
    cycle, values = AMPLITUDES[scene.amplitude].values(run)
    if scene.amplitude not in variables:
        axis = ("amplitude_cycle", cycle, described("1", "cycle number of the amplitude"))
        variables[scene.amplitude] = xr.DataArray(values, dims="amplitude_cycle", coords={"amplitude_cycle": axis},
                                                  attrs=quantity_attrs(scene.amplitude))
    variables["fixed_point_19"] = scalar_variable(fixed_point_19(scene.params), "m s-1", "fixed point of the map (17) "
                                                  "by Eq. (19) as printed (velocity before impact)")
    return dataset(
        run, variables, title=scene.study.title("fig3"), scene="poincare_map",
        summary=("This file holds the Poincare map of one run released at x0 with velocity v0: per cycle, the "
                 "velocity just before the impact at a1, the period and the largest displacement, for n_cycles "
                 "cycles, and the amplitude named by amplitude_variable; every event of the run (impacts and ends "
                 "of the impulse zones); and the fixed point of Eq. (19) as printed."),
        **scene.study.attributes(), n_cycles=scene.n_cycles, amplitude_variable=scene.amplitude)


def shock_detail(settings: Mapping | ShockScene) -> xr.Dataset:
    """The motion, impacts and events over the union of the velocity and acceleration windows, and the windows."""
    scene = settings if isinstance(settings, ShockScene) else ShockScene.from_mapping(settings)
    (v_lo, v_hi), (a_lo, a_hi) = scene.velocity_window, scene.acceleration_window
    lo, hi = min(v_lo, a_lo), max(v_hi, a_hi)
    run = solve_exact(scene.params, scene.release.x0, scene.release.v0, t_end=hi)
    grid = np.linspace(lo, hi, int(round((hi - lo) * scene.samples_per_second)) + 1)
    variables = sample_variables(run, sample_times(grid, run.events.t), acceleration=True)
    variables.update({**impact_variables(run, window=(lo, hi)), **event_variables(run, window=(lo, hi))})
    for name, window in (("velocity", scene.velocity_window), ("acceleration", scene.acceleration_window)):
        variables[f"{name}_window"] = xr.DataArray(np.array(window), dims="window_edge", attrs=described(
            "s", f"time window [start, end] of the {name} panel", coverage_content_type=MODEL_INPUT))
    variables["samples_per_second"] = scalar_variable(
        float(scene.samples_per_second), "s-1", "sampling rate of the uniform time grid", MODEL_INPUT)
    return dataset(
        run, variables, title=scene.study.title("fig4"), scene="shock_detail",
        summary=("This file holds the shock detail of one run released at x0 with velocity v0: displacement, "
                 "velocity and the smooth part of the acceleration sampled over the union of the velocity and "
                 "acceleration windows, on a uniform grid of samples_per_second with, at each event, a sample at "
                 "the largest float below its time and one at its time; the impacts in the window with their "
                 "impulse and dissipated energy; and every event in the window."),
        **scene.study.attributes())


def phase_diagram(settings: Mapping | PhaseScene) -> xr.Dataset:
    """The phase trajectory from release to the end of cycle ``n_cycles``, the per-cycle map and every impact."""
    scene = settings if isinstance(settings, PhaseScene) else PhaseScene.from_mapping(settings)
    run = solve_exact(scene.params, scene.release.x0, scene.release.v0, n_cycles=scene.n_cycles)
    period = scene.params.natural_period
    end = run.t_final if np.isfinite(run.t_final) else (scene.n_cycles + 1) * period
    impacts = run.events.t[np.isin(run.events.kind, [int(EventKind.IMPACT_A1), int(EventKind.IMPACT_A3)])]
    grid = np.linspace(0.0, end, int(np.ceil(end / period * scene.samples_per_period)) + 1)
    variables = sample_variables(run, sample_times(grid, impacts))
    variables.update({**cycle_variables(run), **impact_variables(run)})
    return dataset(
        run, variables, title=scene.study.title("fig5"), scene="phase_diagram",
        summary=("This file holds one phase diagram: one run released at x0 with velocity v0, from t = 0 to the end of "
                 "cycle n_cycles, its displacement and velocity sampled samples_per_period times per natural period 2 "
                 "pi sqrt(M/K) with, at each impact, a sample at the largest float below its time and one at its time; "
                 "the per-cycle Poincare map; and every impact with its impulse and dissipated energy."),
        **scene.study.attributes(), n_cycles=scene.n_cycles, samples_per_period=scene.samples_per_period)
