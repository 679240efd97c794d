"""The paper's printed formulas under each convention the paper itself uses (:data:`AXES`): positions as magnitudes
(Sec. 4) or signed (Eqs. (9)-(22a)), the force ``f`` or ``sigma f`` (Eq. (2)), the second half period as written or
mirrored, and the velocity after or before an impact; each combination is a reading, tried by :func:`try_readings`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from ..model.parameters import Parameters
from . import printed as pe

__all__ = ["AS_READ", "AXES", "Reading", "Trial", "departure", "readings", "symbols", "second_half_trials",
           "try_readings"]

#: every convention the paper uses, by axis: the first of each is the reading the register adopts
AXES: dict[str, tuple[str, ...]] = {
    "positions": ("signed", "magnitudes"),  # Eqs. (9)-(22a) against Sec. 4
    "force": ("f", "sigma f"),  # Eqs. (11)-(16) against Eq. (2), sigma = -1 in the second half
    "half": ("as written", "mirrored"),  # the second half period as printed, or as the mirror of the first
    "velocity": ("after", "before"),  # the velocity after or before the impact, where a formula takes one
}


@dataclass(frozen=True)
class Reading:
    """One choice per axis of :data:`AXES`."""

    positions: str
    force: str
    half: str
    velocity: str

    def __post_init__(self) -> None:
        for axis, choices in AXES.items():
            if getattr(self, axis) not in choices:
                raise ValueError(f"{axis} = {getattr(self, axis)!r} must be one of {', '.join(choices)}")

    def __str__(self) -> str:
        return ", ".join(f"{axis} {getattr(self, axis)}" for axis in AXES)


AS_READ = Reading(*(choices[0] for choices in AXES.values()))


def readings(axes: tuple[str, ...]) -> list[Reading]:
    """Every reading that varies the named ``axes`` (the others as read), the adopted one first."""
    if any(a not in AXES for a in axes):
        raise ValueError(f"axes = {axes!r} must name axes among {', '.join(AXES)}")
    choices = [AXES[a] if a in axes else (AXES[a][0],) for a in AXES]
    return [Reading(*combination) for combination in itertools.product(*choices)]


def symbols(p: Parameters, reading: Reading, second_half: bool) -> tuple[pe.Symbols, float]:
    """The numbers for a printed formula's symbols under ``reading``, and the sign of its velocities (-1: mirrored)."""
    if not isinstance(second_half, bool):
        raise ValueError(f"second_half = {second_half!r} must be True or False")
    positions = [p.a1, p.a2, p.a3, p.a4]
    f, sign = p.f, 1.0
    if second_half and reading.half == "mirrored":
        positions, sign = [-a for a in positions], -1.0
    if second_half and reading.force == "sigma f":
        f = -f
    if reading.positions == "magnitudes":
        positions = [abs(a) for a in positions]
    return pe.Symbols(*positions, f, p.omega), sign


@dataclass(frozen=True)
class Trial:
    """A printed formula under one reading: its value and whether it reproduces the simulated one."""

    reading: Reading
    value: float
    relative_difference: float
    reproduces: bool


def try_readings(formula: Callable[[Reading], float], simulated: float, tolerance: float,
                 axes: tuple[str, ...]) -> list[Trial]:
    """``formula(reading)`` under each reading of ``axes``, and whether it is within ``tolerance`` of ``simulated``."""
    if not (isinstance(tolerance, (int, float)) and tolerance >= 0):
        raise ValueError(f"tolerance = {tolerance!r} must be a number >= 0")
    if not (isinstance(simulated, float) and math.isfinite(simulated) and simulated != 0.0):
        raise ValueError(f"simulated = {simulated!r} must be a finite non-zero float")
    trials = []
    for reading in readings(axes):
        value = float(formula(reading))
        difference = abs(value - simulated) / abs(simulated) if math.isfinite(value) else math.nan
        trials.append(Trial(reading, value, difference, bool(difference <= tolerance)))
    return trials


def departure(reading: Reading) -> str:
    """The reading's choices that differ from :data:`AS_READ` (``as read`` if none)."""
    changed = [getattr(reading, a) for a in AXES if getattr(reading, a) != getattr(AS_READ, a)]
    return " + ".join(changed) if changed else "as read"


def second_half_trials(p: Parameters, velocity: Mapping[str, float], simulated: float, tolerance: float,
                       formula: Callable[[float, pe.Symbols], float]) -> list[Trial]:
    """A formula of the second half period, ``formula(v_at_a3, symbols)``, under every reading."""
    def evaluate(reading: Reading) -> float:
        s, sign = symbols(p, reading, second_half=True)
        return formula(sign * velocity["v4p" if reading.velocity == "after" else "v4"], s)

    return try_readings(evaluate, simulated, tolerance, ("positions", "force", "half", "velocity"))
