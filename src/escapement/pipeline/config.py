"""The workflow's configuration as Snakemake merges it (``config/paper.yaml``, ``config/config.yaml``, then
``--configfile`` and ``--config``), checked against ``workflow/schemas/config.schema.yaml`` once before any job,
every refusal one line; its scenes are checked by :mod:`escapement.pipeline.plan`.
"""

from __future__ import annotations

import difflib
import math
import reprlib
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path

import yaml

__all__ = ["MAX_DEPTH", "ConfigError", "dotted", "refusal", "refuse_aliases", "typed_config", "validated"]

#: the deepest a configuration file may nest (config/paper.yaml nests 5 levels)
MAX_DEPTH = 16

#: how a refusal shows a value: whole if short, else its start and end (a refusal is one line)
SHORT = reprlib.Repr()
SHORT.maxstring, SHORT.maxother, SHORT.maxlist, SHORT.maxdict = 80, 80, 8, 6
MAX_FLOAT = sys.float_info.max


class ConfigError(ValueError):
    """The configuration is invalid; the message is one line naming the file or key."""


def dotted(path: Iterable) -> str:
    """The dotted name of the key at ``path`` (``fig5.K[1]``)."""
    return "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in path).lstrip(".")


def refuse_aliases(path: str | Path) -> None:
    """Refuse an anchor, an alias or more than :data:`MAX_DEPTH` levels in the YAML file ``path``, before Snakemake
    loads it. Hand-written because Snakemake's merge walks every path through its aliases (a billion laughs)."""
    depth = 0
    with open(path, "rb") as handle:
        for event in yaml.parse(handle):
            depth += isinstance(event, yaml.CollectionStartEvent) - isinstance(event, yaml.CollectionEndEvent)
            if isinstance(event, yaml.AliasEvent) or getattr(event, "anchor", None) is not None:
                problem = "an anchor or alias is refused: a configuration writes each value out"
            elif depth > MAX_DEPTH:
                problem = f"more than {MAX_DEPTH} levels of nesting is refused"
            else:
                continue
            raise ConfigError(f"{path}, line {event.start_mark.line + 1}: {problem}")


def typed_config(config: dict, entries: Iterable[str] | None) -> None:
    """Lay each ``--config key=value`` entry over ``config`` again, its value read as a configuration file's is.
    Hand-written because Snakemake reads a nested ``--config`` value's scalars as text (``{K: [0.1]}`` gives
    ``['0.1']``), which no schema of numbers admits."""
    from snakemake.utils import update_config

    for entry in entries or ():
        key, _, text = str(entry).partition("=")
        try:
            value = yaml.safe_load(text) if text else None
        except yaml.YAMLError as err:
            raise ConfigError(f"--config {key}: not valid YAML: {' '.join(str(err).split())}") from None
        update_config(config, {key: value})


def _plain(value: object, path: list) -> None:
    """Refuse a key that is not a text and a number that is not finite, naming the key (a schema's ``number``
    admits ``.inf``, ``1e400`` and a 401-digit integer)."""
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                raise ConfigError(f"the configuration: {dotted(path) or 'the top level'}: the key {SHORT.repr(key)} "
                                  "is invalid: a key must be a text (in quotes if it reads as a number)")
            _plain(item, [*path, key])
    elif isinstance(value, list):
        for index, item in enumerate(value):
            _plain(item, [*path, index])
    elif isinstance(value, float) and not math.isfinite(value) or isinstance(value, int) and abs(value) > MAX_FLOAT:
        raise ConfigError(f"the configuration: {dotted(path)} = {SHORT.repr(value)} is invalid: it must be a finite "
                          f"number (at most {MAX_FLOAT:.4g} in magnitude)")


def validated(config: Mapping, schema: str | Path, source: str = "the configuration") -> None:
    """Check ``config`` against the JSON Schema file ``schema`` with Snakemake's ``validate``; :class:`ConfigError`
    with :func:`refusal`'s line for the first violation."""
    from jsonschema.exceptions import ValidationError
    from snakemake.exceptions import WorkflowError
    from snakemake.utils import validate

    _plain(config, [])
    try:
        validate(config, str(schema), set_default=False)
    except WorkflowError as err:
        if not isinstance(err.__context__, ValidationError):
            raise
        raise ConfigError(refusal(err.__context__, source)) from None


def refusal(error, source: str) -> str:
    """One line for a violation of the schema (a jsonschema ``ValidationError``): the key, its value and the rule
    (the node's ``description``, its keywords filled in, or an enumeration's values); an unknown key, the closest."""
    path = list(error.absolute_path)
    where = dotted(path) or "the top level"
    node = error.schema if isinstance(error.schema, dict) else {}
    keys = list(node.get("properties", {}))
    unknown = [str(k) for k in error.instance if k not in keys] if isinstance(error.instance, dict) and keys else []
    if error.validator == "required" and unknown:  # a key mistyped is missing too: the unknown one says more
        error.validator = "additionalProperties"
    if error.validator == "additionalProperties":
        key = unknown[0]
        near = [k for k in keys if k.lower() == key.lower()] or difflib.get_close_matches(key, keys, n=1)
        hint = f"did you mean {near[0]!r}?" if near else f"the keys are {', '.join(keys)}"
        if ":" in key:
            hint = f"a flow mapping needs a space after each colon: {{{key.replace(':', ': ', 1)}}}"
        return f"{source}: {where}: unknown key {SHORT.repr(key)} ({hint})"
    if error.validator == "required":
        missing = next(k for k in error.validator_value if k not in error.instance)
        form = f": {path[-1]} must be {node['description'].format_map(node)}" if "description" in node else ""
        return f"{source}: {where}: the key {missing!r} is missing{form}"
    if "description" in node:
        rule = node["description"].format_map(node)
    elif error.validator == "enum":
        rule = f"one of {', '.join(map(str, error.validator_value))}"
    else:
        return f"{source}: {where} = {SHORT.repr(error.instance)} is invalid: {' '.join(error.message.split())}"
    value = SHORT.repr(error.instance)
    if "propertyNames" in error.schema_path:  # the instance is a key
        return f"{source}: {where}: the key {value} is invalid: a key must be {rule}"
    name = next((p for p in reversed(path) if isinstance(p, str)), "the value")
    subject = f"each item of {name}" if path and isinstance(path[-1], int) else name
    return f"{source}: {where} = {value} is invalid: {subject} must be {rule}"
