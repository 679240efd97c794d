"""The simulation jobs: a scene's settings in, its netCDF file out (its wall times, if it measures any, in a CSV
file); a map planned in chunks runs one job a chunk, and :func:`gather` joins their files."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from importlib import import_module

from ..io.netcdf import read_netcdf, write_csv, write_netcdf
from .logs import logged
from .tables import TIMING_COLUMNS, read_timings

__all__ = ["SCENES", "gather", "simulate"]

#: the module of each kind's scene function, which has the kind's name (imported by its job alone: the long run
#: and the checks bring mpmath, the maps the ensemble)
SCENES = {**dict.fromkeys(("poincare_map", "shock_detail", "phase_diagram"), "figures"),
          **dict.fromkeys(("escapement_error", "existence_map", "stability_map"), "maps"),
          **dict.fromkeys(("long_run", "checks"), "runs")}


def simulate(kind: str, scene, outputs: Mapping[str, str], log: str, rule: str = "") -> None:
    """The dataset of ``scene`` (its settings, checked at planning, or their mapping) of the kind ``kind`` to
    ``outputs["nc"]``, its history naming the rule; its wall times, if it measures any, to ``outputs["timing"]``."""
    make = getattr(import_module(f"..scenes.{SCENES[kind]}", __package__), kind)
    with logged(log, kind) as logger:
        logger.info("%s: settings %s", outputs["nc"], scene)
        made = make(scene["cases"], scene["n_cycles"], scene.get("probes")) if kind == "checks" else make(scene)
        ds, timings = made if isinstance(made, tuple) else (made, {})
        if "outcome" in ds.attrs:
            logger.info("outcome: %s: %s", ds.attrs["outcome"], ds.attrs["outcome_message"])
        for key, seconds in timings.items():
            logger.info("%s: %.3e", key, seconds)
        _write(ds, timings, outputs, f"escapement workflow, rule {rule or kind}: {outputs['nc']}")


def gather(kind: str, parts: Sequence[str], timings: Sequence[str], outputs: Mapping[str, str], log: str,
           rule: str = "") -> None:
    """The map of the kind ``kind`` from the files of its chunks (``parts``, in order, and their ``timings``, if it
    measures any) to ``outputs`` as :func:`simulate` writes them."""
    from ..scenes.maps import gather as joined

    with logged(log, kind) as logger:
        logger.info("%s: %d chunks %s", outputs["nc"], len(parts), ", ".join(parts))
        ds, timing = joined([read_netcdf(path) for path in parts], [read_timings(path) for path in timings])
        _write(ds, timing, outputs, f"escapement workflow, rule {rule or kind}: {outputs['nc']}")


def _write(ds, timings: Mapping[str, float], outputs: Mapping[str, str], history: str) -> None:
    write_netcdf(ds, outputs["nc"], history=history)
    if "timing" in outputs:
        write_csv([{"measurement": k, "seconds": repr(float(v))} for k, v in timings.items()], TIMING_COLUMNS,
                  outputs["timing"])
