"""A study of the user's own: its blocks laid over the paper's key by key at every level (as Snakemake merges
configurations), a kind run only where what the user changed reaches its scenes, one line for each kind it does
not reach, and the changes carried from the settings through the dataset.

The kinds that must not run are taken from what each kind's scene computes, checked here on the scenes
themselves: the escapement error's zones set a1..a4, the stability map's axes are b and F, the existence map's a3
and F (and whether a release settles does not depend on the mass, which sets only the time scale), Fig. 4's block
sets its own K and Fig. 5 a K per panel (config/paper.yaml)."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
from snakemake.utils import update_config

from escapement.io.netcdf import read_netcdf, write_netcdf
from escapement.pipeline.config import (
    ConfigError,
    laid_over,
    own_blocks,
    read_yaml,
    study_notes,
    study_scenes,
    validated,
)
from escapement.scenes.figures import poincare_map
from escapement.scenes.maps import escapement_error, existence_map, stability_map

REPO = Path(__file__).resolve().parents[2]
PAPER = read_yaml(REPO / "config" / "paper.yaml")
ALL = {"fig3", "fig4", "fig5", "escapement_error", "stability_map", "existence_map"}
ASYMMETRIC = {"name": "asym", "model": {"a3": 0.12, "a4": -0.03}}


def kinds(config: dict) -> set[str]:
    return set(own_blocks(config, PAPER)) - {"model"}


@pytest.mark.parametrize("config", [
    {"fig3": {"cases": {"c": {"F": 0.75, "x0": -2.0}}}},
    {"fig3": {"cases": {"a": {"F": 2.0, "x0": -1.0}}, "n_cycles": 80}},
    {"stability_map": {"F": {"n": 50}}, "escapement_error": {"zones": {"before": [-0.3, -0.05]}}},
    {"fig5": {"K": [0.1, 5.0], "F": 0.5}, "model": {"M": 2.0}, "existence_map": {"a3": {"stop": 0.2}}},
])
def test_the_blocks_merge_key_by_key_at_every_level_as_snakemake_merges_configurations(config):
    expected = copy.deepcopy(PAPER)
    update_config(expected, copy.deepcopy(config))  # in place: mappings merged at every level, other values replaced
    blocks = own_blocks(config, PAPER)
    assert blocks["model"] == expected["model"] and kinds(config)
    for block in kinds(config):
        assert {k: v for k, v in blocks[block].items() if k != "changes"} == expected[block]


def test_the_study_laid_over_the_paper_is_what_snakemake_s_merge_gives_and_the_paper_s_bounds_hold_on_it():
    """The paper's schema checks the merged study again: the cases a user adds join the paper's, and their count
    is bounded as the paper's own (the bound read from the schema)."""
    config = {"model": {"b": 0.3}, "fig3": {"cases": {"c": {"F": 0.75, "x0": -2.0}}}}
    expected = copy.deepcopy(PAPER)
    update_config(expected, copy.deepcopy(config))
    assert laid_over(config, PAPER) == expected
    schema = REPO / "workflow" / "schemas" / "paper.schema.yaml"
    validated(laid_over(config, PAPER), schema, "your study 'own'")
    most = read_yaml(REPO / "workflow" / "schemas" / "config.schema.yaml")["$defs"]["fig3"]["properties"]["cases"][
        "maxProperties"]
    many = {"fig3": {"cases": {c: {"F": 1.0, "x0": -1.0} for c in "cdefghijklmnopqrstuvwxyz"[:most - 1]}}}
    with pytest.raises(ConfigError, match=r"^your study 'own': fig3\.cases = .* is invalid: cases must be"):
        validated(laid_over(many, PAPER), schema, "your study 'own'")


def test_a_third_case_joins_the_paper_s_two_and_only_it_is_new():
    blocks = own_blocks({"fig3": {"cases": {"c": {"F": 0.75, "x0": -2.0}}}}, PAPER)
    assert list(blocks["fig3"]["cases"]) == ["a", "b", "c"] and kinds({"fig3": blocks["fig3"]}) == {"fig3"}
    assert blocks["fig3"]["cases"]["a"] == PAPER["fig3"]["cases"]["a"]
    assert blocks["fig3"]["changes"] == "case c added (F = 0.75 N, x0 = -2 m)"
    scenes = study_scenes("own", blocks)["fig3"]
    assert list(scenes) == ["a", "b", "c"] and scenes["c"]["F"] == 0.75 and scenes["b"]["x0"] == -3.0
    axis = own_blocks({"stability_map": {"F": {"n": 50}}}, PAPER)["stability_map"]
    assert axis["F"] == {"start": 0.01, "stop": 2.0, "n": 50} and axis["changes"] == "F.n = 50 (paper: 200)"


def test_the_asymmetric_study_does_not_rerun_the_escapement_error_and_says_why_in_one_line():
    assert kinds(ASYMMETRIC) == ALL - {"escapement_error"}
    assert study_notes(ASYMMETRIC, PAPER) == [
        "your study 'asym': escapement_error does not run: its zones set a1 and a2, and a3 = -a1, a4 = -a2 "
        "(model.a3 = 0.12, model.a4 = -0.03)",
        "your study 'asym': model.a3 = 0.12 does not reach existence_map: a3 is its axis",
    ]
    blocks = own_blocks(ASYMMETRIC, PAPER)
    assert blocks["existence_map"]["changes"] == "a4 = -0.03 m (paper: -0.05 m)"  # a3 is its axis
    assert blocks["fig4"]["changes"] == "a3 = 0.12 m (paper: 0.1 m), a4 = -0.03 m (paper: -0.05 m)"


def test_a3_alone_runs_neither_the_escapement_error_nor_the_existence_map_over_a3():
    config = {"name": "a3", "model": {"a3": 0.12}}
    assert kinds(config) == {"fig3", "fig4", "fig5", "stability_map"}
    notes = study_notes(config, PAPER)
    assert [line.split(": ")[1] for line in notes] == ["escapement_error does not run", "existence_map does not run"]
    assert notes[1] == "your study 'a3': existence_map does not run: a3 is its axis (model.a3 = 0.12)"


def test_the_impact_coefficient_does_not_rerun_the_map_over_b():
    config = {"name": "b", "model": {"b": 0.3}}
    assert kinds(config) == ALL - {"stability_map"}
    assert study_notes(config, PAPER) == ["your study 'b': stability_map does not run: b is its axis (model.b = 0.3)"]
    assert all(own_blocks(config, PAPER)[k]["changes"] == "b = 0.3 (paper: 0.1)" for k in kinds(config))


def test_the_mass_reaches_every_kind_but_the_existence_map():
    config = {"name": "m", "model": {"M": 2.0}}
    assert kinds(config) == ALL - {"existence_map"}
    assert study_notes(config, PAPER) == [
        "your study 'm': existence_map does not run: its outcome does not depend on M (the mass sets only the time "
        "scale, sqrt(M/K)) (model.M = 2)"]


def test_the_model_s_spring_reaches_neither_fig4_nor_fig5_which_set_their_own():
    config = {"name": "k", "model": {"K": 2.0}}
    assert kinds(config) == ALL - {"fig4", "fig5"}
    assert study_notes(config, PAPER) == [
        "your study 'k': fig4 does not run: its block sets its own K (model.K = 2)",
        "your study 'k': fig5 does not run: every panel sets its own K (model.K = 2)"]
    both = {"name": "k", "model": {"K": 2.0, "b": 0.2}}
    assert kinds(both) == ALL and own_blocks(both, PAPER)["fig4"]["changes"] == "b = 0.2 (paper: 0.1)"
    assert "your study 'k': model.K = 2 does not reach fig4: its block sets its own K" in study_notes(both, PAPER)


@pytest.mark.parametrize("config, line", [
    ({"model": {"F": 2.0}}, "your study 'own' does not run: nothing you changed (model.F = 2) reaches a scene (fig3: "
                            "every case sets its own F | fig4: its block sets its own F | fig5: every panel sets its "
                            "own F | escapement_error: F is its axis | stability_map: F is its axis | existence_map: "
                            "F is its axis)"),
    ({"fig5": {"x0": [-1.0, -1.0, -1.0]}}, "your study 'own' does not run: nothing you changed (fig5.x0 = [-1, -1, "
                                           "-1]) reaches a scene: every kind's scenes stay the paper's"),
    ({"fig4": {"K": 0.1}, "model": {"a3": 0.1}},
     "your study 'own' does not run: the blocks you give (model, fig4) hold the paper's values"),
])
def test_when_nothing_the_user_changed_reaches_a_scene_no_study_runs_and_one_line_says_so(config, line):
    assert kinds(config) == set() and study_notes(config, PAPER) == [line]


def test_a_configuration_of_no_blocks_is_no_study_and_says_nothing():
    assert kinds({"name": "own"}) == set() and study_notes({"name": "own"}, PAPER) == []


def test_fig5_s_panels_are_compared_by_their_place():
    blocks = own_blocks({"fig5": {"K": [0.1, 1.0, 5.0]}}, PAPER)
    assert blocks["fig5"]["changes"] == "panel (c): K = 5 N/m (paper: 10 N/m)"
    fewer = own_blocks({"fig5": {"K": [0.1, 1.0], "F": 0.5}}, PAPER)["fig5"]["changes"]
    assert fewer == "panel (a): F = 0.5 N (paper: 1 N); the paper's panel (c) (K = 10 N/m) left out"


#: small grids of each map's kind, the model's keys it ignores changed to other valid values, and its scene
SMALL = {
    "escapement_error": ({"F": {"start": 0.5, "stop": 1.0, "n": 2}, "zones": {"paper": [-0.1, 0.05]}},
                         {"a1": -0.2, "a2": 0.1, "a3": 0.15, "a4": -0.02, "F": 3.0}, escapement_error),
    "stability_map": ({"b": {"start": 0.0, "stop": 2.0, "n": 3}, "F": {"start": 0.5, "stop": 1.0, "n": 2}},
                      {"b": 0.7, "F": 3.0}, lambda s: stability_map(s, speed_sample=1)[0]),
    "existence_map": ({"a3": {"start": 0.0, "stop": 0.2, "n": 2}, "F": {"start": 0.0, "stop": 0.01, "n": 2},
                       "x0": -1.0, "n_cycles": 20, "tolerance": 1e-9}, {"a3": 0.3, "F": 3.0, "M": 2.0}, existence_map),
}
#: another valid value of each model key, one at a time
OTHER = {"M": 2.0, "K": 2.0, "b": 0.3, "a1": -0.15, "a2": 0.08, "a3": 0.13, "a4": -0.06}


def _data(block: str, model: dict) -> dict:
    """What the scene computed: its dataset's variables but its inputs (the parameters it was given)."""
    settings, _, scene = SMALL[block]
    ds = scene({**model, **settings, "study": "replication"})  # the block's keys win, as the configuration builds
    return {name: ds[name].values for name in ds.variables
            if ds[name].attrs.get("coverage_content_type") != "auxiliaryInformation"}


@pytest.mark.parametrize("block", list(SMALL))
def test_the_keys_a_map_is_said_to_ignore_leave_its_data_as_they_were_and_every_other_key_does_not(block):
    """What the rule rests on, checked on the scenes: the data of a kind do not depend on the model keys it is said
    to ignore (so its study under them would be the paper's data), and depend on every other key of the model."""
    ignored = SMALL[block][1]
    paper = _data(block, PAPER["model"])
    changed = _data(block, {**PAPER["model"], **ignored})
    assert paper.keys() == changed.keys()
    for name in paper:
        np.testing.assert_array_equal(changed[name], paper[name], err_msg=name)
    for key in sorted(set(OTHER) - set(ignored)):
        other = _data(block, {**PAPER["model"], key: OTHER[key]})
        assert any(not np.array_equal(other[n], paper[n], equal_nan=True) for n in paper), key
    assert block not in own_blocks({"model": {k: v for k, v in ignored.items()}}, PAPER)


def test_the_dataset_of_a_study_scene_names_its_changes_and_the_replication_s_none(tmp_path):
    scenes = study_scenes("asym", own_blocks({**ASYMMETRIC, "fig3": {"n_cycles": 5}}, PAPER))
    expected = "a3 = 0.12 m (paper: 0.1 m), a4 = -0.03 m (paper: -0.05 m), n_cycles = 5 (paper: 50)"
    assert scenes["fig3"]["a"]["changes"] == expected
    path = write_netcdf(poincare_map(scenes["fig3"]["a"]), tmp_path / "case_a.nc")
    ds = read_netcdf(path)
    assert ds.attrs["study_changes"] == expected and ds.attrs["study"] == "asym"
    assert all(isinstance(value, str) for key, value in ds.attrs.items() if key.startswith("study"))
    assert float(ds["a3"]) == 0.12 and float(ds["a4"]) == -0.03  # what it names is what ran
    replication = study_scenes("replication", PAPER)["fig3"]["a"]
    assert "changes" not in replication
    assert "study_changes" not in poincare_map({**replication, "n_cycles": 2}).attrs
