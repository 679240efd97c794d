"""The settings of each scene, checked once: frozen dataclasses made from a flat mapping of the configuration.

Each ``from_mapping`` checks every key before any work, refusing with a ParameterError naming the key and its value.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..model.parameters import ParameterError, Parameters, check_initial_state
from ..model.printing import texts
from ..studies.readings import AMPLITUDES as DEFINED_AMPLITUDES

__all__ = ["KINDS", "REPLICATION", "EscapementErrorScene", "ExistenceMapScene", "Kind", "LongRunScene",
           "PhaseScene", "PoincareScene", "Release", "ShockScene", "SizeError", "StabilityMapScene", "Study",
           "as_typed", "positive_int", "time_window"]

REPLICATION = "replication"  #: the study of the paper's scenes (the others are the user's own, by their name)


@dataclass(frozen=True)
class Kind:
    """A kind of scene: its block, its name in files, what it shows, the paper's figure, the keys it ignores."""

    block: str
    name: str
    shows: str
    figure: str | None = None
    label: str = "{}"  #: how a scene's label reads in a title
    ignores: tuple[tuple[str, str], ...] = ()  #: (model key, why the kind's data do not depend on it)

    @property
    def ignored(self) -> tuple[str, ...]:
        return tuple(key for key, _ in self.ignores)

    def why(self, keys) -> str:
        """Why the kind's data do not depend on ``keys``, each reason once, in the kind's order."""
        return "; ".join(dict.fromkeys(reason for key, reason in self.ignores if key in keys))


#: every kind of scene a study may hold, by its configuration block
KINDS = {k.block: k for k in (
    Kind("fig3", "poincare_map", "Poincaré map", "Fig. 3", "case {}"),
    Kind("fig4", "shock_detail", "shock detail", "Fig. 4"),
    Kind("fig5", "phase_diagrams", "phase diagram", "Fig. 5", "K = {} N/m"),
    Kind("escapement_error", "escapement_error", "escapement error: rate against amplitude",
         ignores=(("F", "F is its axis"),
                  *((key, "its zones set a1 and a2, and a3 = -a1, a4 = -a2") for key in ("a1", "a2", "a3", "a4")))),
    Kind("stability_map", "stability_map", "stability and existence map over (b, F)",
         ignores=(("b", "b is its axis"), ("F", "F is its axis"))),
    Kind("existence_map", "existence_map", "existence map of the limit cycle over (a3, F)",
         ignores=(("a3", "a3 is its axis"), ("F", "F is its axis"),
                  ("M", "its outcome does not depend on M (the mass sets only the time scale, sqrt(M/K))"))),
)}


@dataclass(frozen=True)
class Study:
    """Where a scene belongs: the study, the scene's label within its kind, and what a user's own study changes."""

    name: str
    label: str = ""
    changes: str = ""

    def title(self, block: str) -> str:
        """The dataset's title: what it shows, and the paper's figure for the replication's scenes."""
        kind = KINDS[block]
        label = f", {kind.label.format(self.label)}" if self.label else ""
        where = (f" ({kind.figure} of Mao, Fu & Li 2013)" if self.name == REPLICATION and kind.figure
                 else f", study {self.name}")
        return f"{kind.shows[:1].upper()}{kind.shows[1:]} of the escapement model{label}{where}"

    def attributes(self) -> dict[str, str]:
        """The global attributes that place the dataset: ``study``, and ``study_changes`` for a user's own study."""
        return {"study": self.name, **({"study_changes": self.changes} if self.changes else {})}

    @classmethod
    def from_mapping(cls, values: Mapping) -> Study:
        return cls(str(values.get("study", REPLICATION)), str(values.get("label", "")), str(values.get("changes", "")))


def positive_int(name: str, value: object, most: int, least: int = 1) -> int:
    """``value`` as an int if it is an integer (not a bool) in ``[least, most]``; else ParameterError."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or not least <= value <= most:
        raise ParameterError(name, value, f"an integer in [{least:_}, {most:_}]")
    return int(value)


def _real(value: object) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)


def time_window(name: str, window: object) -> tuple[float, float]:
    """The window ``[start, end]`` (s) with ``0 <= start < end < inf``; else ParameterError naming ``name``."""
    if isinstance(window, str | bytes | Mapping) or not hasattr(window, "__len__") or len(window) != 2 \
            or not all(_real(w) for w in window):  # type: ignore[union-attr]
        raise ParameterError(name, window, "a pair [start, end] of times in s")
    lo, hi = (float(w) for w in window)  # type: ignore[union-attr]
    if not 0 <= lo < hi < np.inf:
        raise ParameterError(name, window, "a pair [start, end] with 0 <= start < end (s)")
    return lo, hi


#: the bounds [least, most] of each count a scene takes, by ``block.key``, as the configuration's schema states them
COUNTS = {
    "fig3.n_cycles": (1, 1_000_000),
    "fig4.samples_per_second": (1, 100_000),
    "fig5.n_cycles": (1, 10_000),
    "fig5.samples_per_period": (8, 100_000),  # the impulse zones resolved (tests/pipeline/test_fig5_sampling.py)
    "escapement_error.F.n": (1, 1_000),
    "stability_map.b.n": (1, 2_000),
    "stability_map.F.n": (1, 2_000),
    "existence_map.a3.n": (1, 400),
    "existence_map.F.n": (1, 400),
    "existence_map.n_cycles": (2, 10_000),  # convergence compares the last two cycles
    "long_run.n_cycles": (10, 100_000_000),
    "long_run.ivp_cycles": (10, 20_000),
}


def _count(key: str, value: object) -> int:
    """``value`` within the bounds of ``key`` (``block.key``) in :data:`COUNTS`, named without its block."""
    least, most = COUNTS[key]
    return positive_int(key.split(".", 1)[1], value, most, least)


def _axis(block: str, name: str, axis: object) -> tuple[float, float, int]:
    """``(start, stop, n)`` of the axis ``name`` of ``block``: finite ``start < stop`` (or one point), ``n`` counted."""
    if not isinstance(axis, Mapping) or set(axis) != {"start", "stop", "n"} or not _real(axis["start"]) \
            or not _real(axis["stop"]):
        raise ParameterError(name, axis, "an axis {start, stop, n}: two numbers and a count")
    start, stop, n = float(axis["start"]), float(axis["stop"]), _count(f"{block}.{name}.n", axis["n"])
    if not (np.isfinite(start) and np.isfinite(stop) and (start < stop or n == 1)):
        raise ParameterError(name, dict(axis), "an axis {start, stop, n} with finite start < stop")
    return start, stop, n


AMPLITUDES = tuple(DEFINED_AMPLITUDES)  #: the definitions of Fig. 3's amplitude, by the variable that holds it
MAX_SAMPLES = 10_000_000  #: the most samples a sampled time series may hold (three float64 arrays: 240 MB)


def as_typed(value: object) -> str:
    """A value as a configuration gives it: a float by its shortest form (``2`` for 2.0), a list item by item."""
    if isinstance(value, list | tuple):
        return "[" + ", ".join(as_typed(v) for v in value) + "]"
    return format(value, "g") if isinstance(value, float) and float(format(value, "g")) == value else str(value)


class SizeError(ValueError):
    """A scene larger than one job holds and that is not split: the keys that size it, what they ask beside the most."""

    def __init__(self, keys: Mapping[str, object], asked: float, most: float, what: str, why: str) -> None:
        first, *rest = (f"{key} = {as_typed(value)}" for key, value in keys.items())
        said = first + (f" with {' and '.join(rest)}" if rest else "")
        short = [re.sub(r"e\+0*", "e", text) for text in texts([asked, most], 3)]  # 2e10, 1.2e8
        super().__init__(f"{said}: {short[0]} {what}, at most {short[1]} ({why})")


def _samples(keys: Mapping[str, object], samples: float) -> None:
    """SizeError if a run's ``samples`` (as ``keys`` ask for them) exceed :data:`MAX_SAMPLES`."""
    if samples > MAX_SAMPLES:
        raise SizeError(keys, samples, MAX_SAMPLES, "samples of one trajectory", "one trajectory cannot be split")


@dataclass(frozen=True)
class Release:
    """The state at ``t = 0+`` (after any jump, as the paper's Eq. (2) writes it): displacement and velocity."""

    x0: float
    v0: float = 0.0

    @classmethod
    def from_mapping(cls, values: Mapping) -> Release:
        if "x0" not in values:
            raise ParameterError("x0", None, "given (it is missing)")
        return cls(*check_initial_state(values["x0"], values.get("v0", 0.0)))


@dataclass(frozen=True)
class PoincareScene:
    """A Poincare map (Fig. 3's kind): one release run ``n_cycles`` cycles, its amplitude by ``amplitude``."""

    study: Study
    params: Parameters
    release: Release
    n_cycles: int
    amplitude: str

    @classmethod
    def from_mapping(cls, values: Mapping) -> PoincareScene:
        if values["amplitude"] not in AMPLITUDES:
            raise ParameterError("amplitude", values["amplitude"], f"one of {', '.join(AMPLITUDES)}")
        return cls(Study.from_mapping(values), Parameters.from_mapping(values), Release.from_mapping(values),
                   _count("fig3.n_cycles", values["n_cycles"]), str(values["amplitude"]))


@dataclass(frozen=True)
class ShockScene:
    """A shock detail (Fig. 4's kind): the motion sampled over two windows, velocity and acceleration."""

    study: Study
    params: Parameters
    release: Release
    velocity_window: tuple[float, float]
    acceleration_window: tuple[float, float]
    samples_per_second: int

    @classmethod
    def from_mapping(cls, values: Mapping) -> ShockScene:
        windows = {name: time_window(name, values[name]) for name in ("velocity_window", "acceleration_window")}
        rate = _count("fig4.samples_per_second", values["samples_per_second"])
        ends = [end for window in windows.values() for end in window]  # sampled over the union of the windows
        _samples({f"fig4.{k}": values[k] for k in (*windows, "samples_per_second")}, (max(ends) - min(ends)) * rate)
        return cls(Study.from_mapping(values), Parameters.from_mapping(values), Release.from_mapping(values),
                   windows["velocity_window"], windows["acceleration_window"], rate)


@dataclass(frozen=True)
class PhaseScene:
    """One phase diagram (a panel of Fig. 5's kind): a release run ``n_cycles`` cycles, sampled uniformly."""

    study: Study
    params: Parameters
    release: Release
    n_cycles: int
    samples_per_period: int

    @classmethod
    def from_mapping(cls, values: Mapping) -> PhaseScene:
        n_cycles = _count("fig5.n_cycles", values["n_cycles"])
        per_period = _count("fig5.samples_per_period", values["samples_per_period"])
        _samples({"fig5.n_cycles": n_cycles, "fig5.samples_per_period": per_period}, n_cycles * per_period)
        return cls(Study.from_mapping(values), Parameters.from_mapping(values), Release.from_mapping(values),
                   n_cycles, per_period)


@dataclass(frozen=True)
class EscapementErrorScene:
    """The limit cycle's rate for ``forces`` (spaced geometrically) in each impulse zone ``[a1, a2]``, mirrored."""

    study: Study
    params: Parameters
    forces: tuple[float, ...]
    zones: tuple[tuple[str, float, float], ...]

    @classmethod
    def from_mapping(cls, values: Mapping) -> EscapementErrorScene:
        start, stop, n = _axis("escapement_error", "F", values["F"])
        if start <= 0:
            raise ParameterError("F.start", start, "a number > 0 (N): the forces are spaced geometrically")
        forces = tuple(start * (stop / start) ** (i / (n - 1)) if n > 1 else start for i in range(n))
        zones = []
        for name, (a1, a2) in values["zones"].items():
            Parameters(**{**_model(values), "F": 0.0, "a1": a1, "a2": a2, "a3": -a1, "a4": -a2})  # a1 < a2 checked
            zones.append((str(name), float(a1), float(a2)))
        return cls(Study.from_mapping(values), Parameters.from_mapping({**values, "F": forces[0]}), forces,
                   tuple(zones))


def _model(values: Mapping) -> dict:
    return {k: values[k] for k in ("M", "K", "b", "a1", "a2", "a3", "a4") if values.get(k) is not None}


def _corners(values: Mapping, **axes: tuple[float, ...]) -> Parameters:
    """The model at the first corner of the ``axes``, every corner checked: every cell's is valid if theirs are."""
    for corner in itertools.product(*((v[0], v[-1]) for v in axes.values())):
        Parameters(**{**_model(values), **dict(zip(axes, corner))})
    return Parameters.from_mapping({**values, **{name: v[0] for name, v in axes.items()}})


def cell_centres(start: float, stop: float, n: int) -> tuple[float, ...]:
    """The ``n`` cell centres of ``(start, stop)``."""
    step = (stop - start) / n
    return tuple(start + (i + 0.5) * step for i in range(n))


@dataclass(frozen=True)
class StabilityMapScene:
    """The stability map over ``(b, F)``: b at the cell centres of its axis, F from start to stop (ends included)."""

    study: Study
    params: Parameters
    b_values: tuple[float, ...]
    F_values: tuple[float, ...]

    @classmethod
    def from_mapping(cls, values: Mapping) -> StabilityMapScene:
        b_values = cell_centres(*_axis("stability_map", "b", values["b"]))
        start, stop, n = _axis("stability_map", "F", values["F"])
        F_values = tuple(start + (stop - start) * j / max(n - 1, 1) for j in range(n))
        return cls(Study.from_mapping(values), _corners(values, b=b_values, F=F_values), b_values, F_values)


@dataclass(frozen=True)
class ExistenceMapScene:
    """The existence map over ``(a3, F)`` (cell centres), converged where the last two velocities agree."""

    study: Study
    params: Parameters
    release: Release
    a3_values: tuple[float, ...]
    F_values: tuple[float, ...]
    n_cycles: int
    tolerance: float

    @classmethod
    def from_mapping(cls, values: Mapping) -> ExistenceMapScene:
        a3_values = cell_centres(*_axis("existence_map", "a3", values["a3"]))
        F_values = cell_centres(*_axis("existence_map", "F", values["F"]))
        params = _corners(values, a3=a3_values, F=F_values)
        tolerance = float(values["tolerance"]) if _real(values["tolerance"]) else np.nan
        if not 0 < tolerance < 1:
            raise ParameterError("tolerance", values["tolerance"], "a relative tolerance in (0, 1)")
        n_cycles = _count("existence_map.n_cycles", values["n_cycles"])
        return cls(Study.from_mapping(values), params, Release.from_mapping(values), a3_values, F_values,
                   n_cycles, tolerance)


@dataclass(frozen=True)
class LongRunScene:
    """The long run: the exact solver and closed forms over ``n_cycles``, ``solve_ivp`` over ``ivp_cycles``."""

    params: Parameters
    release: Release
    n_cycles: int
    ivp_method: str
    ivp_rtol: float
    ivp_cycles: int

    @classmethod
    def from_mapping(cls, values: Mapping) -> LongRunScene:
        return cls(Parameters.from_mapping(values), Release.from_mapping(values),
                   _count("long_run.n_cycles", values["n_cycles"]), str(values["ivp_method"]),
                   float(values["ivp_rtol"]), _count("long_run.ivp_cycles", values["ivp_cycles"]))
