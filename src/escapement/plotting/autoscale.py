"""Automatic axis limits as a plotting program would choose them, computed by matplotlib itself.

:func:`autoscaled_limits` plots the values on an Agg canvas with ``axes.autolimit_mode:
round_numbers`` and a fixed :class:`~matplotlib.ticker.MultipleLocator` of the given tick step,
lets matplotlib autoscale, and reads the limits back: the data range widened by the margin on
each side, then rounded outward to multiples of the step (no rounding of our own).
:func:`autoscaled_limits_many` does the same for many arrays on one axes, one array at a time.

Two variants (:data:`VARIANTS`):

* ``round, margin 0``: the limits round the data range itself outward to the ticks. This is the
  assumption for the paper's figures: MATLAB, the likely software of the paper (2012), chose
  automatic limits that enclose the data and end on ticks, with no padding (its ``'padded'``
  limit method came in 2021); matplotlib's classic style (before 2.0) did the same, with
  ``round_numbers`` and zero margins.
* ``round, margin 0.05``: matplotlib's default margins (``axes.xmargin = axes.ymargin = 0.05``
  since 2.0, whose default mode is ``data``, unrounded) added before rounding to the ticks.

The tick step is the printed one, given: a program that chooses its own step from the data
range could choose another, and would then round to other limits.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import matplotlib
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

__all__ = ["VARIANTS", "autoscaled_limits", "autoscaled_limits_many"]

#: the autoscaling variants by name: the margin added on each side before rounding, as a fraction of the range
VARIANTS: dict[str, float] = {"round, margin 0": 0.0, "round, margin 0.05": 0.05}


def _finite(values) -> np.ndarray:
    data = np.asarray(values, dtype=float).ravel()
    data = data[np.isfinite(data)]
    if data.size == 0:
        raise ValueError("no finite values to scale an axis to")
    return data


def autoscaled_limits_many(series: Iterable, step: float, margin: float = 0.0) -> list[tuple[float, float]]:
    """:func:`autoscaled_limits` of each array of ``series`` in turn, on one axes (each array alone
    on it: the previous line is removed and the data limits recomputed before the next)."""
    arrays = [_finite(values) for values in series]
    if not (math.isfinite(step) and step > 0):
        raise ValueError(f"step = {step!r} must be a positive finite number")
    if not (math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin = {margin!r} must be a non-negative finite number")
    rc = {"axes.autolimit_mode": "round_numbers", "axes.xmargin": margin, "axes.ymargin": margin}
    limits = []
    with matplotlib.rc_context(rc):
        figure = Figure()
        FigureCanvasAgg(figure)
        ax = figure.add_subplot()
        ax.yaxis.set_major_locator(MultipleLocator(step))
        for data in arrays:
            (line,) = ax.plot(np.arange(data.size), data)
            ax.autoscale_view()
            low, high = ax.get_ylim()
            limits.append((float(low), float(high)))
            line.remove()
            ax.relim()
    return limits


def autoscaled_limits(values, step: float, margin: float = 0.0) -> tuple[float, float]:
    """The limits matplotlib gives an axis holding ``values`` (NaN ignored) with major ticks every
    ``step``, limits rounded to the ticks (``round_numbers``) after a margin of ``margin`` times
    the data range on each side."""
    return autoscaled_limits_many([values], step, margin)[0]
