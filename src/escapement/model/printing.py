"""Numbers as text that is true as printed, zero without a sign; hand-written, because Python's formats print a
fixed number of digits, not the fewest that keep an order true."""

from __future__ import annotations

from itertools import combinations

import numpy as np
from numpy.typing import ArrayLike

from .arguments import Numeric

__all__ = ["compared", "exact", "number", "span", "texts", "with_unit"]


#: the significant digits that tell every two doubles apart
_ALL_DIGITS = 17


def _unsigned_zero(value: Numeric) -> float:
    """``value`` as a double (an mpmath number as its nearest), a negative zero made positive."""
    return float(value) + 0.0  # -0.0 + 0.0 is +0.0; every other double is unchanged


def with_unit(text: str, unit: str) -> str:
    """``text`` followed by ``unit``, none for a dimensionless one."""
    return text if unit in ("", "1") else f"{text} {unit}"


def exact(value: Numeric, unit: str = "") -> str:
    """An input as it can be typed back (Python's ``repr``, without a trailing ``.0``), with its unit."""
    return with_unit(repr(_unsigned_zero(value)).removesuffix(".0"), unit)


def _order(x: float, y: float) -> int:
    """-1, 0 or 1 as ``x`` is below, equal to or above ``y``; 0 where either is NaN."""
    return (x > y) - (x < y)


def texts(values: ArrayLike, digits: int = 6) -> list[str]:
    """``values`` to ``digits`` significant digits, or to more where fewer would misstate how two of them compare
    (alike, or in the wrong order); as typed back (:func:`exact`) when 16 digits are not enough."""
    floats = [_unsigned_zero(v) for v in values]
    pairs = list(combinations(range(len(floats)), 2))
    for width in range(digits, _ALL_DIGITS):
        printed = [f"{x:.{width}g}" for x in floats]
        read = [float(text) for text in printed]
        if all(_order(read[i], read[j]) == _order(floats[i], floats[j]) for i, j in pairs):
            return printed
    return [exact(x) for x in floats]


def compared(value: Numeric, bounds: ArrayLike, digits: int = 12) -> str:
    """A computed ``value`` to ``digits`` significant digits, or to more where fewer would misstate how it compares
    with one of the inputs ``bounds`` (printed by :func:`exact`)."""
    value, bounds = _unsigned_zero(value), [_unsigned_zero(b) for b in bounds]
    for width in range(digits, _ALL_DIGITS):
        text = f"{value:.{width}g}"
        if all(_order(float(text), b) == _order(value, b) for b in bounds):
            return text
    return exact(value)


def number(value: Numeric, unit: str = "", digits: int = 6) -> str:
    """A computed ``value`` to ``digits`` significant digits, with its unit."""
    return with_unit(texts([value], digits)[0], unit)


def span(values: ArrayLike, unit: str) -> str:
    """The range of ``values`` (NaN ignored): ``lo .. hi unit`` with the digits that tell them apart, or one."""
    values = np.asarray(values, dtype=float)
    if np.isnan(values).all():
        return "none"
    lo, hi = texts([np.nanmin(values), np.nanmax(values)])
    return with_unit(lo, unit) if lo == hi else f"{lo} .. {with_unit(hi, unit)}"
