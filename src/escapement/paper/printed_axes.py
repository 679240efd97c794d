"""The axes of the paper's Figs. 3-5 as printed: their tick labels, limits and tick steps.

The figures survive in the paper's text only as their tick labels (:data:`TICK_LINES`, by line of its plain text);
each axis lists its labels low to high and the lines that show them. The limits are the outermost labels: automatic
limits rounded out to ticks (MATLAB's default) end on a labelled tick. Where the text leaves a choice:

* Fig. 3: the eighteen period labels (lines 297-319, 347-367) split into two evenly spaced axes in one way only:
  the odd ten-thousandths and 6.2828, printed once, need a step of 0.0001: (a) 6.283 to 6.2846 by 0.0002 (its labels
  met first), (b) 6.2826 to 6.2834 by 0.0001. The ``3`` ending the page header (line 263) tops (b)'s velocity axis.
* Fig. 4: the velocity window is taken as 80-87 s, by the order of the axis titles; the time axes are the windows
  themselves, so their limits test no reading (``scored=False``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import Decimal

__all__ = ["CYCLES", "FIG3_PERIOD", "FIG5_PANEL_K", "TICK_LINES", "Axis", "Panel", "PANELS", "limits_match", "panel",
           "panels_of"]

#: the lines of the paper's text that carry the figures' tick labels, by line number (1-based), verbatim
TICK_LINES: dict[int, str] = {
    # Fig. 3 (page 1008)
    263: "J. Mao et al. / Dynamics of periodic impulsive collision in escapement mechanism 3",
    269: "1.3 1.25 1.2 1.15 1.1 1.05 1 0.95", 271: "0", 273: "10", 275: "20", 277: "30", 279: "40", 281: "2.5",
    283: "2", 285: "1.5", 287: "1", 289: "0.5", 291: "50", 293: "0", 295: "10", 297: "6.2846", 299: "6.2834",
    301: "6.2844", 303: "6.2833", 305: "6.2842", 307: "6.2832", 309: "6.284 6.2838 6.2836", 311: "6.2827 20",
    313: "30", 315: "40", 317: "50", 319: "6.2826", 323: "10", 325: "20", 327: "40", 329: "30", 331: "50", 333: "3",
    339: "0", 343: "1.4 1.35 1.3 1.25 1.2 1.15 1.1 1.05 1", 345: "50", 347: "6.283", 349: "6.2828", 351: "10",
    353: "40", 355: "6.2829", 357: "6.2832", 359: "0", 361: "30", 363: "6.2831", 365: "6.2834", 367: "6.283",
    369: "20", 379: "0", 381: "10", 383: "20", 385: "30", 387: "40", 389: "50", 391: "2.5", 393: "2", 395: "1.5",
    397: "1", 399: "0.5", 401: "60", 403: "0", 405: "10", 407: "20", 409: "30", 411: "40", 413: "50", 415: "60",
    # Fig. 4 (page 1008)
    425: "0.9", 427: "0.9", 429: "0.8", 431: "0.8", 439: "0.7 0.6 0.5 0.4 0.3 0.2 0.1",
    441: "0.7 0.6 0.5 0.4 0.3 0.2 0.1", 443: "0", 445: "0", 447: "-0.1 81", 449: "-0.1 80", 451: "82", 453: "83",
    455: "84", 457: "85", 459: "86", 461: "87", 463: "81", 465: "82", 467: "83", 475: "84", 477: "85",
    # Fig. 5 (page 1009)
    479: "J. Mao et al. / Dynamics of periodic impulsive collision in escapement mechanism 1.5", 481: "4",
    483: "1 0.8", 485: "3", 487: "0.6", 489: "0.5 0 -0.5", 491: "0.4", 499: "1", 501: "0.2 0 -0.2 -0.4 -0.6",
    503: "-1", 505: "0", 507: "5", 509: "-1 -1", 511: "2 1 0 -1 -2", 513: "-0.8 -1.5 -5",
    515: "1009",  # the page number
    517: "-0.5", 519: "0", 521: "0.5", 523: "1", 525: "-3 -1", 527: "-0.5", 529: "0", 543: "0.5", 545: "1",
}


def limits_match(low: float, high: float, printed_low: float, printed_high: float, step: float) -> int:
    """How many of the two limits equal the printed ones (to a billionth of the tick step)."""
    pairs = ((low, printed_low), (high, printed_high))
    return sum(math.isclose(a, b, rel_tol=0.0, abs_tol=1e-9 * step) for a, b in pairs)


@dataclass(frozen=True)
class Axis:
    """One printed axis: its title, its tick labels as printed (low to high) and the text lines that show them."""

    label: str
    ticks: tuple[str, ...]
    lines: tuple[int, ...]
    scored: bool = True  #: False where the paper set the limits itself (a time window)

    def __post_init__(self) -> None:
        values = [Decimal(t) for t in self.ticks]
        steps = {b - a for a, b in zip(values, values[1:])}
        if len(steps) != 1 or steps.pop() <= 0:
            raise ValueError(f"axis {self.label!r}: tick labels {self.ticks} must be two or more, evenly spaced up")

    low = property(lambda self: float(self.ticks[0]), doc="The lowest tick label, the axis' lower limit.")
    high = property(lambda self: float(self.ticks[-1]), doc="The highest tick label, the axis' upper limit.")
    step = property(lambda self: float(Decimal(self.ticks[1]) - Decimal(self.ticks[0])),
                    doc="The spacing of the tick labels.")


@dataclass(frozen=True)
class Panel:
    """One panel of a figure (``figure`` "3", "4" or "5"): its ``name`` and its two axes."""

    figure: str
    name: str
    x: Axis
    y: Axis

    @property
    def axes(self) -> dict[str, Axis]:
        return {"x": self.x, "y": self.y}


#: the title of the cycle axes of Fig. 3: their limits follow from the number of cycles plotted
CYCLES = "Number of cycles"
_CYCLES_50 = ("0", "10", "20", "30", "40", "50")
_CYCLES_60 = ("0", "10", "20", "30", "40", "50", "60")
_HALVES_3 = ("0.5", "1", "1.5", "2", "2.5", "3")
_SHOCK = ("-0.1", "0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9")
_SHOCK_LINES = (425, 427, 429, 431, 439, 441, 443, 445, 447, 449)
_UNIT_HALVES = ("-1", "-0.5", "0", "0.5", "1")

PANELS: tuple[Panel, ...] = (
    # Fig. 3 (a), captioned "F=1, x(0)=1" in the paper
    Panel("3", "a/velocity", Axis(CYCLES, _CYCLES_50, (271, 273, 275, 277, 279, 291)),
          Axis("Velocity before impact (m/s)", ("0.95", "1", "1.05", "1.1", "1.15", "1.2", "1.25", "1.3"), (269,))),
    Panel("3", "a/period", Axis(CYCLES, _CYCLES_50, (323, 325, 327, 329, 331, 339)),
          Axis("Period (s)", ("6.283", "6.2832", "6.2834", "6.2836", "6.2838", "6.284", "6.2842", "6.2844", "6.2846"),
               (297, 301, 305, 309, 347, 357, 365, 367))),
    Panel("3", "a/amplitude", Axis(CYCLES, _CYCLES_60, (379, 381, 383, 385, 387, 389, 401)),
          Axis("Amplitude of oscillation (m)",
               ("1", "1.05", "1.1", "1.15", "1.2", "1.25", "1.3", "1.35", "1.4"), (343,))),
    # Fig. 3 (b), captioned "F=0.5, x(0)=3" in the paper
    Panel("3", "b/velocity", Axis(CYCLES, _CYCLES_50, (293, 295, 311, 313, 315, 317)),
          Axis("Velocity before impact (m/s)", _HALVES_3, (263, 281, 283, 285, 287, 289))),
    Panel("3", "b/period", Axis(CYCLES, _CYCLES_50, (345, 351, 353, 359, 361, 369)),
          Axis("Period (s)", ("6.2826", "6.2827", "6.2828", "6.2829", "6.283", "6.2831", "6.2832", "6.2833", "6.2834"),
               (299, 303, 307, 311, 319, 347, 349, 355, 357, 363, 365, 367))),
    Panel("3", "b/amplitude", Axis(CYCLES, _CYCLES_60, (403, 405, 407, 409, 411, 413, 415)),
          Axis("Amplitude of oscillation (m)", _HALVES_3, (333, 391, 393, 395, 397, 399))),
    # Fig. 4: the case is not named
    Panel("4", "velocity",
          Axis("Time (s)", ("80", "81", "82", "83", "84", "85", "86", "87"),
               (447, 449, 451, 453, 455, 457, 459, 461, 463), scored=False),
          Axis("Velocity (m/s)", _SHOCK, _SHOCK_LINES)),
    Panel("4", "acceleration",
          Axis("Time (s)", ("81", "82", "83", "84", "85"), (447, 463, 465, 467, 475, 477), scored=False),
          Axis("Acceleration (m/s2)", _SHOCK, _SHOCK_LINES)),
    # Fig. 5: neither F nor x0 is given
    Panel("5", "a", Axis("Displacement (m)", ("-5", "0", "5"), (505, 507, 513)),
          Axis("Velocity (m/s)", ("-1.5", "-1", "-0.5", "0", "0.5", "1", "1.5"), (479, 483, 489, 499, 503, 513))),
    Panel("5", "b", Axis("Displacement (m)", _UNIT_HALVES, (509, 517, 519, 521, 523)),
          Axis("Velocity (m/s)", ("-1", "-0.8", "-0.6", "-0.4", "-0.2", "0", "0.2", "0.4", "0.6", "0.8", "1"),
               (483, 487, 491, 499, 501, 509, 513))),
    Panel("5", "c", Axis("Displacement (m)", _UNIT_HALVES, (525, 527, 529, 543, 545)),
          Axis("Velocity (m/s)", ("-3", "-2", "-1", "0", "1", "2", "3", "4"), (481, 485, 511, 525))),
)


#: the period Sec. 4 prints for both Fig. 3 cases, s: "the period for both motions are identical as 6.2832 s"
FIG3_PERIOD = 6.2832
#: the spring constant of each Fig. 5 panel, from the paper's panel captions "(a) K=0.1" etc., N/m
FIG5_PANEL_K: dict[str, float] = {"a": 0.1, "b": 1.0, "c": 10.0}


def panel(figure: str, name: str) -> Panel:
    """The panel ``name`` of Fig. ``figure``."""
    for p in PANELS:
        if p.figure == figure and p.name == name:
            return p
    raise KeyError(f"Fig. {figure} has no panel {name!r}")


def panels_of(figure: str) -> tuple[Panel, ...]:
    """The panels of Fig. ``figure``, in the order above."""
    return tuple(p for p in PANELS if p.figure == figure)
