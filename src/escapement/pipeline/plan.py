"""The scenes each study runs, built and checked before any job: the replication's from ``config/paper.yaml``, and
the user's own from the merged configuration, where a kind of figure's scenes then run something the paper's do
not (:func:`plan`).

A scene's settings are a flat mapping: the model's keys, its block's and its own (a Fig. 3 case, a Fig. 5 panel),
later ones winning; the rules pass it as a param, which Snakemake compares by its text to rerun a job. Each is
checked here by its settings class (:mod:`escapement.scenes.settings`: the model's bounds are
:class:`~escapement.model.parameters.Parameters`'). A study's changes are the dotted keys whose value differs from
the paper's (:func:`changes`); each kind's scenes carry those that reach it, which its dataset and figure show.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..model.parameters import ParameterError, Parameters
from ..model.quantities import INITIAL_STATE, PARAMETERS, SYMMETRIC_DEFAULTS
from ..paper.printed_axes import FIG5_PANEL_K
from ..scenes.settings import (
    KINDS,
    REPLICATION,
    EscapementErrorScene,
    ExistenceMapScene,
    LongRunScene,
    PhaseScene,
    PoincareScene,
    Release,
    ShockScene,
    StabilityMapScene,
)
from .config import ConfigError

__all__ = ["BLOCKS", "REPLICATION_ONLY", "Planned", "changes", "check_cases", "check_probes", "leaves", "plan",
           "replication_scenes", "study_scenes"]

#: the blocks a study may change, and the replication's own, which only config/paper.yaml sets
BLOCKS = ("model", *KINDS)
REPLICATION_ONLY = ("checks", "benchmark", "speed", "long_run")
#: each kind's settings, by its block
SETTINGS = {"fig3": PoincareScene, "fig4": ShockScene, "fig5": PhaseScene, "escapement_error": EscapementErrorScene,
            "existence_map": ExistenceMapScene, "stability_map": StabilityMapScene}
#: the keys of a scene's mapping that place it, not settings of its run
PLACING = ("study", "label", "changes")


@dataclass(frozen=True)
class Planned:
    """A scene as planned: its flat ``settings`` (a rule's param, which Snakemake compares by its text to rerun a
    job) and the settings object built and checked from them at planning (a rule's param the job runs)."""

    settings: dict
    checked: object


def leaves(values: Mapping, prefix: str = "") -> dict:
    """The values of a mapping by dotted key (``F.n``, ``cases.c.x0``), the keys that place a scene left out."""
    out = {}
    for key, value in values.items():
        if isinstance(value, Mapping):
            out.update(leaves(value, f"{prefix}{key}."))
        elif prefix or key not in PLACING:
            out[f"{prefix}{key}"] = value
    return out


def _number(value: object) -> str:
    """A value as a configuration gives it: a float by its shortest form (``2`` for 2.0), a list item by item."""
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_number(v) for v in value) + "]"
    return format(value, "g") if isinstance(value, float) and float(format(value, "g")) == value else str(value)


def _worded(key: str, value: object) -> str:
    """``value`` with the units of the quantity ``key`` names (``fig5.K``, ``stability_map.F.start``), if any."""
    parts = key.split(".")
    name = parts[-2] if parts[-1] in ("start", "stop") and len(parts) > 1 else parts[-1]
    quantity = {**PARAMETERS, **INITIAL_STATE}.get(name)
    unit = "m" if "zones" in parts[:-1] else quantity.unit_label if quantity and not quantity.dimensionless else ""
    return f"{_number(value)} {unit}".rstrip()


def changes(config: Mapping, paper: Mapping) -> dict[str, str]:
    """Each dotted key of the study blocks whose value differs from the paper's (the model with the symmetric
    defaults ``a3 = -a1``, ``a4 = -a2`` filled in), as ``key = value (paper: value)``."""
    def flat(source: Mapping) -> dict:
        model = dict(source["model"])
        model.update({k: -model[m] for k, m in SYMMETRIC_DEFAULTS.items() if k not in model})
        return leaves({**{b: source[b] for b in BLOCKS}, "model": model})

    mine, theirs = flat(config), flat(paper)
    return {key: f"{key} = {_worded(key, value)} (paper: {_worded(key, theirs[key]) if key in theirs else 'absent'})"
            for key, value in mine.items() if theirs.get(key, ...) != value}


def _flat(*parts: Mapping) -> dict:
    """The parts merged (later ones win), nested mappings left out, sorted by key: a scene's flat mapping, which
    reordering a file does not change."""
    flat: dict = {}
    for part in parts:
        flat.update({k: v for k, v in part.items() if not isinstance(v, dict)})
    return dict(sorted(flat.items()))


def _per_panel(fig5: Mapping, key: str, index: int, paper: Mapping):
    """Fig. 5's ``key`` for the panel ``index``: one value for every panel, or a list of one per spring constant."""
    value = fig5[key]
    if not isinstance(value, list):
        return value
    if len(value) != len(fig5["K"]):
        typed = "K" if fig5["K"] != paper.get("K") else key
        raise ConfigError(f"fig5.{typed} = {_number(fig5[typed])} is invalid: fig5.K gives {len(fig5['K'])} panels "
                          f"and fig5.{key} = {_number(value)} one {key} for each of {len(value)}: give fig5.{key} as "
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
    for block in KINDS:
        if block not in blocks:
            continue
        try:
            found = _scene_mappings(block, blocks["model"], blocks[block], {"study": study},
                                    (paper or {}).get(block, {}))
            scenes[block] = {label: Planned(s, SETTINGS[block].from_mapping(s)) for label, s in found.items()}
        except ParameterError as err:
            raise ConfigError(f"{tag}{block}: {err}") from None
        except ConfigError as err:
            raise ConfigError(f"{tag}{err}") from None
    return scenes


def _compared(block: str, model: Mapping, b: Mapping, paper: Mapping) -> list[dict]:
    """What the scenes of ``block`` run, as compared between a study and the paper: their settings without the
    model's keys the kind's data do not depend on, the symmetric defaults filled in."""
    ignored = KINDS[block].ignored
    model = {k: v for k, v in model.items() if k not in ignored}
    model.update({k: -model[m] for k, m in SYMMETRIC_DEFAULTS.items() if k not in model and m in model})
    return [leaves(s) for s in _scene_mappings(block, model, b, {}, paper).values()]


def plan(config: Mapping, paper: Mapping) -> tuple[dict[str, dict], list[str]]:
    """The studies (``replication``, and the user's own by its ``name`` where a kind's scenes differ from the
    paper's), each by kind and label, every scene checked; and the lines the planning prints about the user's study:
    what changed, each kind the changes touch that does not run and why, in one line each."""
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
    """The replication's own runs, checked: ``checks`` (the claims register's runs and their cycles),
    ``benchmark`` and ``long_run`` (each on the Fig. 3 case it names, as Fig. 3 runs it)."""
    found = {"checks": {"cases": check_cases(paper), "n_cycles": paper["checks"]["n_cycles"],
                        "probes": check_probes(paper)}}
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
        for case in found["checks"]["cases"]:
            PoincareScene.from_mapping({**case, "n_cycles": 1, "amplitude": "largest_displacement"})
    except ParameterError as err:
        raise ConfigError(f"config/paper.yaml: {err}") from None
    return found


def check_probes(paper: Mapping) -> dict:
    """The runs behind single claims (the ``checks`` block's ``first_swings``, ``return_map`` and ``phase_shift``,
    each on a Fig. 3 case as the fig3 block runs it; ``existence``, ``release_boundary`` and ``grazing``, on the
    model with their own positions; ``airy``, its zones on the model; ``short_runs``; ``section_crossings``; and
    always ``windows``, the runs of Fig. 4's grid of readings)
    (:func:`escapement.scenes.probes.probe_variables`)."""
    checks, fig3 = paper["checks"], paper["fig3"]

    def case(label: str, *parts: Mapping) -> dict:
        if label not in fig3["cases"]:
            raise ConfigError(f"checks: case {label!r} is invalid: a case must be one of fig3.cases, one of "
                              f"{', '.join(sorted(fig3['cases']))}")
        return _flat(paper["model"], fig3["cases"][label], {"label": label}, *parts)

    probes: dict = {}
    if "first_swings" in checks:
        probes["first_swings"] = [case(c, {"x0": side * abs(fig3["cases"][c]["x0"])})
                                  for c in checks["first_swings"]["cases"] for side in checks["first_swings"]["sides"]]
    if "return_map" in checks:
        probes["return_map"] = case(checks["return_map"]["case"], checks["return_map"])
    if "phase_shift" in checks:
        probes["phase_shift"] = case(checks["phase_shift"]["case"], checks["phase_shift"],
                                     {"n_release": fig3["n_cycles"]})
    own = {key: {**dict(zip(("a1", "a2", "a3", "a4"), block["positions"])), **block}
           for key, block in checks.items() if key in ("existence", "release_boundary", "grazing")}
    probes["releases"] = [_flat(paper["model"], own["existence"], {"F": F}) for F in own["existence"]["forces"]
                          ] if "existence" in own else []
    if "release_boundary" in own:
        probes["releases"] += [_flat(paper["model"], own["release_boundary"], {"x0": x0})
                               for x0 in own["release_boundary"]["releases"]]
    if "grazing" in own:
        probes["grazing"] = _flat(paper["model"], own["grazing"])
    if "airy" in checks:
        zones = dict(sorted(checks["airy"]["zones"].items()))  # _flat leaves nested mappings out
        probes["airy"] = {**_flat(paper["model"], checks["airy"]), "zones": zones}
    if "short_runs" in checks:
        short, given = checks["short_runs"], fig3["cases"][checks["short_runs"]["case"]]
        pairs = [(K, given["x0"]) for K in short["K"]] + [(paper["model"]["K"], x0) for x0 in short["releases"]]
        probes["short_runs"] = [case(short["case"], {"K": K, "x0": x0, "n_cycles": short["n_cycles"]})
                                for K, x0 in dict.fromkeys(pairs)]
    if "section_crossings" in checks:
        probes["crossings"] = {"cases": [case(c, {"n_cycles": fig3["n_cycles"]}) for c in fig3["cases"]],
                               **checks["section_crossings"]}
    magnitudes = sorted({abs(c["x0"]) for c in fig3["cases"].values()})
    probes["windows"] = [_flat(paper["model"], {"F": F, "K": K, "x0": side * m})
                         for F in sorted({c["F"] for c in fig3["cases"].values()}) for K in FIG5_PANEL_K.values()
                         for m in magnitudes for side in (-1.0, 1.0)]
    return probes


def check_cases(paper: Mapping) -> list[dict]:
    """The runs of the claims register (the ``checks`` block), each labelled with its group: the Fig. 3 cases,
    the initial conditions, the impact coefficients, the symmetric and asymmetric geometries, every K of Fig. 5
    at every force of the figure, the releases and the forces."""
    checks = paper["checks"]
    base = _flat(paper["model"], {"F": checks["F"], "x0": checks["x0"]})
    cases = [_flat(base, keys, {"group": "paper", "label": f"fig3{c}"}) for c, keys in paper["fig3"]["cases"].items()]
    cases += [_flat(base, ic, {"group": "initial_condition", "label": f"F={ic['F']:g},x0={ic['x0']:g}"})
              for ic in checks["initial_conditions"]]
    cases += [_flat(base, {"b": b, "group": "b", "label": f"b={b:g}"}) for b in checks["b"]]
    for group in ("symmetric", "asymmetric"):
        for force in checks[group]["F"]:
            for positions in checks[group]["positions"]:
                keys = dict(zip(("a1", "a2", "a3", "a4"), positions))
                label = f"F={force:g}," + ",".join(f"{k}={v:g}" for k, v in keys.items())
                cases.append(_flat(base, keys, {"F": force, "group": group, "label": label}))
    fig5 = paper["fig5"]
    panels = [(k, _per_panel(fig5, "F", i, fig5), _per_panel(fig5, "x0", i, fig5)) for i, k in enumerate(fig5["K"])]
    for force in sorted({F for _, F, _ in panels}):
        cases += [_flat(base, {"K": k, "x0": x0, "F": force, "group": "common_force", "label": f"K={k:g},F={force:g}"})
                  for k, _, x0 in panels]
    if "releases" in checks:
        force = checks["releases"]["F"]
        cases += [_flat(base, {"F": force, "x0": x0, "group": "release", "label": f"F={force:g},x0={x0:g}"})
                  for x0 in checks["releases"]["x0"]]
    if "forces" in checks:
        x0 = checks["forces"]["x0"]
        cases += [_flat(base, {"F": force, "x0": x0, "group": "force", "label": f"F={force:g},x0={x0:g}"})
                  for force in checks["forces"]["F"]]
    return cases
