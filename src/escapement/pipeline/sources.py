"""The configuration's sources, each read by one YAML reader, strictly and within bounds, and checked against its
JSON Schema; every refusal one line.

A source is a file (``config/config.yaml``, a ``--configfile``, ``config/paper.yaml``) or a ``--config key=value``
entry, and :func:`load` reads every one the same way, so that the same text gives the same value from a file and
from the command line: YAML 1.2's core schema (``2e0`` is a number, ``yes`` a text), by ruamel.yaml, which refuses
a key given twice. Before any value is built, on the parser's events, it refuses an anchor, an alias (a
configuration writes each value out: an alias bomb never expands) and a tag, and bounds the text
(:data:`MAX_BYTES`), the nesting (:data:`MAX_DEPTH`), the items (:data:`MAX_ITEMS`: keys, values, lists and
mappings) and each value's length (:data:`MAX_CHARS`); then every key must be a text and every number finite.
:func:`user_config` lays the user's sources over one another as Snakemake does; :func:`validated` checks a source
against its schema with Snakemake's ``validate``, and :func:`refusal` puts the first violation in one line: the
key, its value and the rule (the schema's ``description``, the violated node's bounds filled in), or an unknown
key with the closest one the schema names there.
"""

from __future__ import annotations

import difflib
import functools
import math
import re
import reprlib
from collections.abc import Iterable, Mapping
from pathlib import Path

__all__ = ["MAX_BYTES", "MAX_CHARS", "MAX_DEPTH", "MAX_ITEMS", "ConfigError", "load", "read_yaml", "refusal",
           "typed_overrides", "user_config", "validated"]

#: The most a source may hold, checked before anything validates or walks it. The largest the project has:
#: config/paper.yaml, 8 kB of 350 items 5 levels deep, and the configuration's schema, 16 kB of 1,200 items 9 deep.
MAX_BYTES, MAX_DEPTH, MAX_ITEMS, MAX_CHARS = 65_536, 16, 5_000, 1_000

#: YAML 1.2's core schema (the specification's Sec. 10.3.2): a plain scalar that fully matches one of these, in
#: order, is null, a bool, an int or a float, by the first characters it may start with; any other is a text
CORE_SCHEMA = (
    ("null", r"~|null|Null|NULL|", "~nN"),
    ("bool", r"true|True|TRUE|false|False|FALSE", "tTfF"),
    ("int", r"[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+", "-+0123456789"),
    ("float", r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?|[-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN)",
     "-+.0123456789"),
)

#: how a refusal shows a value: whole if short, else its start and end (a refusal is one line)
SHORT = reprlib.Repr()
SHORT.maxstring, SHORT.maxother, SHORT.maxlist, SHORT.maxdict = 80, 80, 8, 6


class ConfigError(ValueError):
    """The configuration is invalid; the message is one line naming the file or key."""


@functools.cache
def _resolver() -> type:
    """ruamel.yaml's resolver held to YAML 1.2's core schema, whatever a document's ``%YAML`` directive says.

    Hand-written because ruamel.yaml's own adds timestamps (``2001-13-45`` then fails as a ValueError), merge
    keys, ``=`` and digit separators to the core schema, and reads a ``%YAML 1.1`` document by YAML 1.1."""
    from ruamel.yaml.resolver import VersionedResolver

    table: dict[str, list] = {}
    for name, pattern, first in CORE_SCHEMA:
        for char in [*first, *([""] if name == "null" else [])]:
            table.setdefault(char, []).append((f"tag:yaml.org,2002:{name}", re.compile(f"(?:{pattern})\\Z")))

    class CoreSchema(VersionedResolver):
        processing_version = (1, 2)
        versioned_resolver = table

    return CoreSchema


def _yaml():
    from ruamel.yaml import YAML  # read only by Snakemake's process, when it plans the workflow

    yaml = YAML(typ="safe", pure=True)
    yaml.Resolver = _resolver()
    return yaml


def _name(key: object) -> str:
    """A key as a refusal names it: as written if it is a plain name, else quoted (a refusal is one line)."""
    return key if isinstance(key, str) and re.fullmatch(r"[\w-]+", key) else SHORT.repr(key)


def _where(path: Iterable) -> str:
    """The dotted name of the key at ``path`` (``fig5.K[1]``)."""
    return "".join(f"[{p}]" if isinstance(p, int) else f".{_name(p)}" for p in path).lstrip(".")


def _bounded(text: str, source: str, depth: int = 0) -> None:
    """Refuse, on the parser's events and before any value is built, what a configuration never needs: an anchor,
    an alias, a tag, more than the bounds (the nesting counted from ``depth``, the level the text's value lies at
    in the configuration).

    Hand-written because neither ruamel.yaml nor PyYAML can refuse aliases or bound a document while reading it."""
    from ruamel.yaml.events import AliasEvent, CollectionEndEvent, CollectionStartEvent, NodeEvent, ScalarEvent

    size = len(text.encode("utf-8", "surrogateescape"))
    if size > MAX_BYTES:
        raise ConfigError(f"{source}: {size} bytes is too long: a configuration holds at most {MAX_BYTES} bytes")
    items = 0
    for event in _yaml().parse(text):
        depth += isinstance(event, CollectionStartEvent) - isinstance(event, CollectionEndEvent)
        items += isinstance(event, NodeEvent)
        if isinstance(event, AliasEvent) or getattr(event, "anchor", None) is not None:
            what = f"the alias *{event.anchor}" if isinstance(event, AliasEvent) else f"the anchor &{event.anchor}"
            problem = f"{what} is refused: a configuration writes each value out (no anchors or aliases)"
        elif getattr(event, "tag", None) is not None:
            tag = str(event.tag).replace("tag:yaml.org,2002:", "!!")
            problem = f"the tag {tag} is refused: a configuration holds plain values, lists and mappings"
        elif depth > MAX_DEPTH:
            problem = f"more than {MAX_DEPTH} levels of nesting is refused: a configuration is at most {MAX_DEPTH} deep"
        elif items > MAX_ITEMS:
            problem = f"more than {MAX_ITEMS} items is refused: a configuration holds at most {MAX_ITEMS}"
        elif isinstance(event, ScalarEvent) and len(event.value) > MAX_CHARS:
            problem = f"a value of {len(event.value)} characters is refused: a value holds at most {MAX_CHARS}"
        else:
            continue
        mark = event.start_mark
        raise ConfigError(f"{source}, line {mark.line + 1}, column {mark.column + 1}: {problem}")


def _plain(value: object, path: list, source: str) -> None:
    """Refuse a key that is not a text and a number that is not finite, naming the key.

    Hand-written because YAML 1.2 reads ``.inf``, ``.nan`` and ``1e400`` as floats and ``? [a, b]`` as a key, and
    JSON, whose types the schemas' keywords check, has neither."""
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                raise ConfigError(f"{source}: {_where(path) or 'the top level'}: the key {SHORT.repr(key)} is "
                                  "invalid: a key must be a text (in quotes if it reads as a number)")
            _plain(item, [*path, key], source)
    elif isinstance(value, list):
        for index, item in enumerate(value):
            _plain(item, [*path, index], source)
    elif isinstance(value, float) and not math.isfinite(value):
        name = next((p for p in reversed(path) if isinstance(p, str)), "the value")
        raise ConfigError(f"{source}: {_where(path)} = {value!r} is invalid: {_name(name)} must be a finite number")


def load(text: str, source: str, path: tuple = ()):
    """The value of the YAML text ``text`` of ``source`` (a file's name, or ``--config KEY``), read as the module
    says; :class:`ConfigError` naming the source, and the line and column or the key (under ``path``, where the
    value lies in the configuration), for anything it refuses."""
    from ruamel.yaml.error import YAMLError

    try:
        _bounded(text, source, len(path))
        value = _yaml().load(text)
    except YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = "" if mark is None else f", line {mark.line + 1}, column {mark.column + 1}"
        problem = " ".join(str(getattr(err, "problem", None) or err).split())
        raise ConfigError(f"{source}{where}: not valid YAML: {problem}") from None
    _plain(value, [*path], source)
    return value


def read_yaml(path: str | Path) -> dict:
    """The mapping of the YAML (or JSON) file ``path``, read by :func:`load`; :class:`ConfigError` naming the file
    (and the line and column, or the key) for a file it cannot read or refuses, or that holds no mapping."""
    try:
        with open(path, "rb") as handle:
            data = handle.read(MAX_BYTES + 1)
    except OSError as err:
        raise ConfigError(f"{path}: cannot read the configuration ({err.strerror})") from None
    if len(data) > MAX_BYTES:
        raise ConfigError(f"{path}: more than {MAX_BYTES} bytes is too long: a configuration holds at most "
                          f"{MAX_BYTES} bytes")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise ConfigError(f"{path}: byte {err.start + 1} is not UTF-8: a configuration is UTF-8 text") from None
    content = load(text, str(path))
    if not isinstance(content, dict):
        raise ConfigError(f"{path}: the configuration must be a mapping of keys, not "
                          f"{type(content).__name__ if content is not None else 'empty'}")
    return content


def typed_overrides(config: dict, entries: Iterable[str] | None) -> None:
    """Lay each ``--config key=value`` entry over ``config``, in order, as Snakemake does (mappings key by key,
    other values replaced), its value read by :func:`load` as a file's would be (Snakemake reads a scalar as an int,
    a float or YAML 1.1, and leaves a nested value's scalars as text: ``{K: [0.1]}`` gives ``['0.1']``)."""
    from snakemake.utils import update_config

    for entry in entries or ():
        key, _, text = str(entry).partition("=")
        update_config(config, {key: load(text, f"--config {_name(key)}", (key,))})


def user_config(files: Iterable[str | Path], entries: Iterable[str] | None) -> dict:
    """The user's configuration: each file of ``files`` in order, then each ``--config`` entry, laid over the
    previous as Snakemake lays them, every one read by :func:`load`."""
    from snakemake.utils import update_config

    config: dict = {}
    for path in files:
        update_config(config, read_yaml(path))
    typed_overrides(config, entries)
    return config


def validated(data: Mapping, schema: str | Path, source: str) -> None:
    """Check ``data`` (the configuration of ``source``) against the JSON Schema file ``schema`` with Snakemake's
    ``validate``; :class:`ConfigError` with :func:`refusal`'s line for the first violation."""
    from jsonschema.exceptions import ValidationError
    from snakemake.exceptions import WorkflowError
    from snakemake.utils import validate

    try:
        validate(data, str(schema), set_default=False)
    except WorkflowError as err:
        if not isinstance(err.__context__, ValidationError):
            raise
        raise ConfigError(refusal(err.__context__, source, schema)) from None


def refusal(error, source: str, schema: str | Path | None = None) -> str:
    """One line for the first violation of a JSON Schema (a jsonschema ``ValidationError``) in ``source``: the key,
    its value and the rule, the rule the schema's ``description`` with the violated node's keywords filled in
    (``{maximum}``) or, for an enumeration without one, its values; an unknown key with the closest key the schema
    names there (case aside first; the schema file ``schema`` gives them)."""
    path = list(error.absolute_path)
    where = _where(path)
    node = error.schema if isinstance(error.schema, dict) else {}
    keys = _known_keys(error, Path(schema)) if error.validator in ("additionalProperties", "unevaluatedProperties") \
        and schema is not None else []
    key = next((str(k) for k in error.instance if k not in keys), None) if keys else None
    if key is not None:
        near = [k for k in keys if k.lower() == key.lower()] or difflib.get_close_matches(key, keys, n=1)
        hint = f"did you mean {near[0]!r}?" if near else f"the keys are {', '.join(keys)}"
        return f"{source}: {where or 'the top level'}: unknown key {SHORT.repr(key)} ({hint})"
    if error.validator in ("required", "additionalProperties", "unevaluatedProperties"):
        return f"{source}: {where or 'the top level'}: {error.message}"
    if "description" in node:
        rule = node["description"].format_map(node)
    elif error.validator == "enum":
        rule = f"one of {', '.join(map(str, error.validator_value))}"
    else:
        rule = f"of type {error.validator_value}" if error.validator == "type" else None
    value = SHORT.repr(error.instance)
    if "propertyNames" in error.schema_path:  # the node is the propertyNames schema, the instance a key
        return f"{source}: {where or 'the top level'}: the key {value} is invalid: a key must be {rule}"
    name = next((p for p in reversed(path) if isinstance(p, str)), "the value")
    subject = f"each item of {_name(name)}" if path and isinstance(path[-1], int) else _name(name)
    if rule is None:  # a constraint without a description: jsonschema's own sentence
        return f"{source}: {where} = {value} is invalid: {SHORT.repr(' '.join(error.message.split()))}"
    return f"{source}: {where} = {value} is invalid: {subject} must be {rule}"


def _known_keys(error, schema: Path) -> list[str]:
    """The keys the schema names for the object in which ``error`` found one it does not: the ``properties`` of
    the object's schema and of those it refers to. Its node is found by following the error's schema path from
    the root of ``schema``, each ``$ref`` resolved as Snakemake's ``validate`` does, to the schema file of that
    name beside it (jsonschema's path leaves out the ``$ref`` it followed: a step a node lacks is looked up where
    its ``$ref`` leads).

    Hand-written because jsonschema's error names neither the keys its schema allows nor the ``$ref`` it followed."""
    from urllib.parse import urlparse

    from referencing import Registry
    from referencing.jsonschema import DRAFT202012

    def retrieve(uri: str):
        return DRAFT202012.create_resource(read_yaml(schema.parent / Path(urlparse(uri).path).name))

    node = read_yaml(schema)
    registry = Registry(retrieve=retrieve).with_resource(node["$id"], DRAFT202012.create_resource(node))
    resolver = registry.resolver(base_uri=node["$id"])

    def follow(node: Mapping, resolver):
        found = resolver.lookup(node["$ref"])
        return found.contents, found.resolver

    for step in list(error.schema_path)[:-1]:
        while isinstance(node, dict) and step not in node and "$ref" in node:
            node, resolver = follow(node, resolver)
        node = node[step]
    keys = list(node.get("properties", {}))
    while "$ref" in node:
        node, resolver = follow(node, resolver)
        keys += node.get("properties", {})
    return list(dict.fromkeys(keys))
