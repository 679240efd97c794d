"""A study of the user's own: the merged configuration (the paper's file, the user's blocks laid over it by
Snakemake's merge), a kind run only where what the user changed reaches its scenes, the changed keys said once as
dotted keys with the paper's values, one line for each kind they do not reach, and the changes carried from the
settings through the dataset.

The kinds that must not run are taken from what each kind's scene computes, checked here on the scenes
themselves: the escapement error's zones set a1..a4, the stability map's axes are b and F, the existence map's a3
and F (and whether a release settles does not depend on the mass, which sets only the time scale), Fig. 4's block
sets its own K and Fig. 5 a K per panel (config/paper.yaml)."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml
from snakemake.utils import update_config

from escapement.io.netcdf import read_netcdf, write_netcdf
from escapement.pipeline.plan import plan
from escapement.scenes.figures import poincare_map
from escapement.scenes.maps import escapement_error, existence_map, stability_map

REPO = Path(__file__).resolve().parents[2]
PAPER = yaml.safe_load((REPO / "config" / "paper.yaml").read_text())
ALL = {"fig3", "fig4", "fig5", "escapement_error", "stability_map", "existence_map"}


def planned(user: dict) -> tuple[dict, list[str]]:
    """The studies and the planning's lines for the user's blocks laid over the paper's file."""
    config = copy.deepcopy(PAPER)
    update_config(config, copy.deepcopy(user))
    return plan(config, PAPER)


def kinds(user: dict) -> set[str]:
    studies, _ = planned(user)
    return set(studies.get(user.get("name", "own"), {}))


@pytest.mark.parametrize("user, runs", [
    ({"model": {"b": 0.3}}, ALL - {"stability_map"}),
    ({"model": {"a3": 0.12, "a4": -0.03}}, ALL - {"escapement_error"}),
    ({"model": {"a3": 0.12}}, {"fig3", "fig4", "fig5", "stability_map"}),  # the existence map's axis is a3
    ({"model": {"M": 2.0}}, ALL - {"existence_map"}),
    ({"model": {"K": 2.0}}, ALL - {"fig4", "fig5"}),
    ({"model": {"K": 2.0, "b": 0.2}}, ALL),
    ({"model": {"F": 2.0}}, set()),
    ({"fig5": {"x0": [-1.0, -1.0, -1.0]}}, set()),  # the paper's panels, written out
    ({"fig4": {"K": 0.1}, "model": {"a3": 0.1}}, set()),  # the paper's values
    ({"stability_map": {"F": {"n": 50}}, "existence_map": {"a3": {"n": 20}}}, {"stability_map", "existence_map"}),
    ({"fig3": {"cases": {"c": {"F": 0.75, "x0": -2.0}}}}, {"fig3"}),
])
def test_a_kind_runs_as_the_user_s_study_exactly_where_the_changes_reach_its_scenes(user, runs):
    assert kinds(user) == runs


def test_the_changes_are_said_once_as_dotted_keys_and_each_kind_they_do_not_reach_in_one_line():
    _, notes = planned({"name": "asym", "model": {"a3": 0.12, "a4": -0.03}})
    assert notes == ["your study 'asym' changes model.a3 = 0.12 m (paper: 0.1 m); model.a4 = -0.03 m (paper: -0.05 m)",
                     "your study 'asym': escapement_error does not run: its zones set a1 and a2, and a3 = -a1, "
                     "a4 = -a2"]
    assert planned({"model": {"K": 2.0}})[1][1:] == ["your study 'own': fig4 does not run: its scenes set their own K",
                                                     "your study 'own': fig5 does not run: its scenes set their own K"]
    _, notes = planned({"model": {"F": 2.0}})
    assert notes[0] == "your study 'own' does not run: nothing you changed (model.F = 2 N (paper: absent)) reaches a " \
                       "scene" and "your study 'own': stability_map does not run: F is its axis" in notes
    assert planned({"name": "own"}) == (planned({})[0], [])


def test_a_third_case_joins_the_paper_s_two_and_every_scene_of_a_study_carries_what_reaches_its_kind():
    studies, _ = planned({"fig3": {"cases": {"c": {"F": 0.75, "x0": -2.0}}}, "stability_map": {"F": {"n": 50}}})
    cases = {label: planned.settings for label, planned in studies["own"]["fig3"].items()}
    assert list(cases) == ["a", "b", "c"] and cases["c"]["F"] == 0.75 and cases["b"]["x0"] == -3.0
    assert studies["own"]["fig3"]["c"].checked.params.F == 0.75  # the settings the job runs, checked
    assert cases["a"]["changes"] == "fig3.cases.c.F = 0.75 N (paper: absent); fig3.cases.c.x0 = -2 m (paper: absent)"
    axis = studies["own"]["stability_map"][""].settings
    assert axis["F"] == {"start": 0.01, "stop": 2.0, "n": 50} and axis["changes"] == \
        "stability_map.F.n = 50 (paper: 200)"
    studies, _ = planned({"fig5": {"K": [0.1, 1.0, 5.0]}, "model": {"b": 0.3}})
    assert studies["own"]["fig5"]["5"].settings["changes"] == \
        "model.b = 0.3 (paper: 0.1); fig5.K = [0.1, 1, 5] N/m (paper: [0.1, 1, 10] N/m)"
    assert studies["own"]["escapement_error"][""].settings["changes"] == "model.b = 0.3 (paper: 0.1)"


def test_the_dataset_of_a_study_scene_names_its_changes_and_the_replication_s_none(tmp_path):
    studies, _ = planned({"name": "asym", "model": {"a3": 0.12, "a4": -0.03}, "fig3": {"n_cycles": 5}})
    scene = studies["asym"]["fig3"]["a"].checked
    expected = "model.a3 = 0.12 m (paper: 0.1 m); model.a4 = -0.03 m (paper: -0.05 m); fig3.n_cycles = 5 (paper: 50)"
    assert scene.study.changes == expected
    ds = read_netcdf(write_netcdf(poincare_map(scene), tmp_path / "case_a.nc"))
    assert ds.attrs["study_changes"] == expected and ds.attrs["study"] == "asym"
    assert float(ds["a3"]) == 0.12 and float(ds["a4"]) == -0.03  # what it names is what ran
    replication = studies["replication"]["fig3"]["a"].settings
    assert "changes" not in replication
    assert "study_changes" not in poincare_map({**replication, "n_cycles": 2}).attrs


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
    assert block not in kinds({"model": ignored})
