"""The workflow's configuration: read strictly, checked, and made into the studies the rules run.

Two sources. ``config/paper.yaml`` holds the replication (the paper's scenes and the runs that check its
claims); it is read here, never overridden. The user's configuration (Snakemake's ``config``: the
``configfile`` of the Snakefile, ``--configfile``, ``--config``) holds the user's own scenes: each block is laid
over the paper's block of the same name, key by key at every level, the model over the paper's model, and every
kind of figure whose scenes then run something other than the paper's is the user's study (:func:`own_blocks`;
:func:`study_notes` says why a kind the user's changes do not reach does not run).

Checks, in order, each refusal one line naming the file or key, its value and the rule: every source, a file or
a ``--config`` entry, read by one YAML reader, strictly and within bounds (:mod:`escapement.pipeline.sources`:
:func:`read_yaml`, :func:`typed_overrides`, :func:`user_config`); each source against its JSON Schema
(:func:`validated`, its first violation put in one line by :func:`refusal`); then every scene built and checked by
:mod:`escapement.scenes.settings` (:func:`study_scenes`).
"""

from __future__ import annotations

from collections.abc import Mapping

from ..model.parameters import ParameterError, Parameters
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
from .changes import KindPlan, changed_model_keys, describe, filled, leaves, merged, notes
from .sources import ConfigError, read_yaml, refusal, typed_overrides, user_config, validated

__all__ = ["ConfigError", "check_cases", "check_model", "laid_over", "own_blocks", "read_yaml", "refusal",
           "replication_scenes", "study_notes", "study_scenes", "typed_overrides", "user_config", "validated"]

#: the blocks a user's configuration may lay over the paper's (besides ``name``)
BLOCKS = ("model", *KINDS)


def own_blocks(config: Mapping, paper: Mapping) -> dict[str, dict]:
    """The user's study: the model and each kind's block laid over the paper's at every level
    (:func:`~escapement.pipeline.changes.merged`), keeping the kinds whose scenes then differ from the paper's in
    what they run (:func:`~escapement.pipeline.changes.describe`), each block with, under ``changes``, that
    difference in one line (its scenes' ``changes``, their datasets' ``study_changes``)."""
    return _own(config, paper)[0]


def study_notes(config: Mapping, paper: Mapping) -> list[str]:
    """The lines the planning prints about the user's study: each kind the user's changes touch that does not run,
    or that some of the model's changes do not reach, and why; one line if no kind runs
    (:func:`~escapement.pipeline.changes.notes`)."""
    return _own(config, paper)[1]


def laid_over(config: Mapping, paper: Mapping) -> dict:
    """The paper's configuration with the user's blocks laid over it at every level (no kind left out): what the
    paper's schema checks again, so that its bounds hold for the blocks a user's cases or zones join."""
    return {**paper, **{block: merged(paper[block], config.get(block) or {}) for block in BLOCKS}}


def _own(config: Mapping, paper: Mapping) -> tuple[dict[str, dict], list[str]]:
    """The blocks of the kinds that run (with their ``changes``) and the notes: each kind's scenes compared with
    the paper's, and each model key the user changed reverted alone to find the kinds it does not reach."""
    name = str(config.get("name", "own"))
    given_model = config.get("model") or {}
    model = merged(paper["model"], given_model)
    moved = changed_model_keys(model, paper["model"], given_model)
    blocks, laid, plans = {"model": model}, {}, []
    try:
        for block in KINDS:
            mine_block = laid[block] = merged(paper[block], config.get(block) or {})
            mine, theirs = _effective(block, model, mine_block), _effective(block, paper["model"], paper[block])
            missed = tuple(key for key in moved if _effective(block, _reverted(model, paper["model"], key),
                                                                mine_block) == mine)
            own = {case: tuple(keys) for case, keys in mine_block["cases"].items()} if block == "fig3" else \
                {label: ("K", "F", "x0") for label in mine}
            changes = describe(block, mine, theirs, own)
            if changes:
                blocks[block] = {**mine_block, "changes": changes}
            paper_leaves = leaves(paper[block])
            block_changes = tuple((k, v) for k, v in leaves(mine_block).items()
                                  if k not in paper_leaves or paper_leaves[k] != v)
            plans.append(KindPlan(block, changes, missed, block in config, block_changes))
    except ConfigError as err:
        raise ConfigError(f"your study '{name}': {err}") from None
    return blocks, notes(name, plans, model, laid, [b for b in BLOCKS if b in config])


def _reverted(model: Mapping, paper: Mapping, key: str) -> dict:
    """``model`` with ``key`` as the paper's model has it (absent if the paper's model leaves it out)."""
    return {k: v for k, v in model.items() if k != key} | ({key: paper[key]} if key in paper else {})


def _effective(block: str, model: Mapping, b: Mapping) -> dict[str, dict]:
    """The settings each scene of ``block`` runs, by label: the model's keys the kind ignores left out, the
    symmetric defaults filled in, nested axes and zones as dotted keys (:func:`~escapement.pipeline.changes.leaves`)."""
    ignored = KINDS[block].ignored
    scenes = _scene_mappings(block, {k: v for k, v in model.items() if k not in ignored}, b, {})
    return {label: leaves(filled(scene, ignored)) for label, scene in scenes.items()}


def _flat(*parts: Mapping) -> dict:
    """The parts merged (later ones win), nested mappings left out, sorted by key: a scene's flat mapping, which
    reordering a file does not change (Snakemake compares params by their text)."""
    flat: dict = {}
    for part in parts:
        flat.update({k: v for k, v in part.items() if not isinstance(v, dict)})
    return dict(sorted(flat.items()))


def _per_panel(fig5: Mapping, key: str, index: int):
    value = fig5[key]
    if not isinstance(value, list):
        return value
    if len(value) != len(fig5["K"]):
        raise ConfigError(f"fig5.{key} = {value!r} is invalid: {key} must be one number, or a list of "
                          f"{len(fig5['K'])} numbers, one per spring constant of fig5.K = {fig5['K']!r}")
    return value[index]


def _scene_mappings(block: str, model: Mapping, b: Mapping, extra: Mapping) -> dict[str, dict]:
    """The flat mapping of each scene of ``block`` by label (a Fig. 3 case, a spring constant; ``""`` for the kinds
    of one scene), unchecked: the model's keys, the block's, the scene's own and ``extra``, later ones winning; the
    nested axes and zones of a kind of one scene after them."""
    if block == "fig3":
        return {case: _flat(model, b, keys, extra, {"label": case}) for case, keys in b["cases"].items()}
    if block == "fig5":
        labels = [f"{k:g}" for k in b["K"]]
        if len(set(labels)) < len(labels):
            raise ConfigError(f"fig5.K = {b['K']!r} is invalid: K must be spring constants that differ in "
                              "their file labels (e.g. 0.1 and 0.10000000001 both write K_0.1.nc)")
        return {label: _flat(model, b, {"K": b["K"][i], "F": _per_panel(b, "F", i), "x0": _per_panel(b, "x0", i)},
                             extra, {"label": label}) for i, label in enumerate(labels)}
    nested = {k: v for k, v in b.items() if isinstance(v, dict)}  # the axes, the zones
    return {"": {**_flat(model, b, extra), **nested}}


#: each kind's settings, by its block (Fig. 3's and Fig. 5's scenes, one per case or spring constant)
SETTINGS = {"fig3": PoincareScene, "fig4": ShockScene, "fig5": PhaseScene, "escapement_error": EscapementErrorScene,
            "existence_map": ExistenceMapScene, "stability_map": StabilityMapScene}


def study_scenes(study: str, blocks: Mapping) -> dict[str, dict[str, dict]]:
    """Every scene of a study, by kind and label (a Fig. 3 case, a spring constant; ``""`` for the kinds of one
    scene): its flat mapping (the rule's params), each built and checked by its settings
    (:mod:`escapement.scenes.settings`) here, before any job; :class:`ConfigError` naming the block for the first
    that fails."""
    model, scenes = blocks["model"], {}
    tag = "" if study == REPLICATION else f"your study '{study}': "
    for block in KINDS:
        if block not in blocks:
            continue
        try:
            found = _scene_mappings(block, model, blocks[block], {"study": study})
            checked = [SETTINGS[block].from_mapping(s) for s in found.values()]
        except ParameterError as err:
            raise ConfigError(f"{tag}{block}: {err}") from None
        except ConfigError as err:
            raise ConfigError(f"{tag}{err}") from None
        assert len(checked) == len(found)
        scenes[block] = found
    return scenes


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
    panels = [(k, _per_panel(fig5, "F", i), _per_panel(fig5, "x0", i)) for i, k in enumerate(fig5["K"])]
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


def check_model(model: Mapping, source: str) -> None:
    """The model block (laid over the paper's) by the model's own rules, :class:`Parameters` being the one
    statement of each parameter's bounds (the schema states only their types); :class:`ConfigError` naming
    ``model.<key>``. F belongs to the scenes: checked there, with each scene."""
    try:
        Parameters.from_mapping({"F": 0.0, **model})
    except ParameterError as err:
        raise ConfigError(f"{source}: model.{err}") from None
