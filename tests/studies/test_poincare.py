"""The Poincare map measured on the simulated motion (return map, ensemble, grid, largest speed, both Floquet
multipliers) against Eq. (16), hand-derived values and the paper's printed 0.6561."""

import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers.result import ArcTable
from escapement.studies.poincare import (NoReturn, ensemble_return_map, floquet_multipliers, largest_speed,
                                         measure_cycle, return_map, stability_grid)

MODEL = dict(M=1.0, K=1.0, a1=-0.1, a2=0.05)
PAPER = Parameters(**MODEL, F=1.0, b=0.1)


def test_return_map_is_eq16_and_the_ensemble_s_is_the_scalar_one():
    v_in, v_out = return_map(PAPER, 1.1)
    assert v_in == pytest.approx(1.1, rel=1e-14)
    assert v_out == pytest.approx(np.sqrt(0.6561 * v_in**2 + 2 * (0.01 - 0.2 + 2) * 0.15), rel=1e-14)
    b, F, v = np.array([0.1, 0.5, 0.9]), np.array([1.0, 0.3, 2.0]), np.array([1.1, 0.7, 1.5])
    v_in, v_out, period, status = ensemble_return_map(MODEL, b, F, v)
    assert status.tolist() == [Status.COMPLETED.code] * 3 and np.all(np.isfinite(period))
    for i in range(3):
        ref = return_map(Parameters(**MODEL, F=F[i], b=b[i]), v[i])
        assert (v_in[i], v_out[i]) == pytest.approx(ref, rel=1e-14)


def test_grid_multipliers_and_outcomes():
    b = np.array([0.005, 0.1, 0.7, 1.0, 1.3])
    g = stability_grid(MODEL, b, np.full(5, 0.5))
    assert g["multiplier"][:4] == pytest.approx((1 - b[:4]) ** 4, abs=1e-9) and np.isnan(g["multiplier"][4])
    assert g["newton_converged"][:4].all()
    assert g["fixed_point"][:4] == pytest.approx(np.sqrt(2 * 0.15 * 0.5 / (2 * b[:4] - b[:4] ** 2)), rel=1e-10)


def test_without_a_return_the_map_raises_or_gives_nan_and_the_measurement_an_outcome():
    # b = 1.5: the first impact at a1 reverses the velocity, so the motion never returns to the section
    p = Parameters(**MODEL, F=1.0, b=1.5)
    with pytest.raises(NoReturn, match="no return to the section from v = 1.1") as err:
        return_map(p, 1.1)
    assert isinstance(err.value, ValueError) and "reversed the velocity" in str(err.value)
    v_in, v_out = return_map(p, 1.1, strict=False)
    assert v_in == pytest.approx(1.1, rel=1e-14) and math.isnan(v_out)  # the first impact kept
    m = measure_cycle(p, 1.0)
    assert m.outcome == "chattering" and np.isnan(m.multiplier)


@pytest.fixture(scope="module")
def paper_cycle():
    return measure_cycle(PAPER, -1.0, 200)


def test_the_paper_case_against_eqs_19_and_21_and_both_floquet_multipliers(paper_cycle):
    """Eqs. (19) and (21) hold (derived on paper from the energy balance); the flow's multipliers are 1 (along the
    cycle) and (1 - b)^4, Eq. (21) as printed."""
    m = paper_cycle
    assert m.outcome == "completed" and 1 < m.cycles_to_converge < 200
    assert m.velocity == pytest.approx(np.sqrt(2 * 0.15 / (0.2 - 0.01)), rel=1e-12)
    assert m.multiplier == pytest.approx(0.6561, abs=1e-8)
    assert m.floquet[0] == pytest.approx(1.0, abs=1e-8) and m.floquet[1] == pytest.approx(0.6561, abs=1e-8)
    with pytest.raises(ValueError, match="period = -1.0 must be a finite number > 0"):
        floquet_multipliers(PAPER, 1.0, 0.0, -1.0)
    short = measure_cycle(PAPER, -1.0, 3)  # the first period is the first cycle's
    assert short.first_period == m.first_period and short.first_period != m.period


def test_largest_speed_of_one_arc_and_on_the_paper_limit_cycle(paper_cycle):
    # free arc about 0 from x = -1 at rest (w = 1): v = sin t, largest |v| on [0, 1] is sin 1, on [0, 3] it is 1
    arcs = ArcTable(np.array([0.0]), np.array([0.0]), np.array([-1.0]), np.array([0.0]), 1.0, 10.0)
    assert largest_speed(arcs, 0.0, 1.0) == pytest.approx(math.sin(1.0), rel=1e-15)
    assert largest_speed(arcs, 0.0, 3.0) == pytest.approx(1.0, rel=1e-15)
    assert largest_speed(arcs, 2.0, 3.0) == pytest.approx(math.sin(2.0), rel=1e-15)
    with pytest.raises(ValueError, match="t_from = 3.0 must be < t_to = 1.0"):
        largest_speed(arcs, 3.0, 1.0)
    # on the limit cycle v1^2 = 2 (a2 - a1) f / (2b - b^2) = 0.3/0.19; the zone (a1, a2) lies left of its centre
    # c = 1 m, so the speed grows to a2: v2^2 = 0.81 v1^2 + (a1^2 - a2^2) + 2 f (a2 - a1) = 0.81 * 0.3/0.19 + 0.3075
    assert paper_cycle.largest_speed == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)

