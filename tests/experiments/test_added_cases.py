"""The runs that hold all but one parameter fixed (experiments.checks.added_cases) and the checks dataset's
added columns, by value."""

from __future__ import annotations

import math

import pytest

from escapement.experiments.checks import added_cases, measure_cases
from escapement.io.scenes import checks_dataset

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
FIG5 = {"K": [0.1, 1.0, 10.0], "F": [1.0, 0.5, 0.5], "x0": -1.0, "n_cycles": 60}
CHECKS = {"releases": {"F": 1.0, "x0": [-3.0, 1.0]}, "forces": {"F": [0.2, 5.0], "x0": -1.0}}


def test_every_k_of_fig5_at_every_force_of_the_figure_then_releases_then_forces():
    cases = added_cases(MODEL, CHECKS, FIG5)
    labels = [c["label"] for c in cases]
    assert labels == ["K=0.1,F=0.5", "K=1,F=0.5", "K=10,F=0.5", "K=0.1,F=1", "K=1,F=1", "K=10,F=1",
                      "F=1,x0=-3", "F=1,x0=1", "F=0.2,x0=-1", "F=5,x0=-1"]
    assert [c["group"] for c in cases] == ["common_force"] * 6 + ["release"] * 2 + ["force"] * 2
    assert cases[2] == {"K": 10.0, "F": 0.5, "x0": -1.0, "M": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05,
                        "group": "common_force", "label": "K=10,F=0.5"}
    assert list(cases[2]) == sorted(cases[2])
    assert len(added_cases(MODEL, {}, FIG5)) == 6  # releases and forces are optional


def test_per_panel_releases_and_bad_blocks_are_refused_by_name():
    per_panel = added_cases(MODEL, {}, {**FIG5, "x0": [-1.0, -2.0, -3.0]})
    assert [c["x0"] for c in per_panel[:3]] == [-1.0, -2.0, -3.0]
    with pytest.raises(ValueError, match=r"fig5.F = \[1.0, 0.5\] must be one number or one per K \(3\)"):
        added_cases(MODEL, {}, {**FIG5, "F": [1.0, 0.5]})
    with pytest.raises(ValueError, match="checks.forces.F = 'x' must be a number"):
        added_cases(MODEL, {"forces": {"F": "x", "x0": 1.0}}, FIG5)
    with pytest.raises(ValueError, match="checks.releases = .* must give x0"):
        added_cases(MODEL, {"releases": {"F": 1.0}}, FIG5)
    with pytest.raises(ValueError, match="checks.releases.F = \\[1.0, 2.0\\] must be one number"):
        added_cases(MODEL, {"releases": {"F": [1.0, 2.0], "x0": [1.0]}}, FIG5)


def test_the_added_columns_by_value():
    case = {"group": "force", "label": "l", **MODEL, "F": 1.0, "x0": -1.0}
    ds = checks_dataset(measure_cases([case], 200), 200)
    # the limit cycle of the paper's case: the largest speed is at a2, v2^2 = 0.81 * 0.3/0.19 + 0.3075 (hand
    # derivation in tests/paper/test_floquet_and_speed.py); the multipliers 1 and (1 - b)^4 = 0.6561
    assert float(ds["largest_speed"][0]) == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)
    assert float(ds["floquet_major"][0]) == pytest.approx(1.0, abs=1e-8)
    assert float(ds["floquet_minor"][0]) == pytest.approx(0.6561, abs=1e-8)
    assert ds["first_period"].attrs["units"] == "s" and float(ds["first_period"][0]) != float(ds["period"][0])
