"""The checks of the public entry points' arguments, one rule per kind, one error naming the argument, its value
and what it must be; hand-written, because NumPy and the validation libraries coerce silently (``[0.1, True]``
becomes ``[0.1, 1.0]``) and name no row."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from numbers import Integral, Real
from typing import Any, TypeAlias

import numpy as np

__all__ = ["Numeric", "ParameterError", "ParameterTypeError", "check_choice", "check_count", "check_flag",
           "check_index", "real_array", "real_number", "sample_times"]

#: a real number as the closed forms take it: a float, a NumPy array of them or an mpmath number
Numeric: TypeAlias = Any
_MASKED = "a real number, not a masked element (it holds no value)"


class ParameterError(ValueError):
    """An input value is outside its allowed range; the message names it.

    Parameters
    ----------
    name : str
        The input's name (``"a2"``, ``"n_cycles"``, ...), kept as the attribute ``name``.
    value : object
        The refused value, as given (in the input's SI unit).
    requirement : str
        What the value must be, in words, with the unit.
    row : int or None
        The index of the offending trajectory for an array input (the ensemble), else None.

    Examples
    --------
    >>> from escapement import ParameterError, Parameters
    >>> try:
    ...     Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=-0.2)
    ... except ParameterError as err:
    ...     print(err.name, err.value, err)
    a2 -0.2 a2 = -0.2 is invalid: a2 must be > a1 = -0.1 (m)
    """

    def __init__(self, name: str, value: object, requirement: str, row: int | None = None) -> None:
        self.name, self.value, self.requirement, self.row = name, value, requirement, row
        where = "" if row is None else f"row {row}: "
        super().__init__(f"{where}{name} = {value!r} is invalid: {name} must be {requirement}")


class ParameterTypeError(ParameterError, TypeError):
    """An argument of the wrong class: a :class:`ParameterError` of the same shape that is also a TypeError."""


def _refuse_masked(name: str, value: object) -> object:
    """``value`` unmasked if nothing in it is masked, else refused naming the first masked element."""
    if not isinstance(value, np.ma.MaskedArray):
        return value
    mask = np.ma.getmaskarray(value)
    if mask.any():
        if mask.ndim == 0:
            raise ParameterError(name, value, _MASKED)
        raise ParameterError(name, np.ma.masked, _MASKED, row=int(np.flatnonzero(mask.ravel())[0]))
    return np.asarray(value.data)


def _element(name: str, item: object, row: int | None) -> float:
    """One real number as a float, or raise naming ``name`` (and the row)."""
    if item is np.ma.masked:
        raise ParameterError(name, item, _MASKED, row=row)
    if isinstance(item, bool | np.bool_) or not isinstance(item, Real):
        raise ParameterError(name, item, "a real number", row=row)
    try:
        return float(item)
    except OverflowError as err:
        raise ParameterError(name, item, "a real number within the float64 range", row=row) from err


def real_number(name: str, value: object, holds: Callable[[float], bool] | None = None,
                requirement: str = "") -> float:
    """``value`` as a float if it is a single finite real number (not a bool, a string, a complex number, None, a
    masked value or a sequence) and, when given, ``holds(value)``, which ``requirement`` says in words."""
    if isinstance(_refuse_masked(name, value), np.ndarray | list | tuple):
        raise ParameterError(name, value, "a single real number, not an array or a sequence")
    number = _element(name, value, None)
    if not math.isfinite(number):
        raise ParameterError(name, value, "finite")
    if holds is not None and not holds(number):
        raise ParameterError(name, value, requirement)
    return number


def real_array(name: str, value: object) -> np.ndarray:
    """``value`` (a real number or an array-like of them, any shape) as float64; a bad element is refused with
    its flat index as the row."""
    if isinstance(value, bool | np.bool_ | str | bytes):
        raise ParameterError(name, value, "a real number")
    value = _refuse_masked(name, value)
    if isinstance(value, np.ndarray) and value.dtype.kind in "iuf":
        with np.errstate(over="ignore"):  # a long double beyond float64 becomes inf: refused as not finite
            array = value.astype(np.float64)
    else:
        try:
            items = np.asarray(value, dtype=object)
        except (TypeError, ValueError) as err:
            raise ParameterError(name, value, "a real number or an array of them") from err
        rows = range(items.size) if items.ndim else [None]
        flat = [_element(name, item, row) for row, item in zip(rows, items.ravel())]  # one per element
        array = np.asarray(flat, dtype=np.float64).reshape(items.shape)
    bad = ~np.isfinite(array)
    if bad.any():
        row = int(np.flatnonzero(bad.ravel())[0]) if array.ndim else None
        raise ParameterError(name, float(array.ravel()[row or 0]), "finite", row=row)
    return array


def sample_times(name: str, value: object) -> np.ndarray:
    """Times to sample a trajectory at (s): a real number (0-d) or a 1-d array of them, finite, as float64."""
    if value is None:
        raise ParameterError(name, value, "a real number or a 1-d array of them (s)")
    times = real_array(name, value)
    if times.ndim > 1:
        raise ParameterError(name, value, f"a real number or a 1-d array of them (s), not of shape {times.shape}")
    return times


def check_flag(name: str, value: object) -> bool:
    """``value`` as a bool if it is ``True`` or ``False`` (a NumPy bool too); ``"no"`` or 0 is not a no."""
    if not isinstance(value, bool | np.bool_):
        raise ParameterError(name, value, "True or False")
    return bool(value)


def check_count(name: str, value: object, maximum: int, minimum: int = 1) -> int:
    """``value`` as an int if it is an integer (not a bool) in ``[minimum, maximum]``."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, Integral) or not minimum <= value <= maximum:
        least = "a positive integer" if minimum == 1 else f"an integer >= {minimum:_}"
        raise ParameterError(name, value, f"{least}, at most {maximum:_}")
    return int(value)


def check_index(name: str, value: object, size: int) -> int:
    """``value`` as an int if it is a row of an ensemble of ``size``: an integer (not a bool) in ``[0, size)``."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, Integral) or not 0 <= value < size:
        raise ParameterError(name, value, f"an integer in [0, {size - 1}], a row of the {size} trajectories"
                             if size else "a row of the trajectories, and there are none")
    return int(value)


def check_choice(name: str, value: object, choices: Iterable[str]) -> str:
    """``value`` if it is one of the strings ``choices``."""
    choices = tuple(choices)
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, value, "one of " + ", ".join(repr(c) for c in choices))
    return value
