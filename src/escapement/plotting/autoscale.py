"""Automatic axis limits as matplotlib chooses them: each array alone on one axes with ``axes.autolimit_mode:
round_numbers``, the limits read back with the tick step, imposed or matplotlib's own (``step=None``). The margins
(:data:`VARIANTS`): 0, the assumption for the paper's figures (MATLAB, its likely software in 2012, padded no limits
before 2021, nor did matplotlib's classic style), and 0.05, matplotlib's default since 2.0, added before rounding.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import matplotlib
import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

__all__ = ["VARIANTS", "autoscaled_axes", "autoscaled_limits"]

#: the autoscaling variants by name: the margin added on each side before rounding, as a fraction of the range
VARIANTS: dict[str, float] = {"round, margin 0": 0.0, "round, margin 0.05": 0.05}


def _extent(values) -> np.ndarray:
    data = np.asarray(values, dtype=float).ravel()
    data = data[np.isfinite(data)]
    if data.size == 0:
        raise ValueError("no finite values to scale an axis to")
    return np.array([data.min(), data.max()])


def autoscaled_axes(series: Iterable, step: float | None, margin: float = 0.0, axis: str = "y"
                    ) -> list[tuple[float, float, float]]:
    """``(low, high, tick step)`` of each array of ``series`` (NaN ignored) alone on the ``axis`` of one axes, rounded
    to the ticks after a margin of ``margin`` times its range on each side; ticks every ``step``, or matplotlib's."""
    extents = [_extent(values) for values in series]
    if step is not None and not (isinstance(step, (int, float)) and math.isfinite(step) and step > 0):
        raise ValueError(f"step = {step!r} must be a positive finite number, or None for the default locator")
    if not (isinstance(margin, (int, float)) and math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin = {margin!r} must be a non-negative finite number")
    if axis not in ("x", "y"):
        raise ValueError(f"axis = {axis!r} must be one of x, y")
    rc = {"axes.autolimit_mode": "round_numbers", "axes.xmargin": margin, "axes.ymargin": margin}
    found: dict[tuple[float, float], tuple[float, float, float]] = {}
    with matplotlib.rc_context(rc):
        ax = Figure().add_subplot()
        scaled = ax.xaxis if axis == "x" else ax.yaxis
        if step is not None:
            scaled.set_major_locator(MultipleLocator(step))
        for lo, hi in extents:
            if (lo, hi) in found:
                continue
            pair = np.array([lo, hi])
            (line,) = ax.plot(pair, np.zeros(2)) if axis == "x" else ax.plot(np.zeros(2), pair)
            ax.autoscale_view()
            low, high = ax.get_xlim() if axis == "x" else ax.get_ylim()
            if step is None:
                ticks = scaled.get_majorticklocs()
                tick_step = float(ticks[1] - ticks[0]) if len(ticks) > 1 else math.nan
            else:
                tick_step = float(step)
            found[(lo, hi)] = (float(low), float(high), tick_step)
            line.remove()
            ax.relim()
    return [found[(lo, hi)] for lo, hi in extents]


def autoscaled_limits(values, step: float | None, margin: float = 0.0, axis: str = "y") -> tuple[float, float]:
    """The ``(low, high)`` of :func:`autoscaled_axes` for the one array ``values``."""
    return autoscaled_axes([values], step, margin, axis)[0][:2]
