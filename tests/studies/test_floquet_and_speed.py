"""The largest speed of a motion from its arcs and both Floquet multipliers of the flow (studies.poincare),
against hand-derived values and the paper's printed multiplier 0.6561."""

from __future__ import annotations

import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.studies.poincare import floquet_multipliers, largest_speed, measure_cycle
from escapement.solvers.result import ArcTable

PAPER = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


def test_largest_speed_of_one_arc_passing_its_centre_or_not():
    # free arc about 0 from x = -1 at rest (w = 1): v = sin t, largest |v| on [0, 1] is sin 1, on [0, 3] it is 1
    arcs = ArcTable(np.array([0.0]), np.array([0.0]), np.array([-1.0]), np.array([0.0]), 1.0, 10.0)
    assert largest_speed(arcs, 0.0, 1.0) == pytest.approx(math.sin(1.0), rel=1e-15)
    assert largest_speed(arcs, 0.0, 3.0) == pytest.approx(1.0, rel=1e-15)
    assert largest_speed(arcs, 2.0, 3.0) == pytest.approx(math.sin(2.0), rel=1e-15)
    with pytest.raises(ValueError, match="t_from = 3.0 must be < t_to = 1.0"):
        largest_speed(arcs, 3.0, 1.0)


def test_largest_speed_on_the_paper_limit_cycle_is_the_speed_at_a2():
    # on the limit cycle v1^2 = 2 (a2 - a1) f / (2b - b^2) = 0.3/0.19; the zone (a1, a2) lies left of its centre
    # c = 1 m, so the speed grows to a2: v2^2 = 0.81 v1^2 + (a1^2 - a2^2) + 2 f (a2 - a1) = 0.81 * 0.3/0.19 + 0.3075
    m = measure_cycle(PAPER, -1.0, 200)
    assert m.largest_speed == pytest.approx(math.sqrt(0.81 * 0.3 / 0.19 + 0.3075), rel=1e-12)


def test_both_floquet_multipliers_of_the_paper_case():
    m = measure_cycle(PAPER, -1.0, 200)
    assert m.floquet[0] == pytest.approx(1.0, abs=1e-8)
    assert m.floquet[1] == pytest.approx(0.6561, abs=1e-8)  # Eq. (21), printed
    with pytest.raises(ValueError, match="period = -1.0 must be a finite number > 0"):
        floquet_multipliers(PAPER, 1.0, 0.0, -1.0)


def test_the_first_period_is_the_first_cycles():
    short, long_ = measure_cycle(PAPER, -1.0, 3), measure_cycle(PAPER, -1.0, 50)
    assert short.first_period == long_.first_period and short.first_period != long_.period
