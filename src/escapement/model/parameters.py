"""Model parameters of the escapement oscillator, validated when they are made.

The model (Mao, Fu & Li 2013, Sec. 2-3 and Appendix A): a mass ``M`` on a spring
``K`` moves freely, ``x'' + omega**2 x = 0``, except at the impacts and over the impulse
zones that :mod:`escapement.model.automaton` defines.

Signs: ``a1 < 0 < a3`` (the jump set ``x * xdot < 0``); the symmetric default is
``a3 = -a1`` and ``a4 = -a2``.

The rules on the parameters are written once, in :func:`rules`, on NumPy arrays: the scalar
:class:`Parameters` and the ensemble solver (one row per trajectory) apply the same ones.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from .quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS

__all__ = ["ParameterError", "Parameters", "check_initial_state", "real_array", "validate_arrays", "rules"]


class ParameterError(ValueError):
    """An input value is outside its allowed range; the message names it.

    ``row`` is the index of the offending trajectory when the input is an array of them.
    """

    def __init__(self, name: str, value: object, requirement: str, row: int | None = None) -> None:
        self.name = name
        self.value = value
        self.requirement = requirement
        self.row = row
        where = "" if row is None else f"row {row}: "
        super().__init__(f"{where}{name} = {value!r} is invalid: {name} must be {requirement}")


def _unit(name: str) -> str:
    return PARAMETERS[name].unit_label


def rules(v: Mapping[str, np.ndarray]):
    """Each rule as ``(name, holds, requirement)``, in the order they are checked.

    ``v`` maps every model key to a float64 array (all of one shape); ``holds`` is a boolean
    array of that shape; ``requirement`` may name other parameters as ``{a1}`` (filled with the
    offending row's values).
    """
    with np.errstate(all="ignore"):
        yield "M", v["M"] > 0, f"> 0 ({_unit('M')})"
        yield "K", v["K"] > 0, f"> 0 ({_unit('K')})"
        yield "F", v["F"] >= 0, f">= 0 ({_unit('F')})"
        yield "b", (v["b"] > 0) & (v["b"] < 2), "in the open interval (0, 2)"
        yield "a2", v["a1"] < v["a2"], "> a1 = {a1!r} (m)"
        yield "a4", v["a4"] < v["a3"], "< a3 = {a3!r} (m)"
        ratio = v["K"] / v["M"]
        yield "K", (ratio > 0) & np.isfinite(ratio), "such that K/M is a positive finite number"
        yield "F", np.isfinite(v["F"] / v["M"]), "such that F/M is finite"
        for name in ("a1", "a2", "a3", "a4"):
            yield name, np.isfinite(v[name] * v[name] * v["K"]), f"small enough that K * {name}**2 is finite"


def real_array(name: str, value: object) -> np.ndarray:
    """``value`` (a real number or an array of them) as float64, or raise naming ``name``."""
    if isinstance(value, bool | str | bytes):
        raise ParameterError(name, value, "a real number")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as err:
        raise ParameterError(name, value, "a real number") from err
    if array.dtype.kind not in "iuf":
        raise ParameterError(name, value, "a real number")
    array = array.astype(np.float64)
    bad = ~np.isfinite(array)
    if bad.any():
        row = int(np.flatnonzero(bad.ravel())[0]) if array.ndim else None
        raise ParameterError(name, float(array.ravel()[row or 0]), "finite", row=row)
    return array


def validate_arrays(values: Mapping[str, object], single: bool = False) -> dict[str, np.ndarray]:
    """Check every model key (``a3``, ``a4`` None: the symmetric default) and return float64
    arrays broadcast to one shape; the first violation raises, naming the row for arrays."""
    for key in ("M", "K", "F", "b", "a1", "a2"):
        if values.get(key) is None:
            raise ParameterError(key, None, "given")
    checked = {name: real_array(name, values[name]) for name in ("M", "K", "F", "b", "a1", "a2")}
    if single:
        for name, array in checked.items():
            if array.ndim:
                raise ParameterError(name, values[name], "a single real number (use the ensemble for arrays)")
    for name, mirror in (("a3", "a1"), ("a4", "a2")):
        checked[name] = -checked[mirror] if values.get(name) is None else real_array(name, values[name])
        if single and checked[name].ndim:
            raise ParameterError(name, values[name], "a single real number (use the ensemble for arrays)")
    shaped = dict(zip(MODEL_KEYS, np.broadcast_arrays(*(checked[k] for k in MODEL_KEYS))))
    scalar = all(a.ndim == 0 for a in shaped.values())
    for name, holds, requirement in rules(shaped):
        if not np.all(holds):
            row = None if scalar else int(np.flatnonzero(~np.ravel(holds))[0])
            at = {k: float(np.ravel(a)[row or 0]) for k, a in shaped.items()}
            raise ParameterError(name, at[name], requirement.format(**at), row=row)
    return shaped


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
        checked = validate_arrays({name: getattr(self, name) for name in MODEL_KEYS}, single=True)
        for name, value in checked.items():
            object.__setattr__(self, name, float(value))

    @classmethod
    def from_mapping(cls, values: Mapping[str, object]) -> Parameters:
        """From a mapping with the model keys (others are ignored); a missing key is named."""
        for key in ("M", "K", "F", "b", "a1", "a2"):
            if key not in values:
                raise ParameterError(key, None, "given (it is missing)")
        return cls(**{k: values[k] for k in MODEL_KEYS if values.get(k) is not None})

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
        return {n: getattr(self, n) for n in MODEL_KEYS}


def check_initial_state(x0: object, v0: object) -> tuple[float, float]:
    """Validate the initial displacement and velocity; return them as floats."""
    values = []
    for name, value in zip(INITIAL_STATE, (x0, v0)):
        array = real_array(name, value)
        if array.ndim:
            raise ParameterError(name, value, "a single real number")
        values.append(float(array))
    return values[0], values[1]
