"""The configuration's sources read strictly: every configuration file, and the nested values of ``--config``.

Snakemake reads a configuration file as JSON, else as YAML, keeping the last of two values given to one
key and naming neither the file nor the line of a YAML error. :func:`check_config_files` reads every
file again (the default ``config/config.yaml`` and each one given with ``--configfile``) and refuses a
key given twice in one mapping or a YAML error, naming the file, the line and the column, e.g.
``my.yaml, line 4, column 3: not valid YAML: the key 'M' is given twice (first on line 2)``.

Snakemake reads the value of a ``--config key=value`` entry that is a mapping or a list as YAML with
every scalar left as text (``fig3={n_cycles: 40}`` gives ``n_cycles: '40'``). :func:`apply_config_overrides`
reads such a value again as a configuration file would (``40`` an integer, ``1.0e-3`` a number, ``step1``
text), so that a nested override is checked and used with the types a file gives it.
"""

from __future__ import annotations

import json
import re
from collections.abc import Hashable, Iterable, Mapping
from pathlib import Path

import yaml

__all__ = ["ConfigError", "apply_config_overrides", "check_config_file", "check_config_files", "config_overrides"]


class ConfigError(ValueError):
    """The configuration is invalid; the message is one line that names the key (or the file and line)."""


class _UniqueKeyLoader(yaml.SafeLoader):
    """YAML's safe loader, refusing a key given twice in one mapping (PyYAML keeps the last
    silently, which would drop a value the user wrote)."""

    def construct_mapping(self, node, deep=False):
        seen: dict = {}
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":  # ``<<: *anchor``: keys given here override it
                continue
            key = self.construct_object(key_node, deep=deep)
            if not isinstance(key, Hashable):  # refused by the safe loader itself
                continue
            if key in seen:
                first = seen[key]
                same_line = first.line == key_node.start_mark.line
                at = f"at column {first.column + 1}" if same_line else f"on line {first.line + 1}"
                raise yaml.constructor.ConstructorError(
                    None, None, f"the key {key!r} is given twice (first {at})", key_node.start_mark
                )
            seen[key] = key_node.start_mark
        return super().construct_mapping(node, deep=deep)


def _yaml_problem(err: yaml.YAMLError) -> tuple[object, str]:
    """Where a YAML error is (PyYAML's mark, or None) and what it is."""
    if not isinstance(err, yaml.MarkedYAMLError):
        return None, str(err)
    mark = err.problem_mark or err.context_mark
    context = ""
    if err.context and err.context_mark is not None and err.context_mark is not mark:
        context = f" ({err.context} that starts on line {err.context_mark.line + 1})"
    return mark, f"{err.problem}{context}"


def _strict_yaml(text: str):
    return yaml.load(text, Loader=_UniqueKeyLoader)


def _json_duplicate(text: str) -> tuple[bool, object]:
    """Whether ``text`` is JSON (which Snakemake tries first), and the first key given twice in one
    of its objects (None if there is none)."""
    duplicates: list = []

    def pairs(items):
        keys = [key for key, _ in items]
        duplicates.extend(key for i, key in enumerate(keys) if key in keys[:i])
        return dict(items)

    try:
        json.loads(text, object_pairs_hook=pairs)
    except ValueError:
        return False, None
    return True, (duplicates[0] if duplicates else None)


def check_config_file(path: str | Path) -> None:
    """Raise :class:`ConfigError` naming the file, line and column if ``path`` is not valid YAML (nor
    JSON), gives a key twice in one mapping, or holds no mapping of keys at its top level."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError(f"{path}: cannot read the configuration ({err.strerror})") from None
    except UnicodeDecodeError as err:
        raise ConfigError(f"{path}: not UTF-8 text (byte {err.start}: {err.reason})") from None
    is_json, duplicate = _json_duplicate(text)
    if is_json and duplicate is None:
        content = json.loads(text)
    else:
        try:
            content = _strict_yaml(text)
        except yaml.YAMLError as err:
            mark, problem = _yaml_problem(err)
            where = "" if mark is None else f", line {mark.line + 1}, column {mark.column + 1}"
            raise ConfigError(f"{path}{where}: not valid {'JSON' if is_json else 'YAML'}: {problem}") from None
        if is_json:  # a duplicate PyYAML did not see (it should): named without its line
            raise ConfigError(f"{path}: not valid JSON: the key {duplicate!r} is given twice in one object")
    if not isinstance(content, dict):
        raise ConfigError(f"{path}: the configuration must be a mapping of keys at its top level, "
                          f"not {type(content).__name__ if content is not None else 'empty'}")


def check_config_files(paths: Iterable[str | Path]) -> None:
    """:func:`check_config_file` on each of ``paths`` in turn (a file named twice is read once)."""
    seen = set()
    for path in paths:
        resolved = Path(path).resolve()
        if resolved not in seen:
            seen.add(resolved)
            check_config_file(path)


def _text_only(value) -> bool:
    """Whether every scalar in ``value`` (a mapping or a list, nested) is text: what Snakemake's reading
    of a ``--config`` value gives."""
    if isinstance(value, Mapping):
        return all(isinstance(k, str) and _text_only(v) for k, v in value.items())
    if isinstance(value, list):
        return all(_text_only(v) for v in value)
    return isinstance(value, str)


def config_overrides(entries: Iterable[str] | None, given: Mapping) -> dict:
    """The ``--config`` entries (``key=value``, as on the command line) whose value Snakemake read as a
    mapping or a list of text, each read again as YAML and merged in order as Snakemake merges them;
    ``given`` is what Snakemake read from them. An entry whose value Snakemake did not read so is left out: a
    scalar (read by Snakemake as an integer, a number, a boolean or text) or a value passed as an object
    through Snakemake's API rather than typed on a command line. A value that is meant as a mapping or
    a list but is not valid YAML, or gives a key twice, raises :class:`ConfigError`."""
    found: dict = {}
    for entry in entries or ():
        key, sep, text = str(entry).partition("=")
        if not sep or key not in given:
            continue
        value = given[key]
        read_as_text = isinstance(value, (Mapping, list)) and _text_only(value)
        failed = isinstance(value, str) and text.lstrip().startswith(("{", "["))  # Snakemake kept the text
        if not (read_as_text or failed):
            continue
        try:
            typed = _strict_yaml(text)
        except yaml.YAMLError as err:
            mark, problem = _yaml_problem(err)
            if "\n" not in text:  # one line: columns counted in the entry, from the start of ``key=``
                problem = re.sub(r"at column (\d+)", lambda m: f"at column {len(key) + 1 + int(m[1])}", problem)
            where = "" if mark is None else (f", column {len(key) + 2 + mark.column}" if mark.line == 0
                                             else f", line {mark.line + 1}, column {mark.column + 1}")
            raise ConfigError(f"--config {entry!r}{where}: not valid YAML: {problem}; a nested value may "
                              "also be given in a file, with --configfile") from None
        if read_as_text:
            _merge(found, {key: typed})
    return found


def _merge(config: dict, override: Mapping) -> None:
    """Merge ``override`` into ``config`` in place as Snakemake does: mappings key by key, any other
    value replaced."""
    for key, value in override.items():
        if isinstance(value, Mapping):
            if not isinstance(config.get(key), dict):
                config[key] = {}
            _merge(config[key], value)
        else:
            config[key] = value


def apply_config_overrides(config: dict, entries: Iterable[str] | None, given: Mapping) -> None:
    """Merge the :func:`config_overrides` of ``entries`` into ``config`` in place, last (``--config``
    overrides every file, as in Snakemake), so that their scalars have the types a file gives them."""
    _merge(config, config_overrides(entries, given))
