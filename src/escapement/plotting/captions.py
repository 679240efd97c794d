"""The text of the figures: axis labels and quantities with their values and units, the readings a
figure assumes, the paper's figure it reproduces, and the note on a run that ended early.

Names, symbols and units come from :mod:`escapement.model.quantities`; the readings, sources and
outcomes from the datasets' attributes.
"""

from __future__ import annotations

import math
import re
import textwrap

import numpy as np
import xarray as xr

from ..model.quantities import quantity
from ..model.status import Status
from .labels import Label
from .style import ACCENT

__all__ = ["assumed_reading", "axis_label", "broken", "initial_velocity", "math_text", "natural_period",
           "outcome_note", "paper_source", "quantity_value", "release", "signed", "unit", "wrap"]

#: the datasets' plain-text spellings and how a figure writes them: accents, and formulas as mathtext
#: without spaces (so that wrapping never splits one across lines)
_SPELLINGS = (
    ("Poincare", "Poincar\u00e9"),
    ("sqrt(a1^2 + (v_k / omega)^2)", r"$\sqrt{a_1^2+(v_k/\omega)^2}$"),
)
#: symbols written as mathtext wherever they stand as words: the Step-1 and Step-8 amplitudes and a1
_SYMBOLS = re.compile(r"(?<![\w$])(?:h([04])\((k(?:\+1)?)\)|a1)(?![\w$])")


def broken(t: np.ndarray, y: np.ndarray, breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A line with a gap at each break time, so that it is not drawn across a jump.

    Parameters
    ----------
    t, y : numpy.ndarray
        The abscissae (increasing) and ordinates of the line.
    breaks : numpy.ndarray
        The times of the jumps.

    Returns
    -------
    tuple of numpy.ndarray
        ``t`` and ``y`` as floats with NaN inserted at each break.
    """
    idx = np.searchsorted(t, breaks)
    return np.insert(t.astype(float), idx, np.nan), np.insert(y.astype(float), idx, np.nan)


def axis_label(name: str) -> str:
    """The axis label of the quantity ``name`` (:meth:`~escapement.model.quantities.Quantity.axis_label`).

    Parameters
    ----------
    name : str
        A parameter, an initial-state component or a computed variable.

    Returns
    -------
    str
        For example ``Force F (N)``.
    """
    return quantity(name).axis_label()


def unit(name: str) -> str:
    """The units of the quantity ``name`` as printed in a label (empty for a pure number).

    Parameters
    ----------
    name : str
        A parameter, an initial-state component or a computed variable.

    Returns
    -------
    str
        For example ``N s``.
    """
    q = quantity(name)
    return "" if q.dimensionless else q.unit_label


def signed(value: float, spec: str) -> str:
    """``value`` formatted by ``spec``, with the minus sign of the axes' tick labels.

    Parameters
    ----------
    value : float
        The number.
    spec : str
        A format specification, e.g. ``"+.4f"``.

    Returns
    -------
    str
        The formatted number, with U+2212 for the minus sign.
    """
    return format(value, spec).replace("-", "\u2212")


def quantity_value(name: str, value: float) -> str:
    """``F = 0.5 N``: the quantity's symbol, the value and its units.

    The parts are joined by no-break spaces, so that a wrapped line never splits a quantity.

    Parameters
    ----------
    name : str
        A parameter or an initial-state component.
    value : float
        Its value, in the units of the quantities table.

    Returns
    -------
    str
        The symbol, ``=``, the value and, unless it is a pure number, the units.
    """
    units = unit(name)
    return f"{quantity(name).symbol}\u00a0=\u00a0{signed(value, 'g')}" + (f"\u00a0{units}" if units else "")


def initial_velocity(ds: xr.Dataset) -> float:
    """The initial velocity of a run; a dataset without one was released from rest.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's dataset.

    Returns
    -------
    float
        ``v0`` (m/s), or 0.
    """
    return float(ds["v0"]) if "v0" in ds else 0.0


def release(ds: xr.Dataset) -> str:
    """How a run was released: ``released from rest at x(0) = 3 m``, or with its initial velocity.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's dataset, with ``x0`` and possibly ``v0``.

    Returns
    -------
    str
        The phrase.
    """
    x0 = quantity_value("x0", float(ds["x0"]))
    v0 = initial_velocity(ds)
    return f"released from rest at {x0}" if v0 == 0 else f"released at {x0} with {quantity_value('v0', v0)}"


def assumed_reading(ds: xr.Dataset, composed: str) -> str:
    """The readings a figure assumes where the paper is silent.

    Parameters
    ----------
    ds : xarray.Dataset
        The figure's dataset.
    composed : str
        The sentence composed from the dataset's variables.

    Returns
    -------
    str
        The dataset's own sentence (global attribute ``reading``) if it has one, else ``composed``.
    """
    return str(ds.attrs.get("reading") or composed)


def paper_source(ds: xr.Dataset, figure: str) -> str:
    """The paper's figure a dataset reproduces.

    Parameters
    ----------
    ds : xarray.Dataset
        The figure's dataset.
    figure : str
        The paper's figure, e.g. ``"Fig. 3"``, for a dataset with no ``title``.

    Returns
    -------
    str
        The dataset's ``title``, which names the figure, or a citation of ``figure``.
    """
    return str(ds.attrs.get("title") or f"Mao, Fu & Li (2013), {figure}")


def math_text(text: str) -> str:
    """``text`` as a figure writes it: "Poincaré" with its accent, the formulas and symbols of the
    datasets' plain-text long names (``sqrt(a1^2 + (v_k / omega)^2)``, ``h0(k)``, ``a1``) as mathtext.

    Parameters
    ----------
    text : str
        Plain text, as the datasets' attributes hold it.

    Returns
    -------
    str
        The same text with those spellings replaced.
    """
    for plain, written in _SPELLINGS:
        text = text.replace(plain, written)
    parts = text.split("$")  # the odd parts are mathtext already
    for i in range(0, len(parts), 2):
        parts[i] = _SYMBOLS.sub(lambda m: f"$h_{m[1]}({m[2]})$" if m[1] else "$a_1$", parts[i])
    return "$".join(parts)


def wrap(text: str, width: int) -> str:
    """``text`` in lines of at most ``width`` characters (never broken at a hyphen).

    Parameters
    ----------
    text : str
        The text.
    width : int
        The most characters a line.

    Returns
    -------
    str
        The lines joined by newlines.
    """
    return "\n".join(textwrap.wrap(text, width, break_on_hyphens=False))


def natural_period(ds: xr.Dataset) -> float:
    """The natural period 2 pi / omega, omega = sqrt(K/M), from the dataset's own K and M.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's dataset, with ``K`` and ``M``.

    Returns
    -------
    float
        The period (s).
    """
    return 2 * math.pi / math.sqrt(float(ds["K"]) / float(ds["M"]))


def outcome_note(ax, ds: xr.Dataset) -> list[Label]:
    """How a run that did not complete ended, to place in the free corner of its panel nearest the lower left.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The run's panel.
    ds : xarray.Dataset
        The run's dataset, with the global attributes ``outcome`` and ``outcome_message``.

    Returns
    -------
    list of Label
        One framed note, or none if the run completed.
    """
    if Status(ds.attrs.get("outcome", Status.COMPLETED.value)).success:
        return []
    text = wrap(f"{ds.attrs['outcome']}: {ds.attrs['outcome_message']}", 40)
    frame = {"facecolor": "white", "edgecolor": ACCENT, "linewidth": 0.6}
    return [Label(ax, text, (0.0, 0.0), "axes fraction", {"fontsize": 6.5, "color": ACCENT, "bbox": frame},
                  leader=False)]
