"""One clear line for the first problem in the workflow's configuration.

The JSON schema (draft 2020-12) describes every value; its ``description`` says what a value
must be. This turns the most relevant schema error into
``model.M = 0.0 is invalid: M must be a number > 0 (kg)``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import yaml
from jsonschema import Draft202012Validator
from jsonschema.exceptions import best_match

__all__ = ["config_error"]


def _path(parts) -> str:
    return ".".join(str(p) for p in parts) or "the configuration"


def config_error(config: Mapping, schema_path: str | Path) -> str | None:
    """The message for the most relevant violation of the schema, or None if there is none."""
    schema = yaml.safe_load(Path(schema_path).read_text())
    validator = Draft202012Validator(schema)
    error = best_match(validator.iter_errors(dict(config)))
    if error is None:
        return None
    where = _path(error.absolute_path)
    name = str(error.absolute_path[-1]) if error.absolute_path else where
    if error.validator == "required":
        missing = [key for key in error.validator_value if key not in error.instance]
        return f"{where}: the key {missing[0]!r} is missing: it must be given"
    if error.validator == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        unknown = sorted(set(error.instance) - set(allowed))
        return f"{where}: unknown key {unknown[0]!r}; the keys allowed here are {', '.join(allowed)}"
    requirement = error.schema.get("description")
    if requirement is None:
        resolved = error.schema.get("$ref")
        requirement = error.message if resolved is None else error.message
    return f"{where} = {error.instance!r} is invalid: {name} must be {requirement}"
