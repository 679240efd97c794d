"""The checks on an experiment's settings that the model's own checks do not cover: a time window
and a positive count, each refused with a :class:`~escapement.model.parameters.ParameterError`
naming the setting before any run starts."""

from __future__ import annotations

import numpy as np

from ..model.parameters import ParameterError

__all__ = ["positive_int", "time_window"]


def time_window(name: str, window) -> tuple[float, float]:
    """The window ``[start, end]`` (s) of the setting ``name``, with ``0 <= start < end < inf``.

    Parameters
    ----------
    name : str
        The setting's name, for the error message.
    window : sequence of two numbers
        Start and end of the window, s.

    Returns
    -------
    tuple of float
        ``(start, end)``.

    Raises
    ------
    ParameterError
        If ``window`` is not two numbers with ``0 <= start < end < inf``.
    """
    try:
        lo, hi = (float(w) for w in window)
    except (TypeError, ValueError) as err:
        raise ParameterError(name, window, "a pair [start, end] of times in s") from err
    if not (0 <= lo < hi < np.inf):
        raise ParameterError(name, window, "a pair [start, end] with 0 <= start < end (s)")
    return lo, hi


def positive_int(name: str, value) -> int:
    """``value`` as an ``int``, if it is a positive integer (not a bool).

    Parameters
    ----------
    name : str
        The setting's name, for the error message.
    value : int
        The count.

    Returns
    -------
    int
        The count.

    Raises
    ------
    ParameterError
        If ``value`` is not a positive integer.
    """
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ParameterError(name, value, "a positive integer")
    return int(value)
