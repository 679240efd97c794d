"""The replication's own runs: the claims register's (one row per case, its columns by value against hand
derivations) and the long run's settings."""

from __future__ import annotations

import math

import numpy as np
import pytest

from escapement.model.parameters import ParameterError
from escapement.model.quantities import MODEL_KEYS
from escapement.scenes.runs import checks, long_run

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}


def test_one_row_per_case_with_the_limit_cycle_measured_by_value():
    cases = [{"group": "force", "label": "a", **MODEL, "F": 1.0, "x0": -1.0},
             {"group": "b", "label": "b=0.5", **MODEL, "b": 0.5, "F": 0.5, "x0": 3.0}]
    ds = checks(cases, 200)
    assert ds.sizes["case"] == 2 and ds["label"].values.tolist() == ["a", "b=0.5"]
    assert set(MODEL_KEYS) <= set(ds.variables) and ds["a3"].values.tolist() == [0.1, 0.1]  # symmetric default
    # the limit cycle of the paper's case: the largest speed is at a2, v2^2 = 0.81 * 0.3/0.19 + 0.3075 (hand
    # derivation in tests/paper/test_floquet_and_speed.py); the multipliers 1 and (1 - b)^4 = 0.6561
    assert float(ds["largest_speed"][0]) == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)
    assert float(ds["floquet_major"][0]) == pytest.approx(1.0, abs=1e-8)
    assert float(ds["floquet_minor"][0]) == pytest.approx(0.6561, abs=1e-8)
    assert float(ds["multiplier"][1]) == pytest.approx(0.5**4, abs=1e-8)
    assert ds["cycles_to_converge"].dtype == np.int32 and ds["first_period"].attrs["units"] == "s"


def test_a_bad_case_or_count_is_refused_before_any_run():
    with pytest.raises(ParameterError, match="^n_cycles = "):
        checks([], 0)
    with pytest.raises(ParameterError, match="^F = "):
        checks([{"group": "g", "label": "l", **MODEL, "x0": 1.0}], 5)


@pytest.mark.parametrize("name, value", [("n_cycles", 0), ("ivp_cycles", 1.5)])
def test_the_long_run_refuses_a_count_that_is_not_a_positive_integer(name, value):
    settings = {**MODEL, "F": 1.0, "x0": -1.0, "n_cycles": 2000, "ivp_method": "DOP853", "ivp_rtol": 1e-12,
                "ivp_cycles": 10, name: value}
    with pytest.raises(ParameterError, match=f"^{name} = "):
        long_run(settings)
