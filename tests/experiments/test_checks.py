"""The runs of the claims register: one measured value per case in each column."""

import numpy as np
import pytest

from escapement.experiments.checks import measure_cases
from escapement.model.parameters import ParameterError, Parameters
from escapement.model.quantities import MODEL_KEYS
from escapement.paper.poincare import measure_cycle
from escapement.paper.printed import multiplier_21

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}


def test_every_column_has_one_value_per_case_and_the_measurement_of_its_run():
    cases = [{"group": "paper", "label": "a", **MODEL, "F": 1.0, "x0": 1.0},
             {"group": "b", "label": "b=0.5", **MODEL, "b": 0.5, "F": 0.5, "x0": 3.0}]
    columns = measure_cases(cases, 20)
    assert all(len(values) == 2 for values in columns.values())
    assert columns["label"] == ["a", "b=0.5"] and columns["group"] == ["paper", "b"]
    assert set(MODEL_KEYS) <= set(columns) and columns["a3"] == [0.1, 0.1]  # the symmetric default
    p = Parameters(**{**MODEL, "F": 0.5, "b": 0.5})
    m = measure_cycle(p, 3.0, 20)
    assert columns["multiplier"][1] == m.multiplier and columns["velocity"][1] == m.velocity
    assert columns["multiplier_eq21"][1] == multiplier_21(p)
    assert columns["cycles_to_converge"].dtype == np.int32


def test_a_bad_case_or_count_is_refused_before_any_run():
    with pytest.raises(ParameterError, match="^n_cycles = "):
        measure_cases([], 0)
    with pytest.raises(ParameterError, match="F"):
        measure_cases([{"group": "g", "label": "l", **MODEL, "x0": 1.0}], 5)
