"""The workflow's configuration: read strictly, checked, and made into the studies the rules run.

Two sources. ``config/paper.yaml`` holds the replication (the paper's scenes and the runs that check its
claims); it is read here, never overridden. The user's configuration (Snakemake's ``config``: the
``configfile`` of the Snakefile, ``--configfile``, ``--config``) holds the user's own scenes: each block is laid
over the paper's block of the same name, key by key, the model over the paper's model, and every kind of
figure whose settings then differ from the paper's is the user's study (:func:`own_blocks`).

Checks, in order, each refusal one line naming the file or key, its value and the rule: every file read with
ruamel.yaml, which refuses a key given twice (:func:`read_yaml`; Snakemake's loader keeps the last silently),
and a nested ``--config`` value read again as YAML (:func:`typed_overrides`: Snakemake leaves its scalars as
text); each source against its JSON Schema (Snakemake's ``validate`` in the rules, its error put in one line by
:func:`refusal` from the schema's ``description``); then every scene built and checked by
:mod:`escapement.scenes.settings` (:func:`study_scenes`).
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Mapping
from pathlib import Path

from ..model.parameters import ParameterError
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

__all__ = ["ConfigError", "check_cases", "code_digest", "own_blocks", "read_yaml", "refusal", "replication_scenes",
           "study_scenes", "typed_overrides"]

#: the blocks a user's configuration may lay over the paper's (besides ``name``)
BLOCKS = ("model", *KINDS)


class ConfigError(ValueError):
    """The configuration is invalid; the message is one line naming the file or key."""


def _yaml():
    from ruamel.yaml import YAML  # read only by Snakemake's process, when it plans the workflow

    return YAML(typ="safe", pure=True)


def read_yaml(path: str | Path) -> dict:
    """The mapping of the YAML (or JSON) file ``path``; :class:`ConfigError` naming the file, line and column
    for a YAML error or a key given twice, or if the file holds no mapping."""
    from ruamel.yaml.error import MarkedYAMLError

    try:
        with open(path, encoding="utf-8") as handle:
            content = _yaml().load(handle)
    except OSError as err:
        raise ConfigError(f"{path}: cannot read the configuration ({err.strerror})") from None
    except MarkedYAMLError as err:
        mark = err.problem_mark
        where = "" if mark is None else f", line {mark.line + 1}, column {mark.column + 1}"
        raise ConfigError(f"{path}{where}: not valid YAML: {err.problem}") from None
    if not isinstance(content, dict):
        raise ConfigError(f"{path}: the configuration must be a mapping of keys, not "
                          f"{type(content).__name__ if content is not None else 'empty'}")
    return content


def typed_overrides(config: dict, entries: Iterable[str] | None) -> None:
    """Read again, as a configuration file would, each ``--config key=value`` entry whose value Snakemake read as
    a mapping or a list (it leaves their scalars as text: ``{K: [0.1]}`` gives ``['0.1']``), and lay it over
    ``config`` in order, as Snakemake does (mappings key by key, other values replaced)."""
    from ruamel.yaml.error import YAMLError
    from snakemake.utils import update_config

    for entry in entries or ():
        key, _, text = str(entry).partition("=")
        if not isinstance(config.get(key), dict | list):
            continue
        try:
            update_config(config, {key: _yaml().load(text)})
        except YAMLError as err:
            raise ConfigError(f"--config {entry}: not valid YAML ({getattr(err, 'problem', err)}); a nested "
                              "value may also be given in a file, with --configfile") from None


def refusal(error, source: str) -> str:
    """One line for the first violation of a JSON Schema (a jsonschema ``ValidationError``) in ``source``:
    the key, its value and the rule, the rule taken from the schema's ``description``."""
    path = list(error.absolute_path)
    where = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in path).lstrip(".")
    rule = error.schema.get("description") if isinstance(error.schema, dict) else None
    if "propertyNames" in error.schema_path:  # the rule is the propertyNames schema's, one level up
        rule = error.parent.schema.get("description") if error.parent is not None else rule
    if error.validator in ("required", "additionalProperties", "unevaluatedProperties"):
        return f"{source}: {where or 'the top level'}: {error.message}"
    if "propertyNames" in error.schema_path:
        return f"{source}: {where or 'the top level'}: the key {error.instance!r} is invalid: a key must be {rule}"
    name = next((p for p in reversed(path) if isinstance(p, str)), "the value")
    subject = f"each item of {name}" if path and isinstance(path[-1], int) else name
    if rule is None:  # a constraint without a description: jsonschema's own sentence
        return f"{source}: {where} = {error.instance!r} is invalid: {error.message}"
    return f"{source}: {where} = {error.instance!r} is invalid: {subject} must be {rule}"


def own_blocks(config: Mapping, paper: Mapping) -> dict[str, dict]:
    """The user's study: the model and each kind's block laid over the paper's, keeping the kinds whose
    settings then differ from the paper's (the model counts for every kind)."""
    model = {**paper["model"], **config.get("model", {})}
    found = {"model": model}
    for block in KINDS:
        merged = {**paper[block], **config.get(block, {})}
        if merged != paper[block] or model != paper["model"]:
            found[block] = merged
    return found


def _flat(*parts: Mapping) -> dict:
    """The parts merged (later ones win), nested mappings left out, sorted by key: a scene's flat mapping, which
    reordering a file does not change (Snakemake compares params by their text)."""
    merged: dict = {}
    for part in parts:
        merged.update({k: v for k, v in part.items() if not isinstance(v, dict)})
    return dict(sorted(merged.items()))


def _per_panel(fig5: Mapping, key: str, index: int):
    value = fig5[key]
    if not isinstance(value, list):
        return value
    if len(value) != len(fig5["K"]):
        raise ConfigError(f"fig5.{key} = {value!r} is invalid: {key} must be one number, or a list of "
                          f"{len(fig5['K'])} numbers, one per spring constant of fig5.K = {fig5['K']!r}")
    return value[index]


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
        b = blocks[block]
        try:
            if block == "fig3":
                found = {case: _flat(model, b, keys, {"study": study, "label": case})
                         for case, keys in b["cases"].items()}
                checked = [PoincareScene.from_mapping(s) for s in found.values()]
            elif block == "fig5":
                labels = [f"{k:g}" for k in b["K"]]
                if len(set(labels)) < len(labels):
                    raise ConfigError(f"fig5.K = {b['K']!r} is invalid: K must be spring constants that differ in "
                                      "their file labels (e.g. 0.1 and 0.10000000001 both write K_0.1.nc)")
                found = {label: _flat(model, b, {"K": b["K"][i], "F": _per_panel(b, "F", i),
                                                 "x0": _per_panel(b, "x0", i), "study": study, "label": label})
                         for i, label in enumerate(labels)}
                checked = [PhaseScene.from_mapping(s) for s in found.values()]
            else:
                settings = {"fig4": ShockScene, "escapement_error": EscapementErrorScene,
                            "existence_map": ExistenceMapScene, "stability_map": StabilityMapScene}[block]
                nested = {k: v for k, v in b.items() if isinstance(v, dict)}  # the axes, the zones
                found = {"": {**_flat(model, b, {"study": study}), **nested}}
                checked = [settings.from_mapping(s) for s in found.values()]
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
    found = {"checks": {"cases": check_cases(paper), "n_cycles": paper["checks"]["n_cycles"]}}
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


def code_digest(root: str | Path, *parts: str) -> str:
    """A digest of the source files under ``parts`` (folders or files, relative to ``root``): a rule's params
    hold the digest of the layers it runs, so that Snakemake's params trigger reruns a job when their code
    changes (Snakemake itself follows only a rule's own script)."""
    digest = hashlib.sha256()
    for part in parts:
        path = Path(root, part)
        for file in sorted(path.rglob("*") if path.is_dir() else [path]):
            if file.is_file() and file.suffix in (".py", ".yaml", ".mplstyle") and "__pycache__" not in file.parts:
                digest.update(file.relative_to(root).as_posix().encode() + b"\0" + file.read_bytes())
    return digest.hexdigest()[:16]
