"""The runs that hold all but one parameter fixed (pipeline.config.check_cases: the configuration's checks
and fig5 blocks expanded) and the checks dataset's added columns, by value."""

from __future__ import annotations

import math

import pytest

from escapement.experiments.checks import measure_cases
from escapement.io.scenes import checks_dataset
from escapement.pipeline.config import check_cases

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
FIG5 = {"K": [0.1, 1.0, 10.0], "F": [1.0, 0.5, 0.5], "x0": -1.0, "n_cycles": 60}
CHECKS = {"releases": {"F": 1.0, "x0": [-3.0, 1.0]}, "forces": {"F": [0.2, 5.0], "x0": -1.0}}


def test_every_k_of_fig5_at_every_force_of_the_figure_then_releases_then_forces():
    config = {"model": MODEL, "fig3": {"cases": {}}, "fig5": FIG5,
              "checks": {"F": 1.0, "x0": 1.0, "initial_conditions": [], "b": [],
                         "symmetric": {"F": [], "positions": []}, "asymmetric": {"F": [], "positions": []}, **CHECKS}}
    cases = check_cases(config)
    labels = [c["label"] for c in cases]
    assert labels == ["K=0.1,F=0.5", "K=1,F=0.5", "K=10,F=0.5", "K=0.1,F=1", "K=1,F=1", "K=10,F=1",
                      "F=1,x0=-3", "F=1,x0=1", "F=0.2,x0=-1", "F=5,x0=-1"]
    assert [c["group"] for c in cases] == ["common_force"] * 6 + ["release"] * 2 + ["force"] * 2
    assert cases[2] == {"K": 10.0, "F": 0.5, "x0": -1.0, "M": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05,
                        "group": "common_force", "label": "K=10,F=0.5"}
    per_panel = check_cases({**config, "fig5": {**FIG5, "x0": [-1.0, -2.0, -3.0]}})
    assert [c["x0"] for c in per_panel[:3]] == [-1.0, -2.0, -3.0]
    without = {k: v for k, v in config["checks"].items() if k not in ("releases", "forces")}
    assert len(check_cases({**config, "checks": without})) == 6  # releases and forces are optional


def test_the_added_columns_by_value():
    case = {"group": "force", "label": "l", **MODEL, "F": 1.0, "x0": -1.0}
    ds = checks_dataset(measure_cases([case], 200), 200)
    # the limit cycle of the paper's case: the largest speed is at a2, v2^2 = 0.81 * 0.3/0.19 + 0.3075 (hand
    # derivation in tests/paper/test_floquet_and_speed.py); the multipliers 1 and (1 - b)^4 = 0.6561
    assert float(ds["largest_speed"][0]) == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)
    assert float(ds["floquet_major"][0]) == pytest.approx(1.0, abs=1e-8)
    assert float(ds["floquet_minor"][0]) == pytest.approx(0.6561, abs=1e-8)
    assert ds["first_period"].attrs["units"] == "s" and float(ds["first_period"][0]) != float(ds["period"][0])
