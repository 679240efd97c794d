"""Automatic axis limits from matplotlib, for hand-made data whose round-number limits are known."""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest

from escapement.plotting.autoscale import VARIANTS, autoscaled_axes, autoscaled_limits


@pytest.mark.parametrize("values, step, expected", [  # the data range rounded outward to the ticks, where not on one
    ([0.995, 1.257], 0.05, (0.95, 1.3)), ([1.0497, 1.2566], 0.05, (1.0, 1.3)), ([1, 50], 10, (0, 50)),
    ([1, 51], 10, (0, 60)), ([0.8885, 2.9983], 0.5, (0.5, 3.0)), ([-2.858, 3.146], 1, (-3, 4)),
    ([-3.146, 2.858], 1, (-4, 3)), ([0.1285, 0.8999], 0.1, (0.1, 0.9)), ([6.2957, 6.3043], 0.0002, (6.2956, 6.3044)),
])
def test_round_numbers_without_margin(values, step, expected):
    assert autoscaled_limits(np.array(values), step) == pytest.approx(expected, abs=1e-12)


def test_only_the_extent_counts_and_a_value_a_rounding_error_away_from_a_tick_counts_as_on_it():
    values = np.array([1.2, 0.995, 1.1, 1.257, 1.0])
    assert autoscaled_limits(values, 0.05) == autoscaled_limits(values[::-1], 0.05) == \
        autoscaled_limits([0.995, 1.257], 0.05) == autoscaled_limits([np.nan, 0.995, 1.257, np.nan], 0.05)
    # 3 from sqrt(a1**2 + v**2) may come out one unit in the last place off; the axis still ends at 3
    assert autoscaled_limits([0.9, math.nextafter(3.0, 4.0)], 0.5)[1] == pytest.approx(3.0, abs=1e-12)
    assert autoscaled_limits([math.nextafter(0.5, 0.0), 2.0], 0.5)[0] == pytest.approx(0.5, abs=1e-12)


def test_a_margin_widens_the_range_before_rounding_and_the_variants_are_0_and_matplotlibs_default():
    # [1, 50] plus 5 % of 49 on each side is [-1.45, 52.45]: ticks -10 and 60
    assert autoscaled_limits([1, 50], 10, margin=0.05) == pytest.approx((-10, 60))
    # [0.995, 1.257] plus 0.0131 on each side stays within [0.95, 1.3]
    assert autoscaled_limits([0.995, 1.257], 0.05, margin=0.05) == pytest.approx((0.95, 1.3))
    # [1.0, 1.26] plus 0.013: below 1.0, so down to 0.95
    assert autoscaled_limits([1.0, 1.26], 0.05, margin=0.05) == pytest.approx((0.95, 1.3))
    assert autoscaled_limits([1.0, 1.26], 0.05, margin=0.0) == pytest.approx((1.0, 1.3))
    assert VARIANTS == {"round, margin 0": 0.0, "round, margin 0.05": 0.05}
    assert matplotlib.rcParamsDefault["axes.ymargin"] == 0.05


@pytest.mark.parametrize("values, step, margin, axis, words", [
    ([np.nan], 0.05, 0.0, "y", "no finite values"),
    ([1.0, 2.0], 0.0, 0.0, "y", "step = 0.0 must be a positive finite number"),
    ([1.0, 2.0], 0.5, -0.1, "y", "margin = -0.1 must be a non-negative finite number"),
    ([1.0, 2.0], 0.5, 0.0, "z", "axis = 'z' must be one of x, y"),
])
def test_bad_arguments_are_refused(values, step, margin, axis, words):
    with pytest.raises(ValueError, match=words):
        autoscaled_limits(values, step, margin, axis)


def test_the_global_settings_are_left_as_they_were():
    before = {k: matplotlib.rcParams[k] for k in ("axes.autolimit_mode", "axes.xmargin", "axes.ymargin")}
    autoscaled_limits([0.995, 1.257], 0.05, margin=0.05)
    assert {k: matplotlib.rcParams[k] for k in before} == before


@pytest.mark.parametrize("step", [0.05, None], ids=["printed step", "matplotlib's own"])
def test_many_arrays_on_one_axes_give_each_arrays_own_limits_and_tick_step(step):
    series = [[0.995, 1.257], [1, 51], [-3.146, 2.858], [0.1285, 0.8999]]
    for margin in VARIANTS.values():
        alone = [autoscaled_axes([s], step, margin)[0] for s in series]
        assert autoscaled_axes(series, step, margin) == alone and autoscaled_axes(series[::-1], step, margin) == \
            alone[::-1]
        # the tick step is the one imposed, or matplotlib's own; either way the limits end on ticks around the data
        assert all(tick == 0.05 if step else tick > 0 for _, _, tick in alone)
        assert all(abs(x / tick - round(x / tick)) < 1e-9 for low, high, tick in alone for x in (low, high))
        assert all(low <= min(s) and max(s) <= high for (low, high, _), s in zip(alone, series))
