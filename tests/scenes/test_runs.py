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


def test_the_runs_behind_single_claims_by_value():
    """The paper's case (a) (w = 1): from rest at -1 m the first impact at a1 comes at sqrt(1 - a1^2); the return
    map's slope is Eq. (20), 0.6561 x / sqrt(0.6561 x^2 + 0.543 F); the runs from the section at the converged
    speed and 1 % above it agree in speed after 100 cycles and keep their impact times -0.000848 s apart (the
    referee's simulator, in 40-digit arithmetic, finds -0.000848 s)."""
    case = {**MODEL, "a3": 0.1, "a4": -0.05, "F": 1.0, "x0": -1.0, "label": "a"}
    ds = checks([], 1, {"first_swings": [case, {**case, "x0": -3.0}],
                        "return_map": {**case, "velocities": [0.5, 2.0]},
                        "phase_shift": {**case, "n_release": 50, "perturbation": 0.01, "n_cycles": 100}})
    assert ds["first_swing_velocity"].values == pytest.approx([math.sqrt(0.99), math.sqrt(8.99)], rel=1e-12)
    slope = [0.6561 * v / math.sqrt(0.6561 * v * v + 0.543) for v in (0.5, 2.0)]
    assert ds["map_slope"].values == pytest.approx(slope, rel=1e-9) and ds["map_slope"].attrs["case"] == "a"
    times = ds["perturbed_impact_time"].values
    assert ds["perturbation"].values.tolist() == [0.0, 0.01] and np.isfinite(times).all()
    assert times[1, -1] - times[0, -1] == pytest.approx(-0.000848, abs=5e-7)
    speeds = ds["perturbed_speed"].values
    assert abs(speeds[1] - speeds[0]) <= 1e-8 * speeds[0]
    assert ds["perturbed_speed"].attrs["converged_speed"] == pytest.approx(math.sqrt(0.3 / 0.19), rel=1e-8)
