"""The configuration as the workflow checks it before any job: the merged configuration (config/paper.yaml with
the user's blocks laid over it by Snakemake's own merge) against the one schema, and the rules the schema cannot
state at planning; every refusal one line naming the key as the user typed it, its value and the form it must
have. Then the two hand-written parts: the ``--config`` entries typed as a file's, and the user's file refused
with an alias or a deep nesting before Snakemake loads it. Last, the schema's own hygiene: every constraint and
every mapping states its form, every bound once. The refusals through Snakemake itself: tests/test_workflow.py."""

from __future__ import annotations

import copy
import re
import time
from pathlib import Path

import pytest
import yaml
from snakemake.common.configfile import load_configfile
from snakemake.utils import update_config

from escapement.model.parameters import ParameterError
from escapement.pipeline.config import MAX_DEPTH, ConfigError, refuse_aliases, typed_config, validated
from escapement.pipeline.plan import plan
from escapement.scenes import settings
from escapement.studies.readings import AMPLITUDES

REPO = Path(__file__).resolve().parents[2]
SCHEMA = REPO / "workflow" / "schemas" / "config.schema.yaml"
PAPER = yaml.safe_load((REPO / "config" / "paper.yaml").read_text())


def merged(user: dict) -> dict:
    """The configuration Snakemake hands the workflow: the paper's file, the user's blocks laid over it."""
    config = copy.deepcopy(PAPER)
    update_config(config, copy.deepcopy(user))
    return config


def refused(check, *args) -> str:
    """The one-line refusal of ``check(*args)``."""
    with pytest.raises(ConfigError) as refusal:
        check(*args)
    message = str(refusal.value)
    assert "\n" not in message and len(message) < 400, message
    return message


def test_the_paper_s_file_is_valid_and_plans_the_replication_alone():
    validated(PAPER, SCHEMA)
    studies, notes = plan(merged({"name": "own"}), PAPER)
    assert list(studies) == ["replication"] and notes == []
    assert list(studies["replication"]["fig5"]) == ["0.1", "1", "10"]


@pytest.mark.parametrize("user, message", [
    # an unknown key, with the closest the schema names there; a flow mapping's missing space
    ({"fig5": {"k": [1.0]}}, "the configuration: fig5: unknown key 'k' (did you mean 'K'?)"),
    ({"fig3": {"cases": {"a": {"A1": 0.1}}}}, "fig3.cases.a: unknown key 'A1' (did you mean 'a1'?)"),
    ({"ü": 1}, "the configuration: the top level: unknown key 'ü' (the keys are name, model, fig3, fig4"),
    ({"escapement_error": {"F:0.7": None}}, "escapement_error: unknown key 'F:0.7' (a flow mapping needs a space "
                                            "after each colon: {F: 0.7})"),
    # a number where a mapping is expected: the form the mapping must have
    ({"escapement_error": {"F": 0.7}}, "escapement_error.F = 0.7 is invalid: F must be an axis {start, stop, n} of "
                                       "forces (N)"),
    ({"stability_map": {"b": [0.0, 2.0]}}, "stability_map.b = [0.0, 2.0] is invalid: b must be an axis {start, "
                                           "stop, n}"),
    # a key missing from a case the user adds, with the case's form
    ({"fig3": {"cases": {"c": {"F": 0.75}}}}, "fig3.cases.c: the key 'x0' is missing: c must be a case {F, x0}"),
    # a bound, filled in from the schema's node; an item of a list; an enumeration; a name's pattern
    ({"fig5": {"samples_per_period": 2}}, "fig5.samples_per_period = 2 is invalid: samples_per_period must be an "
                                          "integer in [8, 100000]"),
    ({"existence_map": {"F": {"n": 0}}}, "existence_map.F.n = 0 is invalid: n must be an integer in [1, 400]"),
    ({"fig5": {"K": [0.1, "x"]}}, "fig5.K[1] = 'x' is invalid: each item of K must be a number (N/m)"),
    ({"fig3": {"amplitude": "peak"}}, f"fig3.amplitude = 'peak' is invalid: amplitude must be one of "
                                      f"{', '.join(AMPLITUDES)}"),
    ({"name": "replication\n"}, "name = 'replication\\n' is invalid: name must be a name of lowercase letters"),
    ({"fig3": {"cases": {"a\n": {"F": 1.0, "x0": -1.0}}}}, "fig3.cases: the key 'a\\n' is invalid: a key must be one "
                                                           "lowercase letter"),
    ({"checks": {"b": {"Measure": "release"}}}, "checks.b: unknown key 'Measure' (did you mean 'measure'?)"),
    # what JSON Schema's number admits and YAML gives: not finite, a key that is not a text
    ({"model": {"M": float("inf")}}, "the configuration: model.M = inf is invalid: it must be a finite number"),
    ({"fig5": {"K": [10**400, 0.5]}}, "the configuration: fig5.K[0] = 100000000000000000...0000000000000000000 is "
                                      "invalid: it must be a finite number (at most 1.798e+308 in magnitude)"),
    ({"fig3": {"cases": {1: {"F": 1.0, "x0": -1.0}}}}, "fig3.cases: the key 1 is invalid: a key must be a text"),
])
def test_each_violation_of_the_schema_is_one_line_naming_the_key_its_value_and_the_form(user, message):
    assert message in refused(validated, merged(user), SCHEMA)


@pytest.mark.parametrize("user, message", [
    # the model's bounds, Parameters' own (the schema states only their types)
    ({"model": {"M": 0}}, "the configuration: model.M = 0.0 is invalid: M must be > 0 (kg)"),
    ({"model": {"a4": 0.2}}, "a4 = 0.2 is invalid: a4 must be < a3 = 0.1 (m)"),
    ({"fig3": {"cases": {"a": {"a2": -0.2}}}}, "your study 'own': fig3: a2 = -0.2 is invalid: a2 must be > a1 = -0.1"),
    # lists of another length: the key the user typed, and the form the other must take
    ({"fig5": {"K": [0.1, 1.0, 5.0, 7.0]}}, "your study 'own': fig5.K = [0.1, 1, 5, 7] is invalid: fig5.K gives 4 "
                                            "panels and fig5.F = [1, 0.5, 0.5] one F for each of 3: give fig5.F as one "
                                            "number or a list of 4"),
    ({"fig5": {"x0": [-1.0, -1.0]}}, "your study 'own': fig5.x0 = [-1, -1] is invalid"),
    ({"fig5": {"K": [0.1, 0.1000000000001]}}, "fig5.K = [0.1, 0.1000000000001] is invalid: K must be spring "
                                              "constants that differ in their file labels"),
    ({"fig4": {"velocity_window": [87.0, 80.0]}}, "your study 'own': fig4: velocity_window = [87.0, 80.0] is "
                                                  "invalid: velocity_window must be a pair [start, end] with"),
    ({"checks": {"n_cycles": 5}}, "the configuration: checks is the replication's own (config/paper.yaml), which a "
                                  "study does not change"),
])
def test_each_rule_the_schema_cannot_state_is_refused_at_planning_naming_what_the_user_typed(user, message):
    config = merged(user)
    validated(config, SCHEMA)
    assert message in refused(plan, config, PAPER)


def _keys(value, path=()):
    if isinstance(value, dict):
        for key, item in value.items():
            yield path, key
            yield from _keys(item, (*path, key))


#: the first key of each mapping of the paper's file whose case can be swapped (one per node of the schema), but
#: the names the user chooses (cases, zones, the checks' runs)
CLOSED = list({path: (path, key) for path, key in reversed(list(_keys(PAPER))) if key.swapcase() != key
               and "cases" not in path and "zones" not in path and path != ("checks",)}.values())


@pytest.mark.parametrize("path, key", CLOSED, ids=[".".join(map(str, p + (k,))) for p, k in CLOSED])
def test_every_key_of_the_paper_s_file_mistyped_in_case_is_refused_naming_the_key_it_stands_for(path, key):
    paper = copy.deepcopy(PAPER)
    mapping = paper
    for step in path:
        mapping = mapping[step]
    mapping[key.swapcase()] = mapping.pop(key)
    where = ".".join(path) or "the top level"
    assert refused(validated, paper, SCHEMA, "config/paper.yaml") == \
        f"config/paper.yaml: {where}: unknown key {key.swapcase()!r} (did you mean {key!r}?)"


#: texts whose value a reader of YAML may give otherwise; each must read the same from --config as from a file
TEXTS = ["2e0", "1.0e-3", ".5", "017", "0x1F", "+1", "yes", "~", "true", "1_000", "1:20", "2001-12-14"]


def test_a_config_entry_gets_the_types_a_file_gives_it_laid_over_as_snakemake_lays_it(tmp_path):
    """Snakemake reads ``--config fig5={K: [0.1, 1.0, 5.0]}`` with every scalar as text; each entry is read again
    as Snakemake reads a configuration file, and laid over the configuration key by key."""
    config = {"name": "own", "fig5": {"K": ["0.1", "1.0", "5.0"], "n_cycles": 10}}
    typed_config(config, ["fig5={K: [0.1, 1.0, 5.0]}", "name=two"])
    assert config == {"name": "two", "fig5": {"K": [0.1, 1.0, 5.0], "n_cycles": 10}}
    path = tmp_path / "my.yaml"
    path.write_text("".join(f"k{i}: {text}\n" for i, text in enumerate(TEXTS)))
    from_command_line: dict = {}
    typed_config(from_command_line, [f"k{i}={text}" for i, text in enumerate(TEXTS)])
    assert from_command_line == load_configfile(path)
    assert "not valid YAML" in refused(typed_config, {}, ["fig5={K: [0.1"])


def list_bomb(levels: int = 9) -> str:
    """A billion laughs under model.M: ``levels`` lists of ten aliases of the one before (10**levels items)."""
    text = "model:\n  M:\n    - &a0 [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]\n"
    return text + "".join(f"    - &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]\n" for i in range(1, levels + 1))


@pytest.mark.parametrize("text, match", [
    (list_bomb(), "line 3: an anchor or alias is refused"),
    ("fig5: {K: *k}\n", "line 1: an anchor or alias is refused"),
    ("model:\n  M: " + "[" * 5_000 + "]" * 5_000 + "\n", f"line 2: more than {MAX_DEPTH} levels of nesting"),
])
def test_the_user_s_file_is_refused_with_an_alias_or_a_deep_nesting_before_snakemake_loads_it(tmp_path, text, match):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    start = time.perf_counter()
    assert refused(refuse_aliases, path).startswith(f"{path}, {match}")
    assert time.perf_counter() - start < 2.0
    path.write_text("model:\n  M: " + "[" * (MAX_DEPTH - 2) + "]" * (MAX_DEPTH - 2) + "\n")
    refuse_aliases(path)  # within the bound


def schema_nodes(node, path=""):
    """Every mapping of the schema with its path."""
    if isinstance(node, dict):
        yield path, node
        for key, value in node.items():
            yield from schema_nodes(value, f"{path}/{key}")
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from schema_nodes(value, f"{path}/{index}")


NODES = list(schema_nodes(yaml.safe_load(SCHEMA.read_text())))


def test_every_constraint_and_every_mapping_of_the_schema_states_its_form_for_the_refusal():
    """A refusal's rule is the violated node's description (an enumeration's is its list of values); a
    combinator's branches (anyOf, not) report at the key that holds them, which has one."""
    constraints = ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "minItems", "maxItems", "pattern")
    missing = [path for path, node in NODES if "/anyOf/" not in path and "/not" not in path and "$ref" not in node
               and (node.get("type") in ("integer", "number", "string", "object") or any(k in node for k in
                                                                                        constraints))
               and "description" not in node and path]
    assert missing == []


def test_every_description_is_filled_in_from_its_node_and_states_no_bound_of_its_own():
    keywords = ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "minItems", "maxItems",
                "minProperties", "maxProperties", "maxLength")
    for path, node in NODES:
        if isinstance(node.get("description"), str):
            written = set(re.findall(r"(?<![\w.{])\d+(?:\.\d+)?(?![\w}])", node["description"]))
            assert not written & {str(node[k]) for k in keywords if isinstance(node.get(k), int | float)}, path
            node["description"].format_map(node)


def test_every_pattern_matches_exactly_and_every_list_has_a_most_items():
    patterns = [node["pattern"] for _, node in NODES if isinstance(node.get("pattern"), str)]
    assert len(patterns) >= 4 and all(p.startswith("^") and p.endswith("(?![\\s\\S])") for p in patterns)
    for pattern in patterns:
        example = "a" if "[a-z]" in pattern else "_"
        assert re.search(pattern, example) and not re.search(pattern, example + "\n")
    assert [path for path, node in NODES if node.get("type") == "array" and "maxItems" not in node] == []


def counts_in_schema() -> dict[str, tuple[int, int]]:
    """Every integer of the blocks whose scenes check their counts again, by ``block.key``, with its bounds."""
    schema = yaml.safe_load(SCHEMA.read_text())
    found = {}

    def walk(node: dict, name: str) -> None:
        while "$ref" in node:
            target = schema
            for step in node["$ref"].removeprefix("#/").split("/"):
                target = target[step]
            node = {**target, **{k: v for k, v in node.items() if k != "$ref"}}
        if node.get("type") == "integer":
            found[name] = (node["minimum"], node["maximum"])
        for key, child in node.get("properties", {}).items():
            walk(child, f"{name}.{key}")

    for block in ("fig3", "fig4", "fig5", "escapement_error", "stability_map", "existence_map", "long_run"):
        walk(schema["$defs"][block], block)
    return found


def test_the_scenes_check_their_counts_within_the_bounds_the_schema_states():
    assert counts_in_schema() == settings.COUNTS
    for key, (least, most) in settings.COUNTS.items():
        assert settings._count(key, least) == least and settings._count(key, most) == most
        for value in (least - 1, most + 1, float(least), True):
            with pytest.raises(ParameterError, match=f"^{re.escape(key.split('.', 1)[1])} = "):
                settings._count(key, value)


def test_the_model_s_bounds_are_the_model_s_own_and_the_amplitudes_the_readings():
    model = yaml.safe_load(SCHEMA.read_text())["$defs"]["model"]["properties"]
    assert all(set(node) <= {"title", "type", "description"} for node in model.values())
    assert settings.AMPLITUDES == tuple(AMPLITUDES)
