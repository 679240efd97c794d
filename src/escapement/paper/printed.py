"""The paper's closed forms, as printed (Mao, Fu & Li 2013, Sec. 3.3-3.4), ``a1 .. a4`` signed (``a1 < 0 < a3``);
where the text is garbled, the docstring states the reading. ``v1`` is the velocity just before the impact at a1,
``v1p = (1 - b) v1`` just after it, ``v2`` at a2, ``v4`` and ``v4p`` before and after the impact at a3, ``v5`` at a4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..model.parameters import Parameters
from .corrected import _sqrt, cycle_velocities

__all__ = ["Symbols", "symbols_of", "v5_14", "zone_left_time_22e", "period_terms_23", "phase_jump_24",
           "phase_jump_24_closed", "zone_change_25", "step_velocities", "poincare_map_16", "poincare_map_17",
           "fixed_point_19", "map_derivative_20", "multiplier_21", "multiplier_21_of", "step_times_22", "period_23"]


@dataclass(frozen=True)
class Symbols:
    """The numbers put in for a printed formula's symbols, unchecked: ``a1`` .. ``a4`` (m), ``f`` (m s-2), ``w``."""

    a1: float
    a2: float
    a3: float
    a4: float
    f: float
    w: float

    @property
    def c(self) -> float:
        """``f / w**2``, the centre of the impulse zone's motion."""
        return self.f / self.w**2


def symbols_of(p: Parameters) -> Symbols:
    """The model's signed positions, ``f`` and ``w``: the reading under which :mod:`.corrected` derives."""
    if not isinstance(p, Parameters):
        raise TypeError(f"p = {p!r} must be a Parameters")
    return Symbols(p.a1, p.a2, p.a3, p.a4, p.f, p.omega)


def v5_14(v4p: float, s: Symbols) -> float:
    """Eq. (14) as printed: ``v5 = -sqrt(v4p**2 + (a3**2 - a4**2) w**2 - 2 (a3 - a4) f)``."""
    return -_sqrt(v4p**2 + (s.a3**2 - s.a4**2) * s.w**2 - 2 * (s.a3 - s.a4) * s.f)


def zone_left_time_22e(v4p: float, s: Symbols) -> float:
    """Eq. (22e) as printed: ``t5 - t4 = [atan(v4p / (w (a3 + c))) - acos((a4 + c) / h3)] / w``,
    ``h3 = sqrt((a3 + c)**2 + (v4p/w)**2)``, ``c = f/w**2`` (NaN where the arccosine is undefined)."""
    c = s.c
    h3 = math.hypot(s.a3 + c, v4p / s.w)
    return (math.atan(v4p / (s.w * (s.a3 + c))) - _acos((s.a4 + c) / h3)) / s.w


def period_terms_23(velocities: dict[str, float], s: Symbols) -> dict[str, float]:
    """The terms of Eq. (23) as printed, over ``w``, grouped by the step whose time they give."""
    w, c = s.w, s.c
    r1 = math.hypot(s.a1 - c, velocities["v1p"] / w)
    h2 = math.hypot(s.a2, velocities["v2"] / w)
    r3 = math.hypot(s.a3 + c, velocities["v4p"] / w)
    h5 = math.hypot(s.a4, velocities["v5"] / w)
    return {
        "zone_right": (_acos((c - s.a2) / r1) - _acos((c - s.a1) / r1)) / w,
        "a2_to_a3": (_acos(s.a2 / h2) + _acos(s.a3 / h2)) / w,
        "zone_left": (_acos((c + s.a4) / r3) - _acos((c + s.a3) / r3)) / w,
        "a4_to_a1": (_acos(s.a4 / h5) + _acos(s.a1 / h5)) / w,
    }


def phase_jump_24(v_before: float, v_after: float, s: Symbols) -> float:
    """Eq. (24), first form: ``dT1 = [atan(v_after / (a1 w)) - atan(v_before / (a1 w))] / w``."""
    return (math.atan(v_after / (s.a1 * s.w)) - math.atan(v_before / (s.a1 * s.w))) / s.w


def phase_jump_24_closed(v: float, b: float, s: Symbols) -> float:
    """Eq. (24), second form, with ``v = x1+`` as printed (the velocity after the impact)."""
    return -math.atan(s.a1 * s.w * b * v / (s.a1**2 * s.w**2 + (1 - b) * v**2)) / s.w


def zone_change_25(v1p: float, s: Symbols) -> float:
    """Eq. (25) as printed, with ``v1p`` the velocity entering the zone (the paper's ``x1+``)."""
    w, c = s.w, s.c
    r1 = math.hypot(s.a1 - c, v1p / w)
    zone_time = (_acos((c - s.a2) / r1) - _acos((c - s.a1) / r1)) / w
    w2_exit = _sqrt((v1p / w) ** 2 + s.a1**2 - s.a2**2 - 2 * (s.a1 - s.a2) * s.f / w**2)
    return zone_time - (math.atan(w2_exit / s.a2) - math.atan(v1p / (s.a1 * w))) / w


def _acos(value: float) -> float:
    return math.acos(value) if -1.0 <= value <= 1.0 else math.nan


def step_velocities(v1: float, p: Parameters, first: Symbols | None = None, second: Symbols | None = None
                    ) -> dict[str, float]:
    """Eqs. (10)-(15) as printed from ``v1``, the symbols of each half period ``first``, ``second`` (or the model's)."""
    s1, s2, b = first or symbols_of(p), second or symbols_of(p), p.b
    w2 = s1.w**2
    v1p = (1 - b) * v1  # (10)
    v2 = _sqrt(v1p**2 + (s1.a1**2 - s1.a2**2) * w2 - 2 * (s1.a1 - s1.a2) * s1.f)  # (11)
    v4 = -_sqrt(v2**2 + (s1.a2**2 - s2.a3**2) * w2)  # (12)
    v4p = (1 - b) * v4  # (13)
    v5 = v5_14(v4p, s2)  # (14) as printed
    v1_next = _sqrt(v5**2 + (s2.a4**2 - s2.a1**2) * w2)  # (15)
    return {"v1p": v1p, "v2": v2, "v4": v4, "v4p": v4p, "v5": v5, "v1_next": v1_next}


def poincare_map_16(v1: float, p: Parameters, s: Symbols | None = None) -> float:
    """Eq. (16): the Poincare map for a general geometry, the symbols ``s`` (unless given, :func:`symbols_of`)."""
    b, s = p.b, s or symbols_of(p)
    return _sqrt(
        (1 - b) ** 4 * v1**2
        + (b**2 - 2 * b) * s.w**2 * (s.a1**2 - s.a3**2)
        - 2 * (1 - b) ** 2 * (s.a1 - s.a2) * s.f
        + 2 * (s.a3 - s.a4) * s.f
    )


def poincare_map_17(v1: float, p: Parameters) -> float:
    """Eq. (17): the map for the symmetric geometry a1 = -a3, a2 = -a4."""
    return _sqrt((1 - p.b) ** 4 * v1**2 + 2 * (p.b**2 - 2 * p.b + 2) * (p.a2 - p.a1) * p.f)


def fixed_point_19(p: Parameters) -> float:
    """Eq. (19): the fixed point of Eq. (17)."""
    return _sqrt(2 * (p.a2 - p.a1) * p.f / (2 * p.b - p.b**2))


def map_derivative_20(v1: float, p: Parameters) -> float:
    """Eq. (20): the derivative of Eq. (17)."""
    return (1 - p.b) ** 4 * v1 / poincare_map_17(v1, p)


def multiplier_21(p: Parameters) -> float:
    """Eq. (21): the non-trivial multiplier mu_2 = (1 - b)**4 (:func:`multiplier_21_of`)."""
    return multiplier_21_of(p.b)


def multiplier_21_of(b: float) -> float:
    """Eq. (21) at ``b``: ``(1 - b)**4`` correctly rounded from the exact rational power, the same float on every
    machine (a ``pow`` rounds its last bit as the platform does; the stability map shows differences to 1e-16).

    >>> multiplier_21_of(0.1)
    0.6561
    """
    return float(Fraction(1 - b) ** 4)


def step_times_22(v1: float, p: Parameters, left_amplitude: float) -> dict[str, float]:
    """Eqs. (22a)-(22e) as printed: the durations of steps 1-7 of one cycle from the left turning point at
    ``-left_amplitude``, the velocities from the energy balance (only the times under test); the text read as below."""
    w, c, vel = p.omega, p.zone_offset, cycle_velocities(v1, p)
    v1p, v2, v4p = vel["v1p"], vel["v2"], vel["v4p"]
    r1 = math.hypot(v1p / w, p.a1 - c)
    return {
        "22a": math.acos(-p.a1 / left_amplitude) / w,
        "22b": (math.atan(v1p / (w * (p.a1 - c))) + math.acos((c - p.a2) / r1)) / w,
        "22c": math.atan(v2 / (w * p.a2)) / w,
        "22d": math.acos(p.a3 / math.hypot(p.a2, v2 / w)) / w,
        "22e": zone_left_time_22e(v4p, symbols_of(p)),
    }


def period_23(v1: float, p: Parameters) -> float:
    """Eq. (23) as printed: the period of the cycle from ``v1`` at a1, the velocities from the energy balance."""
    return math.fsum(period_terms_23(cycle_velocities(v1, p), symbols_of(p)).values())

