"""The workflow's configuration: one check with one-line messages, and each scene built from it."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

from escapement.model.parameters import Parameters
from escapement.model.quantities import INITIAL_STATE, PARAMETERS
from escapement.pipeline.config import (
    ConfigError,
    benchmark_scene,
    benchmark_settings,
    check_cases,
    check_config,
    check_config_file,
    config_error,
    fig3_scene,
    fig4_scene,
    fig5_labels,
    fig5_scene,
    long_run_scene,
    stability_axes,
    stability_chunk,
    stability_chunks,
    stability_model,
)

ROOT = Path(__file__).resolve().parents[2]
SCHEMA_PATH = ROOT / "workflow/schemas/config.schema.yaml"
SCHEMA = yaml.safe_load(SCHEMA_PATH.read_text())

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}

#: a small configuration written out here, so that the expected scenes are known by hand
CONFIG = {
    "model": dict(MODEL),
    "fig3": {"n_cycles": 50, "amplitude": "amplitude_h0",
             "cases": {"a": {"F": 1.0, "x0": 1.0}, "b": {"F": 0.5, "x0": 3.0, "b": 0.2}}},
    "fig4": {
        "F": 0.5,
        "x0": 3.0,
        "velocity_window": [80.0, 87.0],
        "acceleration_window": [81.0, 85.0],
        "samples_per_second": 1000,
    },
    "fig5": {"F": 0.5, "x0": 1.0, "K": [0.1, 1.0, 10.0], "n_cycles": 60, "samples_per_period": 400},
    "checks": {
        "n_cycles": 300,
        "x0": 1.0,
        "F": 1.0,
        "initial_conditions": [{"F": 0.5, "x0": 2.0}],
        "b": [0.3],
        "symmetric": {"F": [0.2], "positions": [[-0.3, 0.2]]},
        "asymmetric": {"F": [3.0], "positions": [[-0.1, 0.05, 0.2, -0.02]]},
    },
    "benchmark": {
        "case": "a",
        "n_cycles": 50,
        "min_seconds": 0.2,
        "max_repeats": 500,
        "settings": {"exact": [], "RK45": [1.0e-3, 1.0e-6], "naive-RK4": [0.1]},
        "slow_settings": {"naive-RK4": [1.0e-4], "Radau": [1.0e-9]},
    },
    "speed": {"headline": {"n_cycles": 20, "target": 1.0e-9, "settings": {"DOP853": [1.0e-12]}},
              "floor": {"exact_cycles": [100], "ensemble_trajectories": 10, "ensemble_cycles": 5,
                        "stream_cycles": [100, 1000]}},
    "long_run": {"case": "b", "n_cycles": 1000, "ivp_method": "DOP853", "ivp_rtol": 1.0e-12, "ivp_cycles": 100},
    "escapement_error": {"F": {"start": 0.1, "stop": 0.4, "n": 3}, "zones": {"paper": [-0.1, 0.05]}},
    "stability_map": {"b": {"start": 0.0, "stop": 2.0, "n": 4}, "F": {"start": 1.0, "stop": 2.0, "n": 3}, "chunks": 3},
    "existence_map": {"a3": {"start": 0.0, "stop": 0.25, "n": 5}, "F": {"start": 0.0, "stop": 0.01, "n": 4}, "x0": -1.0,
                      "n_cycles": 120, "tolerance": 1.0e-9},
}


@pytest.fixture
def config():
    return copy.deepcopy(CONFIG)


def test_the_shipped_configuration_is_valid():
    shipped = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    assert config_error(shipped, SCHEMA_PATH) is None
    check_config(shipped, SCHEMA)


def test_the_small_configuration_is_valid(config):
    assert config_error(config, SCHEMA) is None


# --- scenes -----------------------------------------------------------------------------------


def test_fig3_scene_merges_the_model_the_case_and_n_cycles(config):
    assert fig3_scene(config, "b") == {
        "F": 0.5, "K": 1.0, "M": 1.0, "a1": -0.1, "a2": 0.05, "amplitude": "amplitude_h0", "b": 0.2, "n_cycles": 50,
        "x0": 3.0,
    }
    assert list(fig3_scene(config, "a")) == ["F", "K", "M", "a1", "a2", "amplitude", "b", "n_cycles", "x0"]  # sorted
    assert fig3_scene(config, "a")["b"] == 0.1


def test_fig4_scene(config):
    assert fig4_scene(config) == {
        **MODEL, "F": 0.5, "x0": 3.0, "velocity_window": [80.0, 87.0], "acceleration_window": [81.0, 85.0],
        "samples_per_second": 1000,
    }


def test_fig5_labels_and_one_scene_per_spring_constant(config):
    assert fig5_labels(config) == ["0.1", "1", "10"]
    assert fig5_scene(config, "10") == {
        **MODEL, "K": 10.0, "F": 0.5, "x0": 1.0, "n_cycles": 60, "samples_per_period": 400,
    }
    assert fig5_scene(config, "0.1")["K"] == 0.1


def test_fig5_force_and_release_may_be_given_per_panel(config):
    config["fig5"].update(F=[1.0, 0.5, 0.25], x0=[-1.0, -1.0, 3.0])
    assert config_error(config, SCHEMA) is None
    assert [(fig5_scene(config, k)["F"], fig5_scene(config, k)["x0"]) for k in ("0.1", "1", "10")] == [
        (1.0, -1.0), (0.5, -1.0), (0.25, 3.0)]


@pytest.mark.parametrize("key", ["F", "x0"])
def test_a_per_panel_list_of_the_wrong_length_is_named(config, key):
    config["fig5"][key] = [0.5, 0.5]
    assert config_error(config, SCHEMA) == (
        f"fig5.{key} = [0.5, 0.5] is invalid: {key} must be one number, or a list of 3 numbers, one per spring "
        "constant of fig5.K = [0.1, 1.0, 10.0]")


def test_the_amplitudes_the_schema_allows_are_those_the_readings_define():
    from escapement.studies.readings import AMPLITUDES

    assert SCHEMA["properties"]["fig3"]["properties"]["amplitude"]["enum"] == list(AMPLITUDES)


def test_an_unknown_amplitude_is_refused_naming_the_choices(config):
    config["fig3"]["amplitude"] = "peak"
    assert config_error(config, SCHEMA) == (
        "fig3.amplitude = 'peak' is invalid: amplitude must be one of amplitude_h0, amplitude_h4, largest_displacement, largest_abs_displacement")


def test_the_escapement_error_forces_are_spaced_geometrically(config):
    from escapement.pipeline.config import escapement_error_forces

    assert escapement_error_forces(config) == pytest.approx([0.1, 0.2, 0.4], rel=1e-15)


def test_check_cases_in_order_with_their_groups_and_labels(config):
    cases = check_cases(config)
    assert [(c["group"], c["label"]) for c in cases] == [
        ("paper", "fig3a"),
        ("paper", "fig3b"),
        ("initial_condition", "F=0.5,x0=2"),
        ("b", "b=0.3"),
        ("symmetric", "F=0.2,a1=-0.3,a2=0.2"),
        ("asymmetric", "F=3,a1=-0.1,a2=0.05,a3=0.2,a4=-0.02"),
        # every K of Fig. 5 at the figure's one force (0.5 N), from its release
        ("common_force", "K=0.1,F=0.5"),
        ("common_force", "K=1,F=0.5"),
        ("common_force", "K=10,F=0.5"),
    ]
    assert cases[7] == {**MODEL, "K": 1.0, "F": 0.5, "x0": 1.0, "group": "common_force", "label": "K=1,F=0.5"}
    assert cases[1] == {**MODEL, "F": 0.5, "x0": 3.0, "b": 0.2, "group": "paper", "label": "fig3b"}
    assert cases[2] == {**MODEL, "F": 0.5, "x0": 2.0, "group": "initial_condition", "label": "F=0.5,x0=2"}
    assert cases[3] == {**MODEL, "F": 1.0, "x0": 1.0, "b": 0.3, "group": "b", "label": "b=0.3"}
    assert cases[5] == {
        **MODEL, "F": 3.0, "x0": 1.0, "a1": -0.1, "a2": 0.05, "a3": 0.2, "a4": -0.02, "group": "asymmetric",
        "label": "F=3,a1=-0.1,a2=0.05,a3=0.2,a4=-0.02",
    }
    assert all("n_cycles" not in c for c in cases)


def test_benchmark_scene_and_settings(config):
    assert benchmark_scene(config) == {**MODEL, "F": 1.0, "x0": 1.0, "n_cycles": 50, "min_seconds": 0.2,
                                       "max_repeats": 500}
    assert benchmark_settings(config) == {"RK45": [1.0e-3, 1.0e-6], "exact": [], "naive-RK4": [0.1]}
    assert benchmark_settings(config, slow=True) == {
        "RK45": [1.0e-3, 1.0e-6], "Radau": [1.0e-9], "exact": [], "naive-RK4": [0.1, 1.0e-4],
    }


def test_long_run_scene(config):
    """The long run names Fig. 3's case (b): its force, release and override of b, with the run's own keys."""
    assert long_run_scene(config) == {
        **MODEL, "F": 0.5, "x0": 3.0, "b": 0.2, "n_cycles": 1000, "ivp_method": "DOP853", "ivp_rtol": 1.0e-12,
        "ivp_cycles": 100,
    }


@pytest.mark.parametrize("block", ["benchmark", "long_run"])
def test_a_scene_that_names_a_case_fig3_lacks_is_refused(config, block):
    config[block]["case"] = "c"
    message = (rf"^invalid configuration: {block}\.case = 'c' is invalid: case must be a case of fig3\.cases, "
               r"one of a, b$")
    with pytest.raises(ConfigError, match=message):
        check_config(config, SCHEMA)


def test_stability_axes_chunks_and_model(config):
    b_values, f_values = stability_axes(config)
    assert b_values == pytest.approx([0.25, 0.75, 1.25, 1.75])
    assert f_values == pytest.approx([1.0, 1.5, 2.0])
    assert stability_chunks(config) == ["0", "1", "2"]
    assert stability_chunk(config, "0")[0] == pytest.approx([0.25, 0.75])
    assert stability_chunk(config, "1")[0] == pytest.approx([1.25, 1.75])
    assert stability_chunk(config, "2") == ([], f_values)
    assert stability_model(config) == {**MODEL, "F": 0.0}


def test_reordering_the_configuration_does_not_change_a_scene(config):
    reordered = copy.deepcopy(config)
    reordered["fig4"] = dict(reversed(list(config["fig4"].items())))
    reordered["model"] = dict(reversed(list(config["model"].items())))
    assert list(fig4_scene(reordered).items()) == list(fig4_scene(config).items())


# --- one-line messages ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "edit, message",
    [
        (lambda c: c["model"].update(M=0.0), "model.M = 0.0 is invalid: M must be a number > 0 (kg)"),
        (lambda c: c["model"].update(K=-1.0), "model.K = -1.0 is invalid: K must be a number > 0 (N/m)"),
        (lambda c: c["model"].update(K="stiff"), "model.K = 'stiff' is invalid: K must be a number > 0 (N/m)"),
        (lambda c: c["model"].update(b=2.0),
         "model.b = 2.0 is invalid: b must be a number in the open interval (0, 2)"),
        (lambda c: c["fig4"].update(F=-1.0), "fig4.F = -1.0 is invalid: F must be a number >= 0 (N)"),
        (lambda c: c["fig3"]["cases"]["a"].update(M=0), "fig3.cases.a.M = 0 is invalid: M must be a number > 0 (kg)"),
        (lambda c: c["fig5"].update(K=[1.0, -2.0]),
         "fig5.K.1 = -2.0 is invalid: each item of K must be a number > 0 (N/m)"),
        (lambda c: c["model"].update(a1="left"), "model.a1 = 'left' is invalid: a1 must be a number (m)"),
        (lambda c: c["fig3"].update(n_cycles=2.5),
         "fig3.n_cycles = 2.5 is invalid: n_cycles must be an integer in [1, 1000000]"),
        (lambda c: c["model"].pop("K"), "model.K is missing: K must be given, as a number > 0 (N/m)"),
        (lambda c: c.update(extra=1),
         "extra = 1 is invalid: extra is not a key of the configuration, whose keys must be among"),
        (lambda c: c["model"].update(x0=1.0),
         "model.x0 = 1.0 is invalid: x0 is not a key of model, whose keys must be among F, K, M, a1, a2, a3, a4, b"),
        (lambda c: c["fig4"].update(colour="red"), "fig4.colour = 'red' is invalid: colour is not a key of fig4"),
        (lambda c: c["fig4"].update(velocity_window=[80.0]), "fig4.velocity_window = [80.0] is invalid"),
        # rules that the schema cannot state
        (
            lambda c: c["fig4"].update(velocity_window=[87.0, 80.0]),
            "fig4.velocity_window = [87.0, 80.0] is invalid: velocity_window must be [start, end] with start < end (s)",
        ),
        (
            lambda c: c["stability_map"].update(chunks=5),
            "stability_map.chunks = 5 is invalid: chunks must be <= b.n = 4",
        ),
        # every scene's parameters, by the model's own rules
        (lambda c: c["model"].update(a2=-0.2), "fig3.cases.a: a2 = -0.2 is invalid: a2 must be > a1 = -0.1 (m)"),
        (lambda c: c["model"].update(a4=0.2), "a4 = 0.2 is invalid: a4 must be < a3 = 0.1 (m)"),
        (
            lambda c: c["fig3"]["cases"]["b"].update(x0=float("nan")),
            "fig3.cases.b: x0 = nan is invalid: x0 must be finite",
        ),
        (lambda c: c["model"].update(K=float("inf")), "K = inf is invalid: K must be finite"),
        (
            lambda c: c["checks"]["asymmetric"].update(positions=[[-0.1, 0.05, 0.2, 0.3]]),
            "checks (F=3,a1=-0.1,a2=0.05,a3=0.2,a4=0.3): a4 = 0.3 is invalid: a4 must be < a3 = 0.2 (m)",
        ),
        (lambda c: c["fig3"].update(n_cycles=10**7), "fig3.n_cycles = 10000000 is invalid"),
        (lambda c: c["checks"].update(n_cycles=10**6), "checks.n_cycles = 1000000 is invalid"),
        (
            lambda c: c["fig4"].update(samples_per_second=100000, velocity_window=[0.0, 1000.0]),
            "fig4.samples_per_second = 100000 is invalid: over the velocity_window of 1000 s it gives 1e+08 samples",
        ),
        (
            lambda c: c["fig5"].update(n_cycles=10000, samples_per_period=2000),
            "fig5.samples_per_period = 2000 is invalid: with n_cycles = 10000 it gives 20_000_000 samples",
        ),
        (
            lambda c: c["model"].update(M=1e-320),
            "fig3.cases.a: M = 1e-320 is invalid: M must be in [1e-50, 1e+50] (kg)",
        ),
    ],
)
def test_each_problem_is_one_line_naming_the_key_its_value_and_the_rule(config, edit, message):
    edit(config)
    problem = config_error(config, SCHEMA)
    assert problem is not None and message in problem, problem
    assert "\n" not in problem
    with pytest.raises(ConfigError, match="^invalid configuration: ") as raised:
        check_config(config, SCHEMA)
    assert message in str(raised.value)


def test_fig5_spring_constants_with_one_file_label_are_refused(config):
    """1.0 and 1.0000001 both print as ``1``: two panels would write K_1.nc."""
    config["fig5"]["K"] = [1.0, 1.0000001, 10.0]
    problem = config_error(config, SCHEMA)
    assert problem == (
        "fig5.K = [1.0, 1.0000001, 10.0] is invalid: K must be spring constants that differ in their file labels "
        "(1.0 and 1.0000001 would both write K_1.nc)"
    )


# --- the schema agrees with the quantities table and with Parameters ----------------------------

#: the bounds the model states (Parameters): by hand, to compare both the schema and Parameters with
BOUNDS = {
    "M": {"exclusiveMinimum": 0},
    "K": {"exclusiveMinimum": 0},
    "F": {"minimum": 0},
    "b": {"exclusiveMinimum": 0, "exclusiveMaximum": 2},
    "a1": {},
    "a2": {},
    "a3": {},
    "a4": {},
}
BOUND_KEYS = {"minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"}


def _resolve(schema: dict) -> dict:
    while "$ref" in schema:
        target = SCHEMA
        for part in schema["$ref"][2:].split("/"):
            target = target[part]
        schema = target
    return schema


def test_the_schema_has_one_property_per_parameter_named_as_in_the_table():
    assert list(SCHEMA["$defs"]["model"]["properties"]) == list(PARAMETERS)
    assert set(BOUNDS) == set(PARAMETERS)


@pytest.mark.parametrize("name", list(PARAMETERS))
def test_a_parameter_in_the_schema_has_the_tables_long_name_units_and_the_models_bounds(name):
    prop = SCHEMA["$defs"]["model"]["properties"][name]
    quantity = PARAMETERS[name]
    assert prop["title"] == quantity.long_name
    assert prop["type"] == "number"
    if quantity.unit_label != "1":
        assert prop["description"].endswith(f"({quantity.unit_label})")
    assert {k: v for k, v in prop.items() if k in BOUND_KEYS} == BOUNDS[name]


def test_the_initial_displacement_in_the_schema_agrees_with_the_table():
    prop = SCHEMA["$defs"]["x0"]
    assert prop["title"] == INITIAL_STATE["x0"].long_name
    assert prop["description"].endswith(f"({INITIAL_STATE['x0'].unit_label})")


@pytest.mark.parametrize(
    "name, outside, inside",
    [("M", 0.0, 1e-3), ("K", 0.0, 1e-3), ("F", -1e-3, 0.0), ("b", 0.0, 1e-3), ("b", 2.0, 1.999)],
)
def test_parameters_enforce_the_same_bounds(name, outside, inside):
    base = {"M": 1.0, "K": 1.0, "F": 0.5, "b": 0.1, "a1": -0.1, "a2": 0.05}
    with pytest.raises(ValueError):
        Parameters(**{**base, name: outside})
    assert getattr(Parameters(**{**base, name: inside}), name) == inside


SCENE_BLOCKS = {
    "fig3.cases": SCHEMA["properties"]["fig3"]["properties"]["cases"]["additionalProperties"],
    "fig4": SCHEMA["properties"]["fig4"],
    "fig5": SCHEMA["properties"]["fig5"],
}


@pytest.mark.parametrize("where", list(SCENE_BLOCKS))
def test_every_scene_override_refers_to_the_one_model_block(where):
    """No copy of a parameter's rules: a scene's model keys point into $defs/model."""
    node = SCENE_BLOCKS[where]
    model = SCHEMA["$defs"]["model"]["properties"]
    for name in PARAMETERS:
        own = node.get("properties", {}).get(name)
        if own is None:
            assert node["$ref"] == "#/$defs/model"
        elif where == "fig5" and name == "K":  # a list of spring constants, one panel each
            assert _resolve(own["items"]) is model["K"]
        elif where == "fig5" and name == "F":  # one force, or one per panel
            assert [_resolve(o if "$ref" in o else o["items"]) for o in own["anyOf"]] == [model["F"]] * 2
        else:
            assert _resolve(own) is model[name]


@pytest.mark.parametrize(
    "text, where, words",
    [
        ("model:\n  M: 1.0\n  K: [1.0, 2.0\n", "line 4, column 1", ["expected ',' or ']'", "starts on line 3"]),
        ("model:\n  M: 1.0\n\tK: 2.0\n", "line 3, column 1", ["'\\t' that cannot start any token"]),
        ("model:\n  M: 1.0\n  K: 1.0\n  M: 2.0\n", "line 4, column 3",
         ["the key 'M' is given twice (first on line 2)"]),
        ("fig3:\n  n_cycles: 5\nfig3:\n  n_cycles: 6\n", "line 3, column 1", ["the key 'fig3' is given twice"]),
    ],
)
def test_a_configuration_file_that_is_not_yaml_is_named_with_its_line(tmp_path, text, where, words):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as caught:
        check_config_file(path)
    message = str(caught.value)
    assert message.startswith(f"{path}, {where}: not valid YAML: ")
    for word in words:
        assert word in message


def test_the_shipped_configuration_file_reads_as_strict_yaml():
    check_config_file(ROOT / "config/config.yaml")


def test_a_missing_configuration_file_is_named(tmp_path):
    with pytest.raises(ConfigError, match="missing.yaml: cannot read the configuration"):
        check_config_file(tmp_path / "missing.yaml")
