"""The escapement error: every rate field over zones and forces, and the formula's largest miss."""

import numpy as np

from escapement.experiments.escapement_error import RATE_FIELDS, escapement_error
from escapement.model.parameters import Parameters
from escapement.studies.escapement_error import SECONDS_PER_DAY, limit_cycle_rate


def test_each_field_over_zones_and_forces():
    base = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    zones = {"paper": [-0.1, 0.05], "symmetric": [-0.05, 0.05]}
    result = escapement_error(base, [0.5, 1.0], zones)
    assert result.zones == {"paper": (-0.1, 0.05), "symmetric": (-0.05, 0.05)}
    assert all(result.values[name].shape == (2, 2) for name in RATE_FIELDS)
    one = limit_cycle_rate(Parameters(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.05, a2=0.05, a3=0.05, a4=-0.05))
    assert result.values["rate"][1, 0] == one.rate and result.values["period"][1, 0] == one.period
    period, formula = result.values["period"], result.values["period_formula"]
    assert result.max_period_difference == np.max(np.abs(formula - period) / period)
    assert result.seconds_per_day == SECONDS_PER_DAY and result.model == {"M": 1.0, "K": 1.0, "b": 0.1}
