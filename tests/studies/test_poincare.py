import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.studies.poincare import NoReturn, ensemble_return_map, measure_cycle, return_map, stability_grid

MODEL = dict(M=1.0, K=1.0, a1=-0.1, a2=0.05)


def test_return_map_is_eq16():
    p = Parameters(**MODEL, F=1.0, b=0.1)
    v_in, v_out = return_map(p, 1.1)
    assert v_in == pytest.approx(1.1, rel=1e-14)
    assert v_out == pytest.approx(np.sqrt(0.6561 * v_in**2 + 2 * (0.01 - 0.2 + 2) * 0.15), rel=1e-14)


def test_ensemble_return_map_equals_the_scalar_one():
    b = np.array([0.1, 0.5, 0.9])
    F = np.array([1.0, 0.3, 2.0])
    v_in, v_out, period, status = ensemble_return_map(MODEL, b, F, np.array([1.1, 0.7, 1.5]))
    assert status.tolist() == [Status.COMPLETED.code] * 3
    assert np.all(np.isfinite(period))
    for i in range(3):
        ref = return_map(Parameters(**MODEL, F=F[i], b=b[i]), [1.1, 0.7, 1.5][i])
        assert (v_in[i], v_out[i]) == pytest.approx(ref, rel=1e-14)


def test_grid_multipliers_and_outcomes():
    b = np.array([0.005, 0.1, 0.7, 1.0, 1.3])
    g = stability_grid(MODEL, b, np.full(5, 0.5))
    assert g["multiplier"][:4] == pytest.approx((1 - b[:4]) ** 4, abs=1e-9)
    assert np.isnan(g["multiplier"][4])
    assert g["newton_converged"][:4].all()
    expected = np.sqrt(2 * 0.15 * 0.5 / (2 * b[:4] - b[:4] ** 2))
    assert g["fixed_point"][:4] == pytest.approx(expected, rel=1e-10)


def test_measure_cycle_reports_an_outcome_outside_the_regime():
    m = measure_cycle(Parameters(**MODEL, F=1.0, b=1.5), 1.0)
    assert m.outcome == "chattering" and np.isnan(m.multiplier)


def test_return_map_without_a_return_raises_or_gives_nan():
    # b = 1.5: the first impact at a1 reverses the velocity, so the motion never returns to the section
    p = Parameters(**MODEL, F=1.0, b=1.5)
    with pytest.raises(NoReturn, match="no return to the section from v = 1.1") as err:
        return_map(p, 1.1)
    assert isinstance(err.value, ValueError) and "reversed the velocity" in str(err.value)
    _, v_out = return_map(p, 1.1, strict=False)
    assert math.isnan(v_out)


def test_return_map_keeps_v_in_when_the_first_cycle_does_not_close():
    v_in, _ = return_map(Parameters(**MODEL, F=1.0, b=1.5), 1.1, strict=False)
    assert v_in == pytest.approx(1.1, rel=1e-14)


def test_measure_cycle_of_the_paper_case():
    """Measured against Eqs. (19) and (21), which hold (derived on paper from the energy balance)."""
    p = Parameters(**MODEL, F=1.0, b=0.1)
    m = measure_cycle(p, 1.0)
    assert m.outcome == "completed"
    assert m.velocity == pytest.approx(np.sqrt(2 * 0.15 / (0.2 - 0.01)), rel=1e-12)
    assert m.multiplier == pytest.approx(0.6561, abs=1e-8)
    assert 1 < m.cycles_to_converge < 300
