"""Model parameters of the escapement oscillator, validated when they are made.

The model (Mao, Fu & Li 2013, Sec. 2-3 and Appendix A): a mass ``M`` on a spring
``K`` moves freely, ``x'' + omega**2 x = 0``, except

* impacts: on reaching ``x = a1`` moving right and ``x = a3`` moving left the
  velocity jumps, ``v+ = (1 - b) v-``;
* impulse zones: after the impact at ``a1``, while ``x`` runs from ``a1`` to
  ``a2`` moving right, ``x'' + omega**2 x = +f``; after the impact at ``a3``,
  while ``x`` runs from ``a3`` to ``a4`` moving left, ``x'' + omega**2 x = -f``;
  ``f = F / M``.

Signs: ``a1 < 0 < a3`` (the jump set ``x * xdot < 0``); the symmetric default is
``a3 = -a1`` and ``a4 = -a2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real

__all__ = ["ParameterError", "Parameters", "check_initial_state"]


class ParameterError(ValueError):
    """An input value is outside its allowed range; the message names it."""

    def __init__(self, name: str, value: object, requirement: str) -> None:
        self.name = name
        self.value = value
        self.requirement = requirement
        super().__init__(f"{name} = {value!r} is invalid: {name} must be {requirement}")


def _real(name: str, value: object) -> float:
    """Return ``value`` as a finite float, or raise naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ParameterError(name, value, "a real number")
    as_float = float(value)
    if not math.isfinite(as_float):
        raise ParameterError(name, value, "finite")
    return as_float


@dataclass(frozen=True)
class Parameters:
    """Physical parameters in SI units: kg, N/m, N, 1, m.

    ``a3`` and ``a4`` default to the symmetric geometry ``a3 = -a1``,
    ``a4 = -a2``; give them to study the paper's asymmetric map, Eq. (16).
    """

    M: float
    K: float
    F: float
    b: float
    a1: float
    a2: float
    a3: float | None = None
    a4: float | None = None

    def __post_init__(self) -> None:
        checked = {name: _real(name, getattr(self, name)) for name in ("M", "K", "F", "b", "a1", "a2")}
        checked["a3"] = -checked["a1"] if self.a3 is None else _real("a3", self.a3)
        checked["a4"] = -checked["a2"] if self.a4 is None else _real("a4", self.a4)
        for name, value in checked.items():
            object.__setattr__(self, name, value)
        if not checked["M"] > 0:
            raise ParameterError("M", self.M, "> 0 (kg)")
        if not checked["K"] > 0:
            raise ParameterError("K", self.K, "> 0 (N/m)")
        if not checked["F"] >= 0:
            raise ParameterError("F", self.F, ">= 0 (N)")
        if not 0 < checked["b"] < 2:
            raise ParameterError("b", self.b, "in the open interval (0, 2)")
        if not checked["a1"] < checked["a2"]:
            raise ParameterError("a2", self.a2, f"> a1 = {self.a1!r} (m)")
        if not checked["a4"] < checked["a3"]:
            raise ParameterError("a4", self.a4, f"< a3 = {self.a3!r} (m)")
        if checked["K"] / checked["M"] == 0 or not math.isfinite(checked["K"] / checked["M"]):
            raise ParameterError("K", self.K, "such that K/M is a positive finite number")
        if not math.isfinite(checked["F"] / checked["M"]):
            raise ParameterError("F", self.F, "such that F/M is finite")
        for name in ("a1", "a2", "a3", "a4"):
            if not math.isfinite(checked[name] * checked[name] * checked["K"]):
                raise ParameterError(name, checked[name], "small enough that K * " + name + "**2 is finite")

    @property
    def omega(self) -> float:
        """Natural angular frequency sqrt(K/M), rad/s."""
        return math.sqrt(self.K / self.M)

    @property
    def omega2(self) -> float:
        """omega**2 = K/M, 1/s**2."""
        return self.K / self.M

    @property
    def f(self) -> float:
        """Force per unit mass F/M, m/s**2."""
        return self.F / self.M

    @property
    def zone_offset(self) -> float:
        """f / omega**2 = F/K: the shift of the centre of oscillation inside an impulse zone, m."""
        return self.F / self.K

    @property
    def natural_period(self) -> float:
        """2 pi / omega, s."""
        return 2.0 * math.pi / self.omega

    @property
    def symmetric(self) -> bool:
        """True for the paper's symmetric geometry a3 = -a1, a4 = -a2."""
        return self.a3 == -self.a1 and self.a4 == -self.a2

    def as_dict(self) -> dict[str, float]:
        """Every parameter by the paper's symbol."""
        return {n: getattr(self, n) for n in ("M", "K", "F", "b", "a1", "a2", "a3", "a4")}


def check_initial_state(x0: object, v0: object) -> tuple[float, float]:
    """Validate the initial displacement and velocity; return them as floats."""
    return _real("x0", x0), _real("v0", v0)
