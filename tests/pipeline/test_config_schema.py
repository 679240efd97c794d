"""Every kind of violation the configuration's schema can report, at every place of the shipped
configuration, written as one sentence that names the key's path, its value and what it must be.

Each case breaks one keyword of the schema at one key of a valid configuration (the shipped one):
a wrong type, a bound, a count of items, repeated items, a choice, a missing key, an unknown key, a
refused key name, a count of keys. The message must start with that key's path, show the value, say
what it must be in words that state the broken rule (the bound, the count, the choices), and hold
none of jsonschema's own phrases.
"""

from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest
import yaml

from escapement.pipeline.config import config_error
from escapement.pipeline.config_schema import keywords, schema_error, schema_node

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = yaml.safe_load((ROOT / "workflow/schemas/config.schema.yaml").read_text())
SHIPPED = yaml.safe_load((ROOT / "config/config.yaml").read_text())

#: jsonschema's messages, which read as fragments once put after "must be"
RAW = ("is not of type", "is not valid under", "should be non-empty", "is expected to be empty", "is too long",
       "is too short", "has non-unique elements", "was unexpected", "is a required property", "does not match",
       "is less than", "is greater than", "is not one of", "does not have enough properties",
       "has too many properties", "Unevaluated properties", "Additional properties", "a value the schema allows")
#: words that state a count, beside its digits
COUNT_WORDS = {0: ("empty",), 1: ("one",), 2: ("pair", "two"), 4: ("four",)}


def _where(path) -> str:
    return ".".join(str(p) for p in path) or "the configuration"


def _locations(value, path=()):
    """Every place in ``value``: each key of a mapping, the first item of a list."""
    yield path, value
    if isinstance(value, dict):
        for key, item in value.items():
            yield from _locations(item, (*path, key))
    elif isinstance(value, list) and value:
        yield from _locations(value[0], (*path, 0))


def _violations(path, value, found):
    """(keyword, bad value or edit, detail) for each keyword of the schema ``found`` at ``path``."""
    kind = found.get("type")
    if kind == "integer":
        yield "type", 2.5, None
        yield "type", 2.0, None  # an integer is written without a decimal point
    if path and (kind in ("number", "integer", "array", "object") or "anyOf" in found):  # a file holds a mapping
        yield "type", "text", None
    for bound, step in (("minimum", -1), ("maximum", 1), ("exclusiveMinimum", 0), ("exclusiveMaximum", 0)):
        if bound in found:
            yield bound, found[bound] + step if kind == "integer" else float(found[bound] + step), found[bound]
    if "enum" in found:
        yield "enum", "none_of_these", found["enum"]
    if found.get("minItems"):
        yield "minItems", value[: found["minItems"] - 1], found["minItems"]
    if "maxItems" in found:
        pad = value[0] if value else 0.5
        yield "maxItems", [pad] * (found["maxItems"] + 1), found["maxItems"]
    if found.get("uniqueItems") and value:
        yield "uniqueItems", [value[0], value[0]], None
    for key in found.get("required", ()):
        yield "required", key, None
    if found.get("additionalProperties") is False or found.get("unevaluatedProperties") is False:
        yield "unknown key", "unknown_key", None
    if found.get("minProperties"):
        yield "minProperties", dict(list(value.items())[: found["minProperties"] - 1]), found["minProperties"]
    if "maxProperties" in found:
        some = next(iter(value.values()))
        more = {f"extra_{'abcdefgh'[i]}": some for i in range(found["maxProperties"] + 1 - len(value))}
        yield "maxProperties", {**value, **more}, found["maxProperties"]
    if "propertyNames" in found:
        yield "propertyNames", "Bad Name", None


def _cases():
    for path, value in _locations(SHIPPED):
        node = schema_node(SCHEMA, path)
        assert node is not None, f"{_where(path)} has no place in the schema"
        for keyword, bad, detail in _violations(path, value, keywords(node, SCHEMA)):
            yield pytest.param(path, keyword, bad, detail, id=f"{_where(path)}-{keyword}-{bad!r}"[:90])


CASES = list(_cases())


def _at(config, path):
    for key in path:
        config = config[key]
    return config


def _numbers(text: str) -> set[float]:
    return {float(n) for n in re.findall(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?", text)}


def test_the_cases_cover_every_kind_of_violation_the_schema_can_report():
    kinds = {case.values[1] for case in CASES}
    assert kinds == {"type", "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "enum", "minItems",
                     "maxItems", "uniqueItems", "required", "unknown key", "minProperties", "maxProperties",
                     "propertyNames"}
    assert len(CASES) > 150


@pytest.mark.parametrize("path, keyword, bad, detail", CASES)
def test_each_violation_is_one_sentence_naming_the_key_its_value_and_the_rule(path, keyword, bad, detail):
    config = copy.deepcopy(SHIPPED)
    parent = _at(config, path[:-1]) if path else None
    if keyword == "required":
        del _at(config, path)[bad]
        where = _where((*path, bad))
    elif keyword in ("unknown key", "propertyNames"):
        _at(config, path)[bad] = 1 if keyword == "unknown key" else next(iter(_at(config, path).values()))
        where = _where((*path, bad))
    else:
        parent[path[-1]] = bad
        where = _where(path)
    message = schema_error(config, SCHEMA)
    assert message is not None and "\n" not in message
    assert not [raw for raw in RAW if raw in message], message
    if keyword == "required":
        assert message.startswith(f"{where} is missing: {bad} must be given, as "), message
        return
    assert message.startswith(f"{where} = "), message
    assert " is invalid: " in message and " must be " in message, message
    if keyword == "unknown key":
        assert f"{bad} is not a key of {_where(path)}, whose keys must be among " in message
        allowed = message.rsplit("must be among ", 1)[1].split(", ")
        assert set(allowed) >= set(_at(SHIPPED, path)), message
        return
    if keyword == "propertyNames":
        assert f"is not a valid key of {_where(path)}, whose keys must be " in message
        return
    assert repr(bad) in message or len(repr(bad)) > 80, message
    requirement = message.split(" must be ", 1)[1]
    if keyword in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        assert float(detail) in _numbers(requirement), message
    elif keyword == "enum":
        assert all(str(choice) in requirement for choice in detail), message
    elif keyword in ("minItems", "maxItems", "minProperties", "maxProperties"):
        assert float(detail) in _numbers(requirement) or any(w in requirement for w in COUNT_WORDS.get(detail, ())), \
            message
    elif keyword == "uniqueItems":
        assert "distinct" in requirement or "differ" in requirement, message
    elif keyword == "type" and bad == 2.0:
        assert requirement.endswith("(write it without a decimal point)"), message


@pytest.mark.parametrize(
    "edit, message",
    [
        # the audit's cases: a message that read "chunks must be 0 is not of type 'integer'", and one that
        # named x0 for an empty list of spring constants
        (lambda c: c["stability_map"].update(chunks="0"),
         "stability_map.chunks = '0' is invalid: chunks must be an integer in [1, 1000] (it is text: write it "
         "without quotes)"),
        (lambda c: c["fig5"].update(K=[]),
         "fig5.K = [] is invalid: K must be a list of one or more distinct numbers > 0 (N/m), one panel each"),
        (lambda c: c["fig5"].update(K=[1.0, 1.0]),
         "fig5.K = [1.0, 1.0] is invalid: K must be a list of one or more distinct numbers > 0 (N/m), one panel each"),
        (lambda c: c["fig5"].update(x0=[-1.0, "left", 3.0]),
         "fig5.x0.1 = 'left' is invalid: each item of x0 must be a number (m)"),
        # a key the model block lists, refused where a scene may not override it
        (lambda c: c["fig3"]["cases"]["a"].update(colour=1),
         "fig3.cases.a.colour = 1 is invalid: colour is not a key of fig3.cases.a, whose keys must be among "
         "F, K, M, a1, a2, a3, a4, b, x0"),
        (lambda c: c["model"].update(M="1e-3"),
         "model.M = '1e-3' is invalid: M must be a number > 0 (kg) (YAML reads 1e-3 as text: write it 1.0e-3)"),
        (lambda c: c["model"].update(K="2E5"),
         "model.K = '2E5' is invalid: K must be a number > 0 (N/m) (YAML reads 2E5 as text: write it 2.0e+5)"),
        (lambda c: c["checks"]["symmetric"].update(positions=[[-0.1, 0.05], [0.2]]),
         "checks.symmetric.positions.1 = [0.2] is invalid: each item of positions must be a pair [a1, a2] of "
         "positions (m)"),
        (lambda c: c["checks"]["asymmetric"]["positions"][0].__setitem__(2, None),
         "checks.asymmetric.positions.0.2 = None is invalid: each item of positions.0 must be a number (m)"),
    ],
)
def test_the_messages_read_as_sentences(edit, message):
    config = copy.deepcopy(SHIPPED)
    edit(config)
    assert schema_error(config, SCHEMA) == message
    assert config_error(config, SCHEMA) == message


def test_a_whole_number_with_a_decimal_point_is_refused_where_an_integer_must_be():
    """JSON Schema takes 2.0 for an integer; the chunks are counted with range(), which does not."""
    config = copy.deepcopy(SHIPPED)
    config["stability_map"]["chunks"] = 2.0
    assert schema_error(config, SCHEMA) == (
        "stability_map.chunks = 2.0 is invalid: chunks must be an integer in [1, 1000] (write it without a "
        "decimal point)")
    config["stability_map"]["chunks"] = 2
    assert schema_error(config, SCHEMA) is None
