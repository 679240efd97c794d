"""The workflow's configuration: a user's blocks laid over the paper's, the kinds that become the user's study,
and every refusal one line naming the source, the key, its value and the rule (one table of cases), checked with
the schemas through Snakemake's validate as the rules do (the hostile inputs: test_config_hostile.py)."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from snakemake.utils import validate

from escapement.pipeline.config import (
    ConfigError,
    check_cases,
    own_blocks,
    read_yaml,
    replication_scenes,
    study_scenes,
    typed_overrides,
    validated,
)

REPO = Path(__file__).resolve().parents[2]
SCHEMAS = REPO / "workflow" / "schemas"
PAPER = read_yaml(REPO / "config" / "paper.yaml")


def checked(config: dict) -> None:
    """What the rules do with a user's configuration: the schema, then the study it makes."""
    validated(config, SCHEMAS / "config.schema.yaml", "the configuration")
    study_scenes(config.get("name", "own"), own_blocks(config, PAPER))


def test_the_paper_s_file_is_valid_and_makes_every_scene():
    validate(copy.deepcopy(PAPER), str(SCHEMAS / "paper.schema.yaml"), set_default=False)
    scenes = study_scenes("replication", {"model": PAPER["model"], **PAPER})
    assert list(scenes["fig3"]) == list(PAPER["fig3"]["cases"]) and list(scenes["fig5"]) == ["0.1", "1", "10"]
    assert scenes["fig5"]["10"]["F"] == PAPER["fig5"]["F"][2] and scenes["fig3"]["a"]["study"] == "replication"
    runs = replication_scenes(PAPER)
    assert runs["long_run"]["x0"] == PAPER["fig3"]["cases"][PAPER["long_run"]["case"]]["x0"]


def test_the_user_s_blocks_lie_over_the_paper_s_and_only_the_kinds_that_differ_are_the_user_s():
    assert own_blocks({}, PAPER) == {"model": PAPER["model"]}
    assert own_blocks({"fig5": dict(PAPER["fig5"])}, PAPER) == {"model": PAPER["model"]}  # the paper's own values
    blocks = own_blocks({"fig5": {"K": [0.1, 1.0, 5.0]}}, PAPER)
    assert set(blocks) == {"model", "fig5"} and blocks["fig5"]["F"] == PAPER["fig5"]["F"]
    assert blocks["fig5"]["K"] == [0.1, 1.0, 5.0]
    heavier = own_blocks({"model": {"M": 2.0}}, PAPER)  # the model counts for the kinds it reaches
    assert {"model", "fig3", "fig4", "fig5", "escapement_error", "stability_map"} <= set(heavier)
    scenes = study_scenes("heavy", heavier)
    assert scenes["fig4"][""]["M"] == 2.0 and scenes["fig3"]["b"]["study"] == "heavy"


def test_a_nested_config_value_gets_the_types_a_file_gives_it():
    """Snakemake reads ``--config fig5={K: [0.1, 1.0, 5.0]}`` with every scalar as text; each entry is read again
    and laid over the configuration, a mapping key by key."""
    config = {"name": "own", "fig5": {"K": ["0.1", "1.0", "5.0"], "n_cycles": 10}}
    typed_overrides(config, ["fig5={K: [0.1, 1.0, 5.0]}", "name=own"])
    assert config["fig5"] == {"K": [0.1, 1.0, 5.0], "n_cycles": 10} and config["name"] == "own"


@pytest.mark.parametrize("config, message", [
    ({"checks": {"n_cycles": 4}}, "the configuration: the top level: unknown key 'checks' (the keys are name, "
                                  "model, fig3"),
    ({"fig5": {"k": [1.0]}}, "the configuration: fig5: unknown key 'k' (did you mean 'K'?)"),
    ({"fig5": {"K": [0.1, -2.0, 1.0]}}, "your study 'own': fig5: K = -2.0 is invalid: K must be > 0 (N/m)"),
    # a case of the paper's takes the keys given (x0 from the paper's); a new case needs its own
    ({"fig3": {"cases": {"c": {"F": 1.0}}}}, "your study 'own': fig3: x0 = None is invalid: x0 must be given"),
    ({"fig3": {"amplitude": "peak"}}, "fig3.amplitude = 'peak' is invalid: amplitude must be one of amplitude_h0"),
    ({"name": "replication"}, "name = 'replication' is invalid: name must be a name of lowercase letters"),
    ({"fig5": {"K": [0.1, 1.0]}}, "your study 'own': fig5.F = [1.0, 0.5, 0.5] is invalid: F must be one number, "
                                  "or a list of 2 numbers"),
    ({"fig5": {"K": [0.1, 0.1000000000001]}}, "fig5.K = [0.1, 0.1000000000001] is invalid: K must be spring "
                                              "constants that differ in their file labels"),
    ({"fig4": {"velocity_window": [87.0, 80.0]}}, "your study 'own': fig4: velocity_window = [87.0, 80.0] is "
                                                  "invalid: velocity_window must be a pair [start, end] with"),
    ({"fig3": {"cases": {"a": {"F": 1.0, "x0": -1.0, "a2": -0.2}}}}, "your study 'own': fig3: a2 = -0.2 is "
                                                                     "invalid: a2 must be > a1 = -0.1 (m)"),
    ({"model": {"a4": 0.2}}, "a4 = 0.2 is invalid: a4 must be < a3 = 0.1 (m)"),
    ({"stability_map": {"b": {"start": 2.0, "stop": 0.0, "n": 4}}},
     "your study 'own': stability_map: b = {'start': 2.0, 'stop': 0.0, 'n': 4} is invalid: b must be an axis"),
    ({"fig5": {"n_cycles": 10_000, "samples_per_period": 2000}}, "samples_per_period = 2000 is invalid"),
    ({"fig3": {"cases": {"a": {"F": 1.0, "x0": -1.0, "M": 1e-320}}}}, "M = 1e-320 is invalid: M must be"),
    ({"fig5": {"samples_per_period": 2}}, "fig5.samples_per_period = 2 is invalid: samples_per_period must be an "
                                          "integer in [8, 100000]"),
    ({"existence_map": {"F": {"start": 0.0, "stop": 1.0, "n": 0}}}, "existence_map.F.n = 0 is invalid: n must be an "
                                                                    "integer in [1, 400]"),
])
def test_each_problem_is_refused_in_one_line_naming_the_key_its_value_and_the_rule(config, message):
    with pytest.raises(ConfigError) as refused:
        checked(config)
    assert message in str(refused.value) and "\n" not in str(refused.value)


def test_every_constraint_of_the_schemas_names_its_rule_for_the_refusal():
    """A refusal's rule is the violated schema's description (an enumeration's is its list of values); a
    combinator's branches (anyOf, not) report at the key that holds them, which has one."""
    missing = []

    def walk(node, path: str) -> None:
        if isinstance(node, dict):
            constrained = node.get("type") in ("integer", "number", "string", "boolean") or any(
                key in node for key in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum",
                                        "minItems", "maxItems", "pattern"))
            if constrained and "description" not in node and "$ref" not in node:
                missing.append(path)
            for key, value in node.items():
                if key not in ("anyOf", "not"):
                    walk(value, f"{path}/{key}")
        elif isinstance(node, list):
            for value in node:
                walk(value, path)

    for name in ("config.schema.yaml", "paper.schema.yaml"):
        walk(read_yaml(SCHEMAS / name), name)
    assert missing == []


@pytest.mark.parametrize("text, message", [
    ("model:\n  M: 1.0\n  M: 2.0\n", "line 3, column 3: not valid YAML: found duplicate key \"M\""),
    ("fig5: {K: [0.1, 1.0\n", "not valid YAML: expected ',' or ']'"),
    ("- 1\n- 2\n", "the configuration must be a mapping of keys, not list"),
])
def test_a_file_is_read_strictly_naming_its_line(tmp_path, text, message):
    path = tmp_path / "my.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=f"^{path}") as refused:
        read_yaml(path)
    assert message in str(refused.value)


def test_a_benchmark_on_a_case_fig3_lacks_is_refused():
    with pytest.raises(ConfigError, match="benchmark.case = 'z' is invalid: case must be a case of fig3.cases"):
        replication_scenes({**PAPER, "benchmark": {**PAPER["benchmark"], "case": "z"}})


def test_the_claims_runs_take_every_k_of_fig5_at_every_force_of_the_figure():
    cases = check_cases(PAPER)
    common = [c["label"] for c in cases if c["group"] == "common_force"]
    assert common == ["K=0.1,F=0.5", "K=1,F=0.5", "K=10,F=0.5", "K=0.1,F=1", "K=1,F=1", "K=10,F=1"]
    assert [c["label"] for c in cases if c["group"] == "paper"] == ["fig3a", "fig3b"]


@pytest.mark.parametrize("model, message", [
    ({"M": 0}, "the configuration: model.M = 0.0 is invalid: M must be > 0 (kg)"),
    ({"K": 1e60}, "the configuration: model.K = 1e+60 is invalid: K must be in [1e-50, 1e+50] (N/m)"),
    ({"b": 2.0}, "the configuration: model.b = 2.0 is invalid: b must be in the open interval (0, 2)"),
    ({"a2": -0.2}, "the configuration: model.a2 = -0.2 is invalid: a2 must be > a1 = -0.1 (m)"),
])
def test_the_model_block_is_checked_by_the_model_s_own_bounds_which_the_schema_does_not_repeat(model, message):
    import yaml

    from escapement.pipeline.config import check_model

    properties = yaml.safe_load((SCHEMAS / "config.schema.yaml").read_text())["$defs"]["model"]["properties"]
    assert all(set(node) <= {"title", "type", "description"} for node in properties.values())
    with pytest.raises(ConfigError) as refused:
        check_model({**PAPER["model"], **model}, "the configuration")
    assert str(refused.value).startswith(message)
