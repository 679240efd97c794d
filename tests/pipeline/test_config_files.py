"""The configuration's sources read strictly: every file (a key given twice, a YAML or JSON error, no
mapping at the top) named with its line, and the nested values of ``--config`` read again as YAML,
compared with what Snakemake's own reading of the command line gives."""

from __future__ import annotations

import json

import pytest
from snakemake.cli import parse_config

from escapement.pipeline.config_files import (
    ConfigError,
    apply_config_overrides,
    check_config_file,
    check_config_files,
    config_overrides,
)

# --- files ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name, text, where, words",
    [
        # a key given twice: at the top, in a nested block, in a flow mapping, in an item of a list,
        # in a JSON object (which Snakemake reads with json.load, keeping the last)
        ("top.yaml", "model: {}\nfig3: {}\nmodel: {}\n", "line 3, column 1",
         ["'model' is given twice (first on line 1)"]),
        ("deep.yaml", "stability_map:\n  b:\n    start: 0.0\n    n: 4\n    start: 1.0\n", "line 5, column 5",
         ["'start' is given twice (first on line 3)"]),
        ("flow.yaml", "model: {M: 1.0, K: 2.0, M: 3.0}\n", "line 1, column 25",
         ["'M' is given twice (first at column 9)"]),
        ("item.yaml", "checks:\n  initial_conditions:\n    - F: 1.0\n      x0: 3.0\n      F: 2.0\n", "line 5, column 7",
         ["'F' is given twice (first on line 3)"]),
        ("dup.json", '{\n  "model": {\n    "M": 1.0,\n    "M": 2.0\n  }\n}\n', "line 4, column 5",
         ["not valid JSON", "'M' is given twice (first on line 3)"]),
        # syntax errors: an unclosed bracket, an unclosed quote, a tab, a stray indentation, a second colon
        ("bracket.yaml", "fig4:\n  F: [0.5\n  K: 0.1\n", "line 3, column 4",
         ["expected ',' or ']'", "starts on line 2"]),
        ("quote.yaml", 'model:\n  M: "1.0\n  K: 2\n', "line 4, column 1", ["quoted scalar that starts on line 2"]),
        ("tab.yaml", "model:\n\tM: 1.0\n", "line 2, column 1", ["'\\t' that cannot start any token"]),
        ("indent.yaml", "model:\n  M: 1.0\n   K: 2\n", "line 3, column 5", ["mapping values are not allowed here"]),
        ("colon.yaml", "model:\n  M: 1.0: 2\n", "line 2, column 9", ["mapping values are not allowed here"]),
    ],
)
def test_a_file_that_gives_a_key_twice_or_is_not_yaml_is_named_with_its_line(tmp_path, name, text, where, words):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ConfigError) as caught:
        check_config_file(path)
    message = str(caught.value)
    assert message.startswith(f"{path}, {where}: not valid "), message
    assert "\n" not in message
    for word in words:
        assert word in message, message


@pytest.mark.parametrize(
    "text, words",
    [("", "not empty"), ("- 1\n- 2\n", "not list"), ("just text\n", "not str"), ("[1, 2]", "not list")],
)
def test_a_file_without_a_mapping_at_its_top_is_refused(tmp_path, text, words):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as caught:
        check_config_file(path)
    assert str(caught.value) == f"{path}: the configuration must be a mapping of keys at its top level, {words}"


def test_a_file_that_is_not_utf8_is_named(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_bytes(b"model:\n  M: 1.0 # \xe9\n")
    with pytest.raises(ConfigError, match="config.yaml: not UTF-8 text"):
        check_config_file(path)


@pytest.mark.parametrize(
    "text",
    [
        '{\n\t"model": {\n\t\t"M": 1.0\n\t}\n}\n',  # JSON indented by tabs, which YAML would refuse
        "a: &common {M: 1.0, K: 1.0}\nmodel:\n  <<: *common\n  M: 2.0\n",  # a merge key: its keys may be overridden
        "model:\n  M: 1.0\nfig3:\n  cases:\n    a: {M: 2.0}\n    b: {M: 3.0}\n",  # one key in several mappings
    ],
)
def test_a_file_that_gives_each_key_once_is_accepted(tmp_path, text):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    check_config_file(path)


def test_every_file_is_checked_and_each_once(tmp_path):
    good, bad = tmp_path / "good.yaml", tmp_path / "bad.yaml"
    good.write_text("model: {M: 1.0}\n")
    bad.write_text("model: {M: 1.0, M: 2.0}\n")
    check_config_files([good, str(good), tmp_path / "." / "good.yaml"])
    with pytest.raises(ConfigError, match="bad.yaml, line 1, column 17"):
        check_config_files([good, bad])
    with pytest.raises(ConfigError, match="missing.yaml: cannot read"):
        check_config_files([good, tmp_path / "missing.yaml"])


# --- --config overrides -----------------------------------------------------------------------


def _typed(*entries):
    """What the overrides make of ``entries``: Snakemake's reading, merged into an empty configuration
    and then read again (as the workflow does)."""
    given = parse_config(list(entries))
    config = json.loads(json.dumps(given))
    apply_config_overrides(config, list(entries), given)
    return config


@pytest.mark.parametrize(
    "entries, expected",
    [
        (["fig3={n_cycles: 40}"], {"fig3": {"n_cycles": 40}}),
        (["fig3={n_cycles: 40, amplitude: amplitude_h4}"], {"fig3": {"n_cycles": 40, "amplitude": "amplitude_h4"}}),
        (["fig5={K: [0.1, 1.0], F: [1.0, 0.5], x0: -1.0}"], {"fig5": {"K": [0.1, 1.0], "F": [1.0, 0.5], "x0": -1.0}}),
        (["stability_map={b: {start: 0.0, stop: 2.0, n: 4}}"], {"stability_map": {"b": {"start": 0.0, "stop": 2.0,
                                                                                        "n": 4}}}),
        (['model={"M": 2.0, "b": 0.2}'], {"model": {"M": 2.0, "b": 0.2}}),  # JSON
        (["speed={headline: {target: 1.0e-9}}"], {"speed": {"headline": {"target": 1.0e-9}}}),
        (["fig3={cases: {a: {F: 1.0, x0: -1.0}}}"], {"fig3": {"cases": {"a": {"F": 1.0, "x0": -1.0}}}}),
        (["fig3=n_cycles: 40"], {"fig3": {"n_cycles": 40}}),  # a block mapping on one line
        (["checks={b: [0.1, 0.2]}", "checks={F: 0.5}"], {"checks": {"b": [0.1, 0.2], "F": 0.5}}),  # merged
        (["model={M: 1.0}", "model={M: 2.0}"], {"model": {"M": 2.0}}),  # the last wins, as in Snakemake
        (["fig3={amplitude: '5'}"], {"fig3": {"amplitude": "5"}}),  # quoted: text, as in a file
        (["flag=true"], {"flag": "true"}),  # a scalar: Snakemake's own reading (True/False are its booleans)
        (["count=3", "rate=0.5", "name=step1"], {"count": 3, "rate": 0.5, "name": "step1"}),
    ],
)
def test_a_nested_value_has_the_types_a_file_gives_it(entries, expected):
    assert _typed(*entries) == expected


def test_a_key_given_a_scalar_then_a_mapping_keeps_the_files_other_keys_as_in_snakemake():
    """Snakemake merges the entries among themselves first, then into the files' configuration."""
    config = {"fig3": {"n_cycles": 50, "amplitude": "amplitude_h0"}}
    entries = ["fig3=none", "fig3={n_cycles: 40}"]
    given = parse_config(entries)
    config["fig3"]["n_cycles"] = "40"  # as Snakemake merges it
    apply_config_overrides(config, entries, given)
    assert config == {"fig3": {"n_cycles": 40, "amplitude": "amplitude_h0"}}


def test_the_overrides_replace_what_snakemake_merged_into_the_files_and_keep_the_rest():
    config = {"fig3": {"n_cycles": 50, "amplitude": "amplitude_h0", "cases": {"a": {"F": 1.0, "x0": -1.0}}}}
    entries = ["fig3={n_cycles: 40, cases: {a: {F: 0.5}}}"]
    given = parse_config(entries)
    assert given == {"fig3": {"n_cycles": "40", "cases": {"a": {"F": "0.5"}}}}  # Snakemake's reading: text
    config["fig3"]["n_cycles"], config["fig3"]["cases"]["a"]["F"] = "40", "0.5"  # as Snakemake merges it
    apply_config_overrides(config, entries, given)
    assert config == {"fig3": {"n_cycles": 40, "amplitude": "amplitude_h0", "cases": {"a": {"F": 0.5, "x0": -1.0}}}}


def test_values_given_as_objects_through_snakemakes_api_are_left_as_they_are():
    """Without a command line, Snakemake writes the entries from the objects (``repr``): not read again."""
    given = {"speed": {"headline": {"target": 1e-05}}, "fig3": {"n_cycles": 40}}
    entries = [f"{key}={value!r}" for key, value in given.items()]
    assert config_overrides(entries, given) == {}


@pytest.mark.parametrize(
    "entry, words",
    [
        ("fig3={n_cycles: 40", ["--config 'fig3={n_cycles: 40', column 19: not valid YAML: expected ',' or '}'"]),
        ("fig5={K: [0.1, 1.0}", ["--config 'fig5={K: [0.1, 1.0}', column 19: not valid YAML"]),
        ("model={M: 1.0, M: 2.0}", ["column 16: not valid YAML: the key 'M' is given twice (first at column 8)"]),
        ("model={M: 1.0, b: {x: 1, x: 2}}", ["the key 'x' is given twice"]),
    ],
)
def test_a_nested_value_that_is_not_yaml_is_refused_saying_to_use_a_file(entry, words):
    with pytest.raises(ConfigError) as caught:
        config_overrides([entry], parse_config([entry]))
    message = str(caught.value)
    assert message.endswith("; a nested value may also be given in a file, with --configfile"), message
    for word in words:
        assert word in message, message
