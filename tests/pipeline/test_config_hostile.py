"""Hostile configurations, each refused in one line before anything validates, walks or allocates much: alias
bombs, deep nesting, long texts and lists, tags, numbers that are not finite, keys that are not texts, names with
a final newline, unknown keys; the same text read alike from a file and from ``--config``; and each bound stated
once (the scenes' counts against the schema, the descriptions filled in from their nodes' keywords)."""

from __future__ import annotations

import copy
import re
import time
import tracemalloc
from pathlib import Path

import pytest

from escapement.model.parameters import ParameterError
from escapement.pipeline.config import ConfigError, read_yaml, typed_overrides, user_config, validated
from escapement.pipeline.sources import MAX_BYTES, MAX_CHARS, MAX_DEPTH, MAX_ITEMS
from escapement.scenes import settings
from escapement.studies.readings import AMPLITUDES

REPO = Path(__file__).resolve().parents[2]
SCHEMAS = REPO / "workflow" / "schemas"
CONFIG_SCHEMA, PAPER_SCHEMA = SCHEMAS / "config.schema.yaml", SCHEMAS / "paper.schema.yaml"
PAPER = read_yaml(REPO / "config" / "paper.yaml")

pytestmark = pytest.mark.timeout(60)


def list_bomb(levels: int = 9) -> str:
    """A billion laughs under model.M: ``levels`` lists of ten aliases of the one before (10**levels items)."""
    text = "model:\n  M:\n    - &a0 [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]\n"
    return text + "".join(f"    - &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]\n" for i in range(1, levels + 1))


def mapping_bomb(levels: int = 9) -> str:
    """The same with mappings, in one line, as a ``--config`` value."""
    parts = ["a0: &a0 {" + ", ".join(f"k{j}: 1" for j in range(10)) + "}"]
    parts += [f"a{i}: &a{i} {{" + ", ".join(f"k{j}: *a{i - 1}" for j in range(10)) + "}" for i in range(1, levels)]
    return "{" + ", ".join(parts) + "}"


def refused_fast(read, match: str, seconds: float = 5.0, megabytes: float = 20.0) -> str:
    """``read()`` refused with a one-line ConfigError matching ``match``, within ``seconds`` and ``megabytes``."""
    tracemalloc.start()
    start = time.perf_counter()
    try:
        with pytest.raises(ConfigError, match=match) as refused:
            read()
    finally:
        elapsed, peak = time.perf_counter() - start, tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    message = str(refused.value)
    assert "\n" not in message and len(message) < 400, message
    assert elapsed < seconds and peak < megabytes * 1e6, (elapsed, peak)
    return message


def in_file(tmp_path: Path, text: str | bytes) -> Path:
    path = tmp_path / "my.yaml"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


@pytest.mark.parametrize("levels", [3, 9])
def test_an_alias_bomb_in_a_file_is_refused_at_its_first_anchor(tmp_path, levels):
    path = in_file(tmp_path, list_bomb(levels))
    message = refused_fast(lambda: read_yaml(path), "line 3, column 7: the anchor &a0 is refused")
    assert message.startswith(str(path))


def test_an_alias_bomb_of_mappings_on_the_command_line_is_refused_at_once():
    refused_fast(lambda: typed_overrides({}, [f"model={mapping_bomb()}"]), r"^--config model, line 1, column \d+: "
                 "the anchor &a0 is refused")


def test_an_alias_alone_is_refused_too():
    refused_fast(lambda: typed_overrides({}, ["fig5={K: *k}"]), "the alias \\*k is refused")


NESTINGS = {
    "flow lists": lambda d: "[" * d + "]" * d,
    "flow mappings": lambda d: "{a: " * d + "1" + "}" * d,
    "block lists": lambda d: "\n    " + "- " * d + "1",
}


@pytest.mark.parametrize("shape", NESTINGS)
@pytest.mark.parametrize("depth", [MAX_DEPTH - 2, MAX_DEPTH - 1, 5_000])
def test_a_deep_nesting_is_refused_in_one_line_without_a_recursion_error(tmp_path, shape, depth):
    """Nested ``depth`` levels under model.M (two more levels), from a file and from --config alike: within the
    bound it reads; beyond, refused."""
    text = f"model:\n  M: {NESTINGS[shape](depth)}\n"
    if depth + 2 <= MAX_DEPTH:
        config: dict = {}
        typed_overrides(config, [f"model={{M: {NESTINGS[shape](depth)}}}"] if shape != "block lists" else [])
        assert read_yaml(in_file(tmp_path, text)) == (config or read_yaml(in_file(tmp_path, text)))
        return
    refused_fast(lambda: read_yaml(in_file(tmp_path, text)), f"more than {MAX_DEPTH} levels of nesting is refused")
    refused_fast(lambda: typed_overrides({}, [f"model={{M: {NESTINGS[shape](depth)}}}"]), "^--config model, ")


@pytest.mark.parametrize("text, match", [
    ("name: " + "a" * (MAX_BYTES + 10), f"more than {MAX_BYTES} bytes is too long"),
    ("fig5:\n  K: [" + ", ".join(["1.0"] * 10_000) + "]\n", f"more than {MAX_ITEMS} items is refused"),
    ("model:\n  M: " + "1" * 5_000 + "\n", f"a value of 5000 characters is refused: a value holds at most {MAX_CHARS}"),
    ("model:\n  M: !!python/name:os.system\n", "the tag !!python/name:os.system is refused"),
    ("model:\n  M: !!float 1\n", "the tag !!float is refused"),
    ("model:\n  M: !!binary aGVsbG8=\n", "the tag !!binary is refused"),
    ("fig3: !!set {a, b}\n", "the tag !!set is refused"),
    ("model:\n  M: 1e400\n", "my.yaml: model.M = inf is invalid: M must be a finite number"),
    ("model:\n  M: -.inf\n", "model.M = -inf is invalid: M must be a finite number"),
    ("fig5:\n  K: [0.1, .nan]\n", r"fig5.K\[1\] = nan is invalid: K must be a finite number"),
    ("fig3:\n  cases:\n    1: {F: 1.0, x0: -1.0}\n", "fig3.cases: the key 1 is invalid: a key must be a text"),
    ("? [a, b]\n: 1\n", r"the top level: the key \('a', 'b'\) is invalid: a key must be a text"),
    ("model:\n  M: 1.0\n  M: 2.0\n", "line 3, column 3: not valid YAML: found duplicate key"),
    ("a: 1\n---\nb: 2\n", "line 2, column 1: not valid YAML: but found another document"),
    ("model: {M: 1\x00}\n", "not valid YAML"),
    (b"name: \xff\n", "byte 7 is not UTF-8"),
])
def test_a_hostile_file_is_refused_in_one_line_naming_where(tmp_path, text, match):
    path = in_file(tmp_path, text)
    assert refused_fast(lambda: read_yaml(path), match).startswith(str(path))


def test_a_hostile_command_line_value_is_refused_alike():
    refused_fast(lambda: typed_overrides({}, ["model={M: 1e400}"]), "^--config model: model.M = inf is invalid: M "
                 "must be a finite number$")
    refused_fast(lambda: typed_overrides({}, ["name=.nan"]), "^--config name: name = nan is invalid")
    refused_fast(lambda: typed_overrides({}, ["fig5={K: [" + "1," * 20_000 + "]}"]), "more than 5000 items")
    refused_fast(lambda: typed_overrides({}, ["fig5=" + "[" * 500_000]), "bytes is too long")
    refused_fast(lambda: typed_overrides({}, ["a\n={b: .inf}"]), "^--config 'a\\\\n': 'a\\\\n'.b = inf")
    assert "unknown key 'a\\n'" in refusal_of(user_config([], ["a\n=1"]))  # Snakemake's own check lets it by


#: texts whose value YAML 1.1 (Snakemake's reader of files) and YAML 1.2 read differently, or that a reader
#: may fail on; each reads the same from a file and from --config
TEXTS = {"2e0": 2.0, "1e5": 100000.0, "1.0e-3": 0.001, ".5": 0.5, "017": 17, "0o17": 15, "0x1F": 31, "+1": 1,
         "yes": "yes", "on": "on", "~": None, "true": True, "1_000": "1_000", "-0x1F": "-0x1F", "1:20": "1:20",
         "2001-12-14": "2001-12-14", "2001-13-45": "2001-13-45", "0x_": "0x_", "=": "="}


@pytest.mark.parametrize("text", TEXTS)
def test_the_same_text_gives_the_same_value_from_a_file_and_from_the_command_line(tmp_path, text):
    from_file = user_config([in_file(tmp_path, f"model:\n  M: {text}\nname: {text}\n")], [])
    from_command_line = user_config([], [f"model={{M: {text}}}", f"name={text}"])
    assert from_file == from_command_line == {"model": {"M": TEXTS[text]}, "name": TEXTS[text]}


def test_the_sources_lie_over_one_another_as_snakemake_lays_them(tmp_path):
    first, second = tmp_path / "a.yaml", tmp_path / "b.yaml"
    first.write_text("name: one\nmodel: {M: 2.0, K: 3.0}\nfig3: 1\n")
    second.write_text("model: {K: 4.0}\n")
    config = user_config([first, second], ["model={b: 0.2}", "fig3={n_cycles: 5}", "name=two"])
    assert config == {"name": "two", "model": {"M": 2.0, "K": 4.0, "b": 0.2}, "fig3": {"n_cycles": 5}}


def refusal_of(config: dict, schema: Path = CONFIG_SCHEMA, source: str = "the configuration") -> str:
    with pytest.raises(ConfigError) as refused:
        validated(config, schema, source)
    message = str(refused.value)
    assert "\n" not in message and len(message) < 400, message
    return message


@pytest.mark.parametrize("config, message", [
    ({"fig5": {"k": [1.0]}}, "the configuration: fig5: unknown key 'k' (did you mean 'K'?)"),
    ({"model": {"m": 2.0}}, "the configuration: model: unknown key 'm' (did you mean 'M'?)"),
    ({"Model": {}}, "the configuration: the top level: unknown key 'Model' (did you mean 'model'?)"),
    ({"fig6": {}}, "the configuration: the top level: unknown key 'fig6' (did you mean 'fig5'?)"),
    ({"fig4": {"velocity_windw": [1.0, 2.0]}}, "fig4: unknown key 'velocity_windw' (did you mean 'velocity_window'?)"),
    ({"fig3": {"cases": {"a": {"F": 1.0, "x0": 1.0, "A1": 0.1}}}}, "fig3.cases.a: unknown key 'A1' (did you mean "
                                                                    "'a1'?)"),
    ({"ü": 1}, "the configuration: the top level: unknown key 'ü' (the keys are name, model, fig3, fig4, fig5"),
])
def test_an_unknown_key_is_refused_with_the_closest_the_schema_names_there(config, message):
    assert message in refusal_of(config)


def objects(value, path=()):
    """Every mapping of ``value`` with its path."""
    if isinstance(value, dict):
        yield path, value
        for key, item in value.items():
            yield from objects(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from objects(item, (*path, index))


CLOSED = [(path, key) for path, mapping in objects(PAPER) for key in mapping
          if key.swapcase() != key and path[:2] not in (("fig3", "cases"), ("escapement_error", "zones"))
          and path[:3] != ("checks", "airy", "zones")]


@pytest.mark.parametrize("path, key", CLOSED, ids=[".".join(map(str, p + (k,))) for p, k in CLOSED])
def test_every_key_of_the_paper_s_file_mistyped_in_case_is_refused_naming_it(path, key):
    """Each key of config/paper.yaml, its case swapped, refused as unknown with the key it stands for (a key of
    the cases and zones is a name the user chooses: refused by its pattern instead)."""
    paper = copy.deepcopy(PAPER)
    mapping = paper
    for step in path:
        mapping = mapping[step]
    mapping[key.swapcase()] = mapping.pop(key)
    message = refusal_of(paper, PAPER_SCHEMA, "config/paper.yaml")
    where = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in path).lstrip(".") or "the top level"
    assert message == f"config/paper.yaml: {where}: unknown key {key.swapcase()!r} (did you mean {key!r}?)"


@pytest.mark.parametrize("config, message", [
    ({"name": "replication"}, "name = 'replication' is invalid"),
    ({"name": "logs"}, "name = 'logs' is invalid"),
    ({"name": "replication\n"}, "name = 'replication\\n' is invalid"),
    ({"name": "own\n"}, "name = 'own\\n' is invalid"),
    ({"name": "Own"}, "name = 'Own' is invalid"),
    ({"name": "a" * 65}, "(at most 64)"),
    ({"fig3": {"cases": {"a\n": {"F": 1.0, "x0": -1.0}}}}, "fig3.cases: the key 'a\\n' is invalid: a key must be one "
                                                           "lowercase letter"),
    ({"escapement_error": {"zones": {"paper\n": [-0.1, 0.05]}}}, "the key 'paper\\n' is invalid"),
])
def test_a_name_is_refused_unless_it_matches_exactly(config, message):
    assert message in refusal_of(config)


@pytest.mark.parametrize("name", ["own", "replication2", "my-study_2"])
def test_a_name_that_matches_is_taken(name):
    validated({"name": name}, CONFIG_SCHEMA, "the configuration")


def schema_nodes(node, path=""):
    """Every mapping of a schema with its path."""
    if isinstance(node, dict):
        yield path, node
        for key, value in node.items():
            yield from schema_nodes(value, f"{path}/{key}")
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from schema_nodes(value, f"{path}/{index}")


NODES = [(f"{name}{path}", node) for name in ("config.schema.yaml", "paper.schema.yaml")
         for path, node in schema_nodes(read_yaml(SCHEMAS / name))]


def test_every_pattern_of_the_schemas_matches_exactly_not_before_a_final_newline():
    patterns = [node["pattern"] for _, node in NODES if isinstance(node.get("pattern"), str)]
    assert len(patterns) >= 4 and all(p.startswith("^") and p.endswith("(?![\\s\\S])") for p in patterns)
    for pattern in patterns:
        example = "a" if "[a-z]" in pattern else "_"
        assert re.search(pattern, example) and not re.search(pattern, example + "\n")


def test_every_list_of_the_schemas_has_a_most_items():
    lists = [path for path, node in NODES if node.get("type") == "array"]
    assert len(lists) > 15 and [path for path, node in NODES if node.get("type") == "array"
                                and "maxItems" not in node] == []


def test_twenty_thousand_spring_constants_are_refused_by_the_reader_and_thirteen_by_the_schema():
    refused_fast(lambda: typed_overrides({}, [f"fig5={{K: [{','.join(['1'] * 20_000)}]}}"]), "items is refused")
    assert "fig5.K = [1.0, 2.0, 3.0" in refusal_of({"fig5": {"K": [float(k) for k in range(1, 14)]}})


def test_every_description_is_filled_in_from_its_node_and_states_no_bound_of_its_own():
    """The refusal fills ``{maximum}`` from the node; a number a node bounds by is never written in its
    description, so that the bound is stated once."""
    keywords = ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "minItems", "maxItems",
                "minProperties", "maxProperties", "maxLength")
    for path, node in NODES:
        if not isinstance(node.get("description"), str):
            continue
        filled = node["description"].format_map(node)
        written = set(re.findall(r"(?<![\w.{])\d+(?:\.\d+)?(?![\w}])", node["description"]))
        stated = {str(node[k]) for k in keywords if isinstance(node.get(k), int | float)}
        assert not written & stated, (path, node["description"])
        assert "{" not in filled or "{F, x0}" in filled, path


def counts_in_schema() -> dict[str, tuple[int, int]]:
    """Every integer of the blocks whose scenes check their counts again, by ``block.key`` (``block.axis.n``),
    with its bounds, each ``$ref`` followed."""
    schema = read_yaml(CONFIG_SCHEMA)

    def resolved(node: dict) -> dict:
        while "$ref" in node:
            target = schema
            for step in node["$ref"].removeprefix("#/").split("/"):
                target = target[step]
            node = {**target, **{k: v for k, v in node.items() if k != "$ref"}}
        return node

    found = {}

    def walk(node: dict, name: str) -> None:
        node = resolved(node)
        if node.get("type") == "integer":
            found[name] = (node["minimum"], node["maximum"])
        for key, child in node.get("properties", {}).items():
            walk(child, f"{name}.{key}")

    for block in ("fig3", "fig4", "fig5", "escapement_error", "stability_map", "existence_map", "long_run"):
        walk(schema["$defs"][block], block)
    return found


def test_the_scenes_check_their_counts_within_the_bounds_the_schema_states():
    assert counts_in_schema() == settings.COUNTS


@pytest.mark.parametrize("key", settings.COUNTS)
def test_each_count_is_taken_at_its_bounds_and_refused_beyond(key):
    least, most = settings.COUNTS[key]
    name = key.split(".", 1)[1]
    assert settings._count(key, least) == least and settings._count(key, most) == most
    for value in (least - 1, most + 1, float(least), True, "1"):
        with pytest.raises(ParameterError, match=f"^{re.escape(name)} = "):
            settings._count(key, value)


def test_the_amplitudes_are_the_definitions_the_readings_hold_and_a_refusal_names_them():
    assert settings.AMPLITUDES == tuple(AMPLITUDES)
    message = refusal_of({"fig3": {"amplitude": "peak"}})
    assert message.endswith(f"amplitude must be one of {', '.join(AMPLITUDES)}")
