"""The scenes each study runs, built and checked before any job (:func:`plan`): the replication's from
``config/paper.yaml``, and the user's own where a kind's scenes differ from the paper's. A scene's settings are a flat
mapping (the model's keys, its block's and its own, later ones winning).
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..model.automaton import CHOICES
from ..model.limits import MEMORY_BUDGET
from ..model.parameters import ParameterError, Parameters
from ..model.quantities import INITIAL_STATE, PARAMETERS, SYMMETRIC_DEFAULTS
from ..paper.corrected import grazing_release
from ..scenes.settings import (KINDS, REPLICATION, EscapementErrorScene, ExistenceMapScene, LongRunScene, PhaseScene,
                               PoincareScene, Release, ShockScene, SizeError, StabilityMapScene, as_typed)
from ..solvers.ensemble import ensemble_bytes
from .config import ConfigError

__all__ = ["BLOCKS", "MAPS", "REPLICATION_ONLY", "Planned", "changes", "check_runs", "chunks", "leaves", "plan",
           "replication_scenes", "study_scenes"]

#: the blocks a study may change, and the replication's own, which only config/paper.yaml sets
BLOCKS = ("model", *KINDS)
REPLICATION_ONLY = ("checks", "benchmark", "speed", "long_run")
SETTINGS = {"fig3": PoincareScene, "fig4": ShockScene, "fig5": PhaseScene, "escapement_error": EscapementErrorScene,
            "existence_map": ExistenceMapScene, "stability_map": StabilityMapScene}
#: the keys of a scene's mapping that place it, not settings of its run
PLACING = ("study", "label", "changes")
#: each map's rows (the axis its chunks split: each row's trajectories are independent of the others'), and the keys
#: that size one row of a scene, with their values, and the cycles each of its trajectories runs in the ensemble
MAPS = {StabilityMapScene: ("b", lambda s: ({"stability_map.F.n": len(s.F_values)}, 2)),  # the return map's two
        ExistenceMapScene: ("a3", lambda s: ({"existence_map.F.n": len(s.F_values),
                                              "existence_map.n_cycles": s.n_cycles}, s.n_cycles))}


def chunks(scene: object, budget: int = MEMORY_BUDGET) -> int:
    """The jobs ``scene`` runs in: for a map, the fewest chunks of its rows whose ensemble each fits ``budget``
    bytes, else 1; SizeError if one row does not fit."""
    if type(scene) not in MAPS:
        return 1
    axis, size = MAPS[type(scene)]
    keys, cycles = size(scene)
    row_bytes = ensemble_bytes(len(scene.F_values), cycles)
    if row_bytes > budget:
        raise SizeError(keys, row_bytes, budget, f"bytes of the ensemble of one row of {axis}",
                        "a row of the map cannot be split")
    return -(-len(getattr(scene, f"{axis}_values")) // (budget // row_bytes))


@dataclass(frozen=True)
class Planned:
    """A scene as planned: its flat ``settings`` (a rule's param, whose text Snakemake compares to rerun a job),
    the settings object checked from them, and the jobs it runs in (:func:`chunks`)."""

    settings: dict
    checked: object
    chunks: int = 1

    def chunk(self, index: int) -> object:
        """The checked settings of the job ``index`` of a map's :attr:`chunks`: the map over a slice of its rows."""
        field = f"{MAPS[type(self.checked)][0]}_values"
        rows = np.array_split(np.arange(len(getattr(self.checked, field))), self.chunks)[index]
        return dataclasses.replace(self.checked, **{field: getattr(self.checked, field)[rows[0]:rows[-1] + 1]})


def leaves(values: Mapping, prefix: str = "") -> dict:
    """The values of a mapping by dotted key (``F.n``, ``cases.c.x0``), the keys that place a scene left out."""
    out = {}
    for key, value in values.items():
        if isinstance(value, Mapping):
            out.update(leaves(value, f"{prefix}{key}."))
        elif prefix or key not in PLACING:
            out[f"{prefix}{key}"] = value
    return out


def _worded(key: str, value: object) -> str:
    """``value`` with the units of the quantity ``key`` names (``fig5.K``, ``stability_map.F.start``), if any."""
    parts = key.split(".")
    name = parts[-2] if parts[-1] in ("start", "stop") and len(parts) > 1 else parts[-1]
    quantity = {**PARAMETERS, **INITIAL_STATE}.get(name)
    unit = "m" if "zones" in parts[:-1] else quantity.unit_label if quantity and not quantity.dimensionless else ""
    return f"{as_typed(value)} {unit}".rstrip()


def changes(config: Mapping, paper: Mapping) -> dict[str, str]:
    """Each dotted key of the study blocks whose value differs from the paper's (the model with the symmetric
    defaults ``a3 = -a1``, ``a4 = -a2`` filled in), as ``key = value (paper: value)``."""
    mine, theirs = (leaves({**{b: source[b] for b in BLOCKS}, "model": _symmetric(source["model"])})
                    for source in (config, paper))
    return {key: f"{key} = {_worded(key, value)} (paper: {_worded(key, theirs[key]) if key in theirs else 'absent'})"
            for key, value in mine.items() if theirs.get(key, ...) != value}


def _symmetric(model: Mapping) -> dict:
    """``model`` with the symmetric defaults ``a3 = -a1``, ``a4 = -a2`` filled in where the mirror is given."""
    return {**model, **{k: -model[m] for k, m in SYMMETRIC_DEFAULTS.items() if k not in model and m in model}}


def _flat(*parts: Mapping) -> dict:
    """The parts merged (later ones win), nested mappings left out, sorted by key (reordering a file changes none)."""
    return dict(sorted({k: v for part in parts for k, v in part.items() if not isinstance(v, dict)}.items()))


def _per_panel(fig5: Mapping, key: str, index: int, paper: Mapping):
    """Fig. 5's ``key`` for the panel ``index``: one value for every panel, or a list of one per spring constant."""
    value = fig5[key]
    if not isinstance(value, list):
        return value
    if len(value) != len(fig5["K"]):
        typed = "K" if fig5["K"] != paper.get("K") else key
        raise ConfigError(f"fig5.{typed} = {as_typed(fig5[typed])} is invalid: fig5.K gives {len(fig5['K'])} panels "
                          f"and fig5.{key} = {as_typed(value)} one {key} for each of {len(value)}: give fig5.{key} as "
                          f"one number or a list of {len(fig5['K'])}, one per spring constant")
    return value[index]


def _scene_mappings(block: str, model: Mapping, b: Mapping, extra: Mapping, paper: Mapping) -> dict[str, dict]:
    """The flat mapping of each scene of ``block`` by label (a Fig. 3 case, a spring constant; ``""`` for the kinds
    of one scene): the model's keys, the block's, the scene's own and ``extra``; nested axes and zones after them."""
    if block == "fig3":
        return {case: _flat(model, b, keys, extra, {"label": case}) for case, keys in b["cases"].items()}
    if block == "fig5":
        labels = [f"{k:g}" for k in b["K"]]
        if len(set(labels)) < len(labels):
            raise ConfigError(f"fig5.K = {b['K']!r} is invalid: K must be spring constants that differ in "
                              "their file labels (e.g. 0.1 and 0.10000000001 both write K_0.1.nc)")
        return {label: _flat(model, b, {"K": b["K"][i], "F": _per_panel(b, "F", i, paper),
                                        "x0": _per_panel(b, "x0", i, paper)}, extra, {"label": label})
                for i, label in enumerate(labels)}
    nested = {k: v for k, v in b.items() if isinstance(v, dict)}  # the axes, the zones
    return {"": {**_flat(model, b, extra), **nested}}


def study_scenes(study: str, blocks: Mapping, paper: Mapping | None = None) -> dict[str, dict[str, Planned]]:
    """Every scene of ``blocks`` (the model and the kinds' blocks), by kind and label, built and checked by its
    settings class; :class:`ConfigError` naming the block for the first that fails."""
    scenes, tag = {}, "" if study == REPLICATION else f"your study '{study}': "
    for block in [block for block in KINDS if block in blocks]:
        try:
            found = _scene_mappings(block, blocks["model"], blocks[block], {"study": study},
                                    (paper or {}).get(block, {}))
            checked = {label: SETTINGS[block].from_mapping(s) for label, s in found.items()}
            scenes[block] = {label: Planned(found[label], c, chunks(c)) for label, c in checked.items()}
        except (SizeError, ConfigError) as err:
            raise ConfigError(f"{tag}{err}") from None
        except ParameterError as err:
            raise ConfigError(f"{tag}{block}: {err}") from None
    return scenes


def _compared(block: str, model: Mapping, b: Mapping, paper: Mapping) -> list[dict]:
    """What the scenes of ``block`` run, as compared between a study and the paper: their settings without the
    model's keys the kind's data do not depend on, the symmetric defaults filled in."""
    model = _symmetric({k: v for k, v in model.items() if k not in KINDS[block].ignored})
    return [leaves(s) for s in _scene_mappings(block, model, b, {}, paper).values()]


def plan(config: Mapping, paper: Mapping) -> tuple[dict[str, dict], list[str]]:
    """The studies (``replication``, and the user's own by its ``name`` where a kind's scenes differ from the
    paper's), each by kind and label, every scene checked; and the lines saying what changed and what does not run."""
    name = str(config.get("name", "own"))
    given = [b for b in REPLICATION_ONLY if config[b] != paper[b]]
    if given:
        raise ConfigError(f"the configuration: {given[0]} is the replication's own (config/paper.yaml), which a study "
                          f"does not change: leave {given[0]} out of your configuration")
    try:
        Parameters.from_mapping({"F": 0.0, **config["model"]})
    except ParameterError as err:
        raise ConfigError(f"the configuration: model.{err}") from None
    studies = {REPLICATION: study_scenes(REPLICATION, paper)}
    changed = changes(config, paper)
    if not changed:
        return studies, []
    model_keys = [key.split(".", 1)[1] for key in changed if key.startswith("model.")]
    runs, notes = {}, [f"your study '{name}' changes {'; '.join(changed.values())}"]
    for block, kind in KINDS.items():
        reaching = [line for key, line in changed.items() if key.startswith(f"{block}.")
                    or key.startswith("model.") and key[6:] not in kind.ignored]
        try:
            differs = _compared(block, config["model"], config[block], paper[block]) != _compared(
                block, paper["model"], paper[block], paper[block])
        except ConfigError as err:
            raise ConfigError(f"your study '{name}': {err}") from None
        if differs:
            runs[block] = {**config[block], "changes": "; ".join(reaching)}
        elif reaching or any(k in kind.ignored for k in model_keys):
            ignored = [k for k in model_keys if k in kind.ignored]
            own = [k for k in model_keys if k not in kind.ignored]
            why = [kind.why(ignored)] if ignored else []
            why += [f"its scenes set their own {' and '.join(own)}"] if own else []
            notes.append(f"your study '{name}': {block} does not run: "
                         + ("; ".join(why) if why else "its scenes stay the paper's"))
    if not runs:
        return studies, [f"your study '{name}' does not run: nothing you changed ({'; '.join(changed.values())}) "
                         "reaches a scene"] + notes[1:]
    studies[name] = study_scenes(name, {"model": config["model"], **runs}, paper)
    return studies, notes


def replication_scenes(paper: Mapping) -> dict[str, dict]:
    """The replication's own runs, checked: ``checks``, ``benchmark`` and ``long_run`` (on the Fig. 3 case it names)."""
    found = {"checks": check_runs(paper)}
    for block in ("benchmark", "long_run"):
        case = paper[block]["case"]
        if case not in paper["fig3"]["cases"]:
            raise ConfigError(f"{block}.case = {case!r} is invalid: case must be a case of fig3.cases, one of "
                              f"{', '.join(sorted(paper['fig3']['cases']))}")
        found[block] = _flat(paper["model"], paper["fig3"]["cases"][case],
                             {k: v for k, v in paper[block].items() if k != "case"})
    try:
        LongRunScene.from_mapping(found["long_run"])
        Release.from_mapping(found["benchmark"])
    except ParameterError as err:
        raise ConfigError(f"config/paper.yaml: {err}") from None
    return found


def check_runs(paper: Mapping) -> dict:
    """The runs of the ``checks`` block, each checked by the model's rules: the table's (``cases``, each of its
    ``group``) and, by name, those of another ``measure`` (``probes``), for :func:`escapement.scenes.runs.checks`."""
    checks, table, probes = paper["checks"], [], {}
    for name, entry in checks.items():
        if name in ("n_cycles", "x0", "F"):  # the table's defaults
            continue
        base = dict(paper["model"]) if "measure" in entry else {**paper["model"], "F": checks["F"], "x0": checks["x0"]}
        try:
            runs = _runs(paper, entry, base)
            for run in runs:  # the model's bounds and a release, before any job
                Parameters.from_mapping(run)
                Release.from_mapping(run)
        except (ParameterError, ValueError) as err:
            raise ConfigError(f"config/paper.yaml: checks.{name}: {err}") from None
        if "measure" in entry:
            probes[name] = {"measure": entry["measure"], "runs": runs}
        else:
            table += [{**run, "group": name} for run in runs]
    return {"cases": table, "n_cycles": checks["n_cycles"], "probes": probes}


def _derived(paper: Mapping, block: str) -> list[dict]:
    """The runs a checks entry takes ``from`` a block: fig3, its cases; fig5, every K at every F from the panel's x0;
    fig4, every force and release magnitude of the Fig. 3 cases, either side, at every K of fig5."""
    cases, fig5 = paper["fig3"]["cases"].values(), paper["fig5"]
    if block == "fig3":
        return [{"case": case} for case in paper["fig3"]["cases"]]
    if block == "fig5":
        panels = [(k, _per_panel(fig5, "F", i, fig5), _per_panel(fig5, "x0", i, fig5)) for i, k in enumerate(fig5["K"])]
        return [{"K": k, "F": F, "x0": x0} for F in sorted({F for _, F, _ in panels}) for k, _, x0 in panels]
    t_end = max(paper["fig4"][window][1] for window in ("velocity_window", "acceleration_window"))
    return [{"F": F, "K": K, "x0": side * m, "t_end": t_end} for F in sorted({c["F"] for c in cases})
            for K in fig5["K"] for m in sorted({abs(c["x0"]) for c in cases}) for side in (-1.0, 1.0)]


def _runs(paper: Mapping, entry: Mapping, base: Mapping) -> list[dict]:
    """The runs of one entry of the checks block (config/paper.yaml says how its keys read), in order, each a flat
    mapping labelled by the keys that tell it apart from the entry's other runs."""
    swept = {key: list(value.items()) if key == "zones" else value for key, value in entry.items() if key != "runs"
             and (isinstance(value, dict) or isinstance(value, list) and not (key == "positions" and not isinstance(
                 value[0], list)))}
    items = _derived(paper, entry["from"]) if "from" in entry else entry.get("runs", [{}])
    cases, runs = paper["fig3"]["cases"], []
    for item in ({**dict(item), **dict(zip(swept, combination))} for item in items
                 for combination in itertools.product(*swept.values())):
        keys, run = {**{k: v for k, v in entry.items() if k not in swept}, **item}, dict(base)
        if "case" in keys and keys["case"] not in cases:
            raise ValueError(f"case {keys['case']!r} is invalid: a case must be one of fig3.cases, one of "
                             f"{', '.join(sorted(cases))}")
        run.update(cases.get(keys.get("case"), {}))
        for key, value in keys.items():
            if key in ("positions", "zones"):
                name, value = value if key == "zones" else (None, value)
                run.update(zip(("a1", "a2", "a3", "a4"), value if len(value) == 4 else [*value, -value[0], -value[1]]))
                run.update({"zone": name} if name else {})
            elif key not in ("measure", "from", "runs"):
                run[key] = paper[value][key] if isinstance(value, str) and key not in ("case", *CHOICES) else value
        if "side" in run:
            run["x0"] = run["side"] * abs(run["x0"])
        if "offset" in run:
            run["x0"] = -grazing_release(Parameters.from_mapping(run)) * (1 + run["offset"])
        label = [f"fig3{v}" if k == "case" else v[0] if k == "zones" else ",".join(
            f"{a}={p:g}" for a, p in zip(("a1", "a2", "a3", "a4"), v)) if k == "positions" else f"{k}={v:g}"
            for k, v in item.items()]
        runs.append(dict(sorted({**run, "label": ",".join(label)}.items())))
    return runs
