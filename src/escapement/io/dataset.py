"""From a run to CF-1.11 datasets: per-cycle table, samples, impacts, and attributes."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..model.events import EventKind
from ..solvers.result import Solution
from .provenance import REFERENCE, history_line, source_string

__all__ = [
    "cycle_variables",
    "sample_variables",
    "impact_variables",
    "event_variables",
    "global_attributes",
    "dataset",
    "table_dataset",
]

CYCLE_VARIABLES = {
    "impact_time": ("s", "time of impact k at a1 (start of cycle k)"),
    "velocity_before_impact": ("m s-1", "velocity just before impact k at a1"),
    "period": ("s", "time from impact k to impact k+1 at a1"),
    "amplitude": ("m", "largest displacement between impact k and impact k+1 (right turning point)"),
}


def cycle_variables(solution: Solution) -> dict[str, xr.DataArray]:
    """The Poincare map per cycle, on the coordinate ``cycle`` = 1 .. N."""
    cycles = solution.cycles
    coords = {"cycle": ("cycle", cycles.cycle.astype(np.int32), {"long_name": "cycle number", "units": "1"})}
    return {
        name: xr.DataArray(getattr(cycles, name), dims="cycle", coords=coords, attrs={"units": u, "long_name": ln})
        for name, (u, ln) in CYCLE_VARIABLES.items()
    }


def time_coordinate(t: np.ndarray) -> dict:
    return {"t": ("t", np.asarray(t, dtype=float), {"units": "s", "long_name": "time since release"})}


def sample_variables(solution: Solution, t: np.ndarray, acceleration: bool = False) -> dict[str, xr.DataArray]:
    """Displacement, velocity (and the smooth part of the acceleration) at times ``t``."""
    x, v, a = solution.sample(t)
    coords = time_coordinate(t)
    out = {
        "displacement": xr.DataArray(x, dims="t", coords=coords, attrs={"units": "m", "long_name": "displacement x"}),
        "velocity": xr.DataArray(v, dims="t", coords=coords, attrs={"units": "m s-1", "long_name": "velocity dx/dt"}),
    }
    if acceleration:
        out["acceleration"] = xr.DataArray(
            a,
            dims="t",
            coords=coords,
            attrs={
                "units": "m s-2",
                "long_name": "acceleration d2x/dt2 between impacts",
                "comment": "the impulsive part at each impact is the variable impulse divided by M",
            },
        )
    return out


def impact_variables(solution: Solution, window: tuple[float, float] | None = None) -> dict[str, xr.DataArray]:
    """Every impact (optionally those inside ``window``) with its impulse and dissipated energy."""
    ev = solution.events
    keep = (ev.kind == int(EventKind.IMPACT_A1)) | (ev.kind == int(EventKind.IMPACT_A3))
    if window is not None:
        keep &= (ev.t >= window[0]) & (ev.t <= window[1])
    m = solution.params.M
    vb, va = ev.v_before[keep], ev.v_after[keep]
    dims = "impact"
    table = {
        "impact_time": (ev.t[keep], "s", "time of the impact"),
        "impact_position": (ev.x[keep], "m", "position of the impact (a1 or a3)"),
        "velocity_before": (vb, "m s-1", "velocity just before the impact"),
        "velocity_after": (va, "m s-1", "velocity just after the impact"),
        "impulse": (m * (va - vb), "N s", "impulse of the impact force, M (v+ - v-)"),
        "energy_dissipated": (0.5 * m * (vb**2 - va**2), "J", "kinetic energy dissipated by the impact"),
    }
    return {
        name: xr.DataArray(values, dims=dims, attrs={"units": u, "long_name": ln})
        for name, (values, u, ln) in table.items()
    }


def event_variables(solution: Solution, window: tuple[float, float] | None = None) -> dict[str, xr.DataArray]:
    """Every event (impacts and ends of the impulse), optionally inside ``window``."""
    ev = solution.events
    keep = np.ones(len(ev), dtype=bool)
    if window is not None:
        keep = (ev.t >= window[0]) & (ev.t <= window[1])
    kinds = list(EventKind)
    return {
        "event_time": xr.DataArray(ev.t[keep], dims="event", attrs={"units": "s", "long_name": "time of the event"}),
        "event_kind": xr.DataArray(
            ev.kind[keep].astype(np.int8),
            dims="event",
            attrs={
                "long_name": "kind of event",
                "flag_values": np.array([int(k) for k in kinds], dtype=np.int8),
                "flag_meanings": "impact_at_a1 end_of_impulse_at_a2 impact_at_a3 end_of_impulse_at_a4",
            },
        ),
        "event_position": xr.DataArray(
            ev.x[keep], dims="event", attrs={"units": "m", "long_name": "position of the event"}
        ),
        "event_velocity_before": xr.DataArray(
            ev.v_before[keep], dims="event", attrs={"units": "m s-1", "long_name": "velocity just before the event"}
        ),
        "event_velocity_after": xr.DataArray(
            ev.v_after[keep], dims="event", attrs={"units": "m s-1", "long_name": "velocity just after the event"}
        ),
    }


def global_attributes(title: str, scene: str, **extra) -> dict:
    """CF-1.11 global attributes with provenance; ``extra`` adds numeric or text attributes."""
    attrs = {
        "Conventions": "CF-1.11",
        "title": title,
        "institution": "escapement replication project",
        "source": source_string(),
        "history": history_line(f"created by escapement for scene {scene}"),
        "references": REFERENCE,
        "comment": "replication with new code: exact event-driven solution of the piecewise-linear model",
        "scene": scene,
    }
    attrs.update(extra)
    return attrs


def dataset(solution: Solution, variables: dict[str, xr.DataArray], title: str, scene: str, **extra) -> xr.Dataset:
    """Assemble a dataset with the run's parameters, outcome and provenance as attributes."""
    attrs = global_attributes(
        title,
        scene,
        solver=solution.method,
        outcome=solution.status.value,
        outcome_message=solution.message,
        x0=solution.x0,
        v0=solution.v0,
        **solution.params.as_dict(),
    )
    attrs.update(extra)
    return xr.Dataset(variables, attrs=attrs)


def table_dataset(columns: dict[str, tuple], title: str, scene: str, **extra) -> xr.Dataset:
    """A table with one row per case: ``columns`` maps a name to ``(values, units, long_name)``;
    ``units`` None marks a text column."""
    n = len(next(iter(columns.values()))[0])
    variables = {}
    for name, (values, units, long_name) in columns.items():
        attrs = {"long_name": long_name} if units is None else {"units": units, "long_name": long_name}
        dtype = object if units is None else None
        variables[name] = xr.DataArray(np.array(values, dtype=dtype), dims="case", attrs=attrs)
    coords = {"case": ("case", np.arange(n, dtype=np.int32), {"long_name": "case number", "units": "1"})}
    return xr.Dataset(variables, coords=coords, attrs=global_attributes(title, scene, **extra))
