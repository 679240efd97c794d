"""The configuration's JSON schema (draft 2020-12) in words: one sentence for its first violation.

:func:`schema_error` writes the violation that jsonschema's ``best_match`` picks as one line that names
the key by its path, its value and what the value must be:

- a value (a wrong type, a bound, a count of items, items that repeat, a choice, a pattern, a count of
  keys): ``<key path> = <value> is invalid: <key> must be <requirement>``;
- a key the schema does not know: ``<key path> = <value> is invalid: <key> is not a key of <block>,
  whose keys must be among <keys>``;
- a key that is missing: ``<key path> is missing: <key> must be given, as <requirement>``.

The requirement is the one of the key's place in the schema (not of the keyword that failed, which
may lie in a definition the key refers to): its ``description``, or else words made from its keywords
(``an integer in [1, 1000]``, ``a list of 2 items, each a number (m)``, ``one of RK45, DOP853``). An
integer is written without a decimal point (JSON Schema would take ``2.0``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from jsonschema import Draft202012Validator, validators
from jsonschema.exceptions import best_match

__all__ = ["allowed_keys", "keywords", "requirement", "schema_error", "schema_node"]

#: draft 2020-12, but an integer is an ``int``: JSON Schema takes ``2.0`` for an integer, which the code
#: that reads a count need not (``stability_map.chunks = 2.0`` would fail while the jobs are planned)
_Validator = validators.extend(
    Draft202012Validator,
    type_checker=Draft202012Validator.TYPE_CHECKER.redefine(
        "integer", lambda _, value: isinstance(value, int) and not isinstance(value, bool)
    ),
)

#: keywords that say nothing about the value (a node holding only these and ``$ref`` is the definition it refers to)
_ANNOTATIONS = {"$ref", "title", "description", "$comment"}


def _target(ref: str, root: Mapping) -> Mapping:
    """The node a local ``$ref`` (``#/...``) points to."""
    if not ref.startswith("#/"):
        raise ValueError(f"$ref = {ref!r} is invalid: the configuration's schema must refer within itself (#/...)")
    node = root
    for part in ref[2:].split("/"):
        node = node[part]
    return node


def keywords(node: Mapping, root: Mapping) -> dict:
    """The keywords that hold at ``node``: those of the definition it refers to, its own winning (the keys
    it lists are those of both)."""
    if "$ref" not in node:
        return dict(node)
    target = keywords(_target(node["$ref"], root), root)
    merged = {**target, **{k: v for k, v in node.items() if k != "$ref"}}
    if "properties" in target and "properties" in node:
        merged["properties"] = {**target["properties"], **node["properties"]}
    return merged


def _child(node: Mapping, key, root: Mapping) -> Mapping | None:
    """The schema of the value at ``key`` (a name or a list index) inside a value of schema ``node``."""
    merged = keywords(node, root)
    if isinstance(key, int):
        if "items" in merged:
            return merged["items"]
    else:
        if key in merged.get("properties", {}):
            return merged["properties"][key]
        if isinstance(merged.get("additionalProperties"), Mapping):
            return merged["additionalProperties"]
    for branch in merged.get("anyOf", ()):  # the branch that has such a value (a list, or a mapping)
        found = _child(branch, key, root)
        if found is not None:
            return found
    return None


def schema_node(root: Mapping, path) -> Mapping | None:
    """The schema of the value at ``path`` (names and list indexes), or None where the schema has none."""
    node = root
    for key in path:
        node = _child(node, key, root)
        if node is None:
            return None
    return node


def allowed_keys(node: Mapping, root: Mapping) -> list[str]:
    """The names of the keys the schema ``node`` lists (its own and its definition's), sorted."""
    return sorted(keywords(node, root).get("properties", {}))


def _number(x) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def _bounds(merged: Mapping) -> str:
    """`` in [0, 1)``, `` >= 1``, ... for the bounds of a number."""
    lo = ("[", merged["minimum"]) if "minimum" in merged else ("(", merged.get("exclusiveMinimum"))
    hi = ("]", merged["maximum"]) if "maximum" in merged else (")", merged.get("exclusiveMaximum"))
    if lo[1] is not None and hi[1] is not None:
        return f" in {lo[0]}{_number(lo[1])}, {_number(hi[1])}{hi[0]}"
    if lo[1] is not None:
        return f" {'>=' if lo[0] == '[' else '>'} {_number(lo[1])}"
    if hi[1] is not None:
        return f" {'<=' if hi[0] == ']' else '<'} {_number(hi[1])}"
    return ""


def _count(low, high, noun: str) -> str:
    """``2 items``, ``1 to 4 items``, ``at least 1 item``: a count of ``noun``s."""
    if low is not None and low == high:
        return f"{low} {noun}{'' if low == 1 else 's'}"
    if low and high is not None:
        return f"{low} to {high} {noun}s"
    if low:
        return f"at least {low} {noun}{'' if low == 1 else 's'}"
    if high is not None:
        return f"at most {high} {noun}{'' if high == 1 else 's'}"
    return ""


def _words(merged: Mapping, root: Mapping) -> str:
    """What a value of schema ``merged`` (with no description of its own) must be, from its keywords."""
    if "enum" in merged:
        return "one of " + ", ".join(str(choice) for choice in merged["enum"])
    if "anyOf" in merged:
        return ", or ".join(requirement(branch, root) for branch in merged["anyOf"])
    kind = merged.get("type")
    if kind in ("integer", "number"):
        return ("an integer" if kind == "integer" else "a number") + _bounds(merged)
    if kind == "array":
        if merged.get("maxItems") == 0:
            return "an empty list"
        count = _count(merged.get("minItems"), merged.get("maxItems"), "item")
        text = "a list" + (f" of {count}" if count else "") + (" that differ" if merged.get("uniqueItems") else "")
        return text + (f", each {requirement(merged['items'], root)}" if "items" in merged else "")
    if kind == "object" or "properties" in merged:
        count = _count(merged.get("minProperties"), merged.get("maxProperties"), "key")
        text = "a mapping" + (f" of {count}" if count else "")
        if "propertyNames" in merged:
            text += f", each key {requirement(merged['propertyNames'], root)}"
        if isinstance(merged.get("additionalProperties"), Mapping):
            return text + f", each value {requirement(merged['additionalProperties'], root)}"
        keys = allowed_keys(merged, root)
        return text + (f" with the keys {', '.join(keys)}" if keys else "")
    if "pattern" in merged:
        return f"text matching the pattern {merged['pattern']}"
    if kind == "string":
        return "text"
    return "a value the schema allows"


def requirement(node: Mapping, root: Mapping) -> str:
    """What a value of schema ``node`` must be: its description; else, if it only refers to a definition,
    the definition's; else words made from its keywords."""
    if "description" in node:
        return node["description"]
    if "$ref" in node and set(node) <= _ANNOTATIONS:
        return requirement(_target(node["$ref"], root), root)
    return _words(keywords(node, root), root)


def _where(path) -> str:
    return ".".join(str(p) for p in path) or "the configuration"


def _subject(path) -> str:
    """How the message names the value at ``path``: its key, or for an item of a list, ``each item of <list>``."""
    if not path:
        return "the configuration"
    if not isinstance(path[-1], int):
        return str(path[-1])
    named = max((i for i, p in enumerate(path) if not isinstance(p, int)), default=-1)
    return f"each item of {_where(path[max(named, 0):-1])}"


def _shown(value) -> str:
    """The value as Python writes it, shortened to one readable line."""
    text = repr(value)
    return text if len(text) <= 80 else text[:72] + " ... " + text[-4:]


#: a number as it may be written in decimal (``3``, ``-0.5``, ``1e-3``, ``2E5``), which YAML may read as text
_NUMERAL = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def _hint(value, node: Mapping, root: Mapping) -> str:
    """How to write a number that was written otherwise: as text (YAML 1.1 reads ``1e-3`` as text), or
    an integer with a decimal point."""
    kind = keywords(node, root).get("type")
    if kind == "integer" and isinstance(value, float) and value.is_integer():
        return " (write it without a decimal point)"
    if not isinstance(value, str) or kind not in ("number", "integer"):
        return ""
    if not _NUMERAL.fullmatch(value.strip()):
        return ""
    mantissa, e, exponent = value.strip().lower().partition("e")
    if not e:
        return " (it is text: write it without quotes)"
    mantissa += "" if "." in mantissa else ".0"
    exponent = exponent if exponent.startswith(("+", "-")) else f"+{exponent}"
    return f" (YAML reads {value} as text: write it {mantissa}e{exponent})"


def schema_error(config: Mapping, schema: Mapping) -> str | None:
    """The message for the most relevant violation of ``schema``, or None if there is none."""
    error = best_match(_Validator(schema).iter_errors(dict(config)))
    if error is None:
        return None
    path = list(error.absolute_path)
    node = schema_node(schema, path) or error.schema
    if error.validator == "required":
        missing = next(key for key in error.validator_value if key not in error.instance)
        child = _child(node, missing, schema)
        need = requirement(child, schema) if child is not None else "a value"
        return f"{_where([*path, missing])} is missing: {missing} must be given, as {need}"
    if error.validator in ("additionalProperties", "unevaluatedProperties"):
        allowed = allowed_keys(error.schema, schema)
        unknown = sorted((key for key in error.instance if key not in allowed), key=str)[0]
        return (f"{_where([*path, unknown])} = {_shown(error.instance[unknown])} is invalid: {unknown} is not a key "
                f"of {_where(path)}, whose keys must be among {', '.join(allowed)}")
    if "propertyNames" in error.relative_schema_path:
        key = error.instance  # the name that is refused, inside the mapping at ``path``
        names = keywords(node, schema)["propertyNames"]
        value = _dict_at(config, path)[key]
        return (f"{_where([*path, key])} = {_shown(value)} is invalid: {key} is not a valid key of {_where(path)}, "
                f"whose keys must be {requirement(names, schema)}")
    need = requirement(node, schema) + _hint(error.instance, node, schema)
    return f"{_where(path)} = {_shown(error.instance)} is invalid: {_subject(path)} must be {need}"


def _dict_at(config: Mapping, path) -> Mapping:
    for key in path:
        config = config[key]
    return config
