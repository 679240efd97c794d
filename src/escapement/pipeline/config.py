"""The workflow's configuration: checked in one place, and each scene built from it.

:func:`config_error` (and :func:`check_config`, which raises it) gives one clear line for the
first problem: a violation of the JSON schema (draft 2020-12, put in words by
:mod:`escapement.pipeline.config_schema`), a cross-field rule, or a scene whose parameters do not
make a valid model, e.g. ``model.M = 0.0 is invalid: M must be a number > 0 (kg)``. The files the
configuration is read from, and the nested values of ``--config``, are read strictly by
:mod:`escapement.pipeline.config_files`.

The other functions build what each rule runs from the configuration, as plain sorted dicts
(so that reordering the file does not make Snakemake see changed params): the common ``model``
block merged with the scene's own keys, later keys winning.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import yaml

from ..model.parameters import ParameterError, Parameters, check_initial_state
from .config_files import ConfigError, check_config_file
from .config_schema import schema_error

__all__ = [
    "ConfigError",
    "benchmark_scene",
    "benchmark_settings",
    "check_cases",
    "check_config",
    "check_config_file",
    "config_error",
    "escapement_error_forces",
    "escapement_error_scenes",
    "fig3_release",
    "fig3_scene",
    "fig4_scene",
    "FIG5_PER_PANEL",
    "fig5_label_collision",
    "fig5_labels",
    "fig5_scene",
    "long_run_scene",
    "scenes",
    "schema_error",
    "stability_axes",
    "stability_chunk",
    "stability_chunks",
    "stability_model",
]


# ---------------------------------------------------------------------------------------------
# Scenes


def _scene(*blocks: Mapping) -> dict:
    """Merge blocks (later ones win), leaving out nested blocks, sorted by key."""
    merged: dict = {}
    for block in blocks:
        merged.update({k: v for k, v in block.items() if not isinstance(v, dict)})
    return dict(sorted(merged.items()))


def fig3_scene(config: Mapping, case: str) -> dict:
    """Fig. 3, one case: the model block, the case's keys, ``n_cycles`` and ``amplitude``."""
    scene = config["fig3"]
    return _scene(config["model"], scene["cases"][case],
                  {"n_cycles": scene["n_cycles"], "amplitude": scene["amplitude"]})


def fig4_scene(config: Mapping) -> dict:
    return _scene(config["model"], config["fig4"])


def fig5_labels(config: Mapping) -> list[str]:
    """File labels of the Fig. 5 panels, one per spring constant: ``0.1``, ``1``, ``10``."""
    return [f"{k:g}" for k in config["fig5"]["K"]]


def fig5_label_collision(spring_constants: list) -> str | None:
    """The problem, if two of ``spring_constants`` would write the same Fig. 5 file."""
    labels = [f"{k:g}" for k in spring_constants]
    for label in labels:
        same = [k for k, other in zip(spring_constants, labels) if other == label]
        if len(same) > 1:
            return (
                f"fig5.K = {list(spring_constants)!r} is invalid: K must be spring constants that differ "
                f"in their file labels ({' and '.join(repr(k) for k in same)} would both write K_{label}.nc)"
            )
    return None


#: the Fig. 5 keys that may be given one per panel (a list as long as ``fig5.K``)
FIG5_PER_PANEL = ("F", "x0")


def fig5_scene(config: Mapping, label: str) -> dict:
    """Fig. 5, the panel of the spring constant labelled ``label``: a key given as a list (one
    value per spring constant, :data:`FIG5_PER_PANEL`) takes the panel's value."""
    fig5 = config["fig5"]
    index = fig5_labels(config).index(label)
    scene = {k: (v[index] if k in FIG5_PER_PANEL and isinstance(v, list) else v)
             for k, v in fig5.items() if k != "K"}
    return _scene(config["model"], scene, {"K": fig5["K"][index]})


def check_cases(config: Mapping) -> list[dict]:
    """The runs of the claims register (config: checks), each labelled with its group."""
    checks = config["checks"]
    base = _scene(config["model"], {"F": checks["F"], "x0": checks["x0"]})
    cases = [
        _scene(base, {"group": "paper", "label": f"fig3{c}"}, fig3_scene(config, c)) for c in config["fig3"]["cases"]
    ]
    for ic in checks["initial_conditions"]:
        cases.append(_scene(base, ic, {"group": "initial_condition", "label": f"F={ic['F']:g},x0={ic['x0']:g}"}))
    for b in checks["b"]:
        cases.append(_scene(base, {"b": b, "group": "b", "label": f"b={b:g}"}))
    for group in ("symmetric", "asymmetric"):
        for force in checks[group]["F"]:
            for positions in checks[group]["positions"]:
                keys = dict(zip(("a1", "a2", "a3", "a4"), positions))
                label = f"F={force:g}," + ",".join(f"{k}={v:g}" for k, v in keys.items())
                cases.append(_scene(base, keys, {"F": force, "group": group, "label": label}))
    # runs that hold all but one parameter fixed: each K of Fig. 5 (from its panel's x0) at each force of
    # the figure, so that the spring constants are compared at one force; releases at one force; forces at
    # one release
    panels = {label: fig5_scene(config, label) for label in fig5_labels(config)}
    for force in sorted({panel["F"] for panel in panels.values()}):
        for panel in panels.values():
            cases.append(_scene(base, {"K": panel["K"], "x0": panel["x0"], "F": force, "group": "common_force",
                                       "label": f"K={panel['K']:g},F={force:g}"}))
    if "releases" in checks:
        force = checks["releases"]["F"]
        cases += [_scene(base, {"F": force, "x0": x0, "group": "release", "label": f"F={force:g},x0={x0:g}"})
                  for x0 in checks["releases"]["x0"]]
    if "forces" in checks:
        x0 = checks["forces"]["x0"]
        cases += [_scene(base, {"F": force, "x0": x0, "group": "force", "label": f"F={force:g},x0={x0:g}"})
                  for force in checks["forces"]["F"]]
    return [{k: v for k, v in case.items() if k not in ("n_cycles", "amplitude")} for case in cases]


def fig3_release(config: Mapping, block: str) -> dict:
    """The scene of the Fig. 3 case that ``block`` (benchmark, long_run) names by its ``case``: the model block
    and the case's own keys (F, x0, any override), as Fig. 3 runs it; the block's other keys are its own."""
    case = config["fig3"]["cases"][config[block]["case"]]
    return _scene(config["model"], case, {k: v for k, v in config[block].items() if k != "case"})


def benchmark_scene(config: Mapping) -> dict:
    scene = fig3_release(config, "benchmark")
    return {k: v for k, v in scene.items() if "settings" not in k}


def benchmark_settings(config: Mapping, slow: bool = False) -> dict[str, list]:
    """Settings per method: the default ones, and with ``slow`` the slow ones too (merged,
    largest first)."""
    settings = {k: list(v) for k, v in config["benchmark"]["settings"].items()}
    if slow:
        for method, values in config["benchmark"]["slow_settings"].items():
            settings[method] = sorted(set(settings.get(method, [])) | set(values), reverse=True)
    return dict(sorted(settings.items()))


def escapement_error_forces(config: Mapping) -> list[float]:
    """The forces of the escapement-error study: ``n`` values spaced geometrically from ``start`` to
    ``stop`` (N)."""
    axis = config["escapement_error"]["F"]
    start, stop, n = float(axis["start"]), float(axis["stop"]), int(axis["n"])
    return [start] if n == 1 else [start * (stop / start) ** (i / (n - 1)) for i in range(n)]


def escapement_error_scenes(config: Mapping) -> dict[str, dict]:
    """The model of each impulse zone of the escapement-error study (the second half cycle mirrors
    the first), without F."""
    return {name: _scene(config["model"], {"a1": a1, "a2": a2, "a3": -a1, "a4": -a2})
            for name, (a1, a2) in config["escapement_error"]["zones"].items()}


def long_run_scene(config: Mapping) -> dict:
    return fig3_release(config, "long_run")


def stability_axes(config: Mapping) -> tuple[list[float], list[float]]:
    """Values of b (the cell centres of (start, stop)) and of F (start to stop, ends included)."""
    b, f = config["stability_map"]["b"], config["stability_map"]["F"]
    step = (b["stop"] - b["start"]) / b["n"]
    b_values = [b["start"] + (i + 0.5) * step for i in range(b["n"])]
    f_values = [f["start"] + (f["stop"] - f["start"]) * j / max(f["n"] - 1, 1) for j in range(f["n"])]
    return b_values, f_values


def stability_chunks(config: Mapping) -> list[str]:
    return [str(i) for i in range(config["stability_map"]["chunks"])]


def stability_chunk(config: Mapping, chunk: str) -> tuple[list[float], list[float]]:
    """The b values of one chunk (of equal size, the last one shorter), and all F values."""
    b_values, f_values = stability_axes(config)
    size = -(-len(b_values) // config["stability_map"]["chunks"])
    i = int(chunk)
    return b_values[i * size : (i + 1) * size], f_values


def stability_model(config: Mapping) -> dict:
    """The model block for the map (F is set per point)."""
    return _scene(config["model"], {"F": 0.0})


def scenes(config: Mapping) -> dict[str, dict]:
    """Every scene that a job runs, by where it comes from in the configuration; for the map,
    its four corners."""
    found = {f"fig3.cases.{c}": fig3_scene(config, c) for c in config["fig3"]["cases"]}
    found["fig4"] = fig4_scene(config)
    found.update({f"fig5 (K = {label})": fig5_scene(config, label) for label in fig5_labels(config)})
    found.update({f"checks ({case['label']})": case for case in check_cases(config)})
    found["benchmark"] = benchmark_scene(config)
    found["long_run"] = long_run_scene(config)
    for name, model in escapement_error_scenes(config).items():
        for force in {escapement_error_forces(config)[0], escapement_error_forces(config)[-1]}:
            found[f"escapement_error.zones.{name} (F = {force:g})"] = _scene(model, {"F": force, "x0": 1.0})
    b_values, f_values = stability_axes(config)
    for b in (b_values[0], b_values[-1]):
        for force in (f_values[0], f_values[-1]):
            found[f"stability_map (b = {b:g}, F = {force:g})"] = _scene(
                stability_model(config), {"b": b, "F": force, "x0": 1.0}
            )
    return found


# ---------------------------------------------------------------------------------------------
# Checks


#: the most samples a sampled time series may hold (three float64 arrays: 240 MB)
MAX_SAMPLES = 10_000_000


def _cross_field_error(config: Mapping) -> str | None:
    """Rules that the schema cannot state: distinct Fig. 5 files, windows, chunks, the size of the
    sampled time series (checked before any job, not after the work)."""
    collision = fig5_label_collision(config["fig5"]["K"])
    if collision:
        return collision
    for name in ("velocity_window", "acceleration_window"):
        lo, hi = config["fig4"][name]
        if not lo < hi:
            return f"fig4.{name} = {[lo, hi]!r} is invalid: {name} must be [start, end] with start < end (s)"
        samples = (hi - lo) * config["fig4"]["samples_per_second"]
        if samples > MAX_SAMPLES:
            return (
                f"fig4.samples_per_second = {config['fig4']['samples_per_second']!r} is invalid: over the "
                f"{name} of {hi - lo:g} s it gives {samples:.3g} samples; samples_per_second times the window "
                f"must be at most {MAX_SAMPLES:_}"
            )
    fig5 = config["fig5"]
    for key in FIG5_PER_PANEL:
        if isinstance(fig5[key], list) and len(fig5[key]) != len(fig5["K"]):
            return (f"fig5.{key} = {fig5[key]!r} is invalid: {key} must be one number, or a list of "
                    f"{len(fig5['K'])} numbers, one per spring constant of fig5.K = {fig5['K']!r}")
    if fig5["samples_per_period"] * fig5["n_cycles"] > MAX_SAMPLES:
        return (
            f"fig5.samples_per_period = {fig5['samples_per_period']!r} is invalid: with n_cycles = "
            f"{fig5['n_cycles']!r} it gives {fig5['samples_per_period'] * fig5['n_cycles']:_} samples; "
            f"samples_per_period times n_cycles must be at most {MAX_SAMPLES:_}"
        )
    cases = config["fig3"]["cases"]
    for block in ("benchmark", "long_run"):
        if config[block]["case"] not in cases:
            return (f"{block}.case = {config[block]['case']!r} is invalid: case must be a case of fig3.cases, "
                    f"one of {', '.join(sorted(cases))}")
    chunks, n = config["stability_map"]["chunks"], config["stability_map"]["b"]["n"]
    if chunks > n:
        return f"stability_map.chunks = {chunks!r} is invalid: chunks must be <= b.n = {n}"
    return None


def _scene_error(config: Mapping) -> str | None:
    """The first scene whose parameters or initial state do not make a valid model."""
    for where, scene in scenes(config).items():
        try:
            Parameters.from_mapping(scene)
            if "x0" not in scene:
                raise ParameterError("x0", None, "given (it is missing)")
            check_initial_state(scene["x0"], scene.get("v0", 0.0))
        except ParameterError as err:
            return f"{where}: {err}"
    return None


def _load(schema: Mapping | str | Path) -> Mapping:
    return schema if isinstance(schema, Mapping) else yaml.safe_load(Path(schema).read_text())


def config_error(config: Mapping, schema: Mapping | str | Path) -> str | None:
    """One line for the first problem of ``config`` (the schema's first, then the cross-field
    rules, then every scene's parameters), or None if it is valid. ``schema`` is the schema or
    the path of its YAML file."""
    return schema_error(config, _load(schema)) or _cross_field_error(config) or _scene_error(config)


def check_config(config: Mapping, schema: Mapping | str | Path) -> None:
    """Raise :class:`ConfigError` with :func:`config_error`'s line if ``config`` is invalid."""
    problem = config_error(config, schema)
    if problem is not None:
        raise ConfigError(f"invalid configuration: {problem}")
