"""The model's parameters, validated when they are made: :class:`Parameters` for one run, :class:`ParameterArrays`
for the ensemble's many, both by the one rule set of :func:`rules` and :func:`state_rules`.

The impacts are at ``a1`` (moving right) and ``a3`` (moving left), the force acts from ``a1`` to ``a2`` and from
``a3`` to ``a4`` (Mao, Fu & Li 2013, Sec. 2-3, Appendix A): so ``a1 < a2`` and ``a4 < a3``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass

import numpy as np

from .arguments import ParameterError, check_choice, real_array, real_number
from .automaton import CHOICES
from .quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS, REQUIRED_KEYS, SYMMETRIC_DEFAULTS, quantity

__all__ = ["B_SMALLEST", "LARGEST", "SIGNS", "SMALLEST", "ParameterArrays", "ParameterError", "Parameters",
           "check_initial_state", "parameters_section", "rules", "state_rules", "validate_arrays"]

SMALLEST, LARGEST = 1e-50, 1e50  #: the magnitudes of a non-zero dimensional input, SI units (see :func:`rules`)
B_SMALLEST = 1e-12  #: the smallest impact coefficient: 1 - b keeps b to 4 significant digits

#: the sign and order rules on the parameters, in words, as the messages and the docstring state them
SIGNS = {"M": "> 0", "K": "> 0", "F": ">= 0", "b": "in the open interval (0, 2)", "a2": "> a1", "a4": "< a3"}

_WHY = ("so that the squares and products the solvers form (omega**2 = K/M, F/K, v/omega, squared speeds, "
        "energies) stay normal float64 numbers")
#: each parameter's and initial-state component's unit, as printed
_UNIT = {name: q.unit_label for name, q in {**PARAMETERS, **INITIAL_STATE}.items()}
#: the positions along the line of motion: the parameters measured as the displacement is
_POSITIONS = tuple(name for name, q in PARAMETERS.items() if q.units == quantity("displacement").units)


def _magnitude(name: str, values: np.ndarray, zero: bool) -> tuple[str, np.ndarray, str]:
    """The rule that a dimensional input's magnitude lies in [SMALLEST, LARGEST] (or, with ``zero``, is 0)."""
    size = np.abs(values)
    holds = ((size >= SMALLEST) & (size <= LARGEST)) | (zero & (size == 0.0))
    allowed = f"0 or of magnitude in [{SMALLEST:.0e}, {LARGEST:.0e}]" if zero else f"in [{SMALLEST:.0e}, {LARGEST:.0e}]"
    return name, holds, f"{allowed} ({_UNIT[name]}), {_WHY}"


def rules(v: Mapping[str, np.ndarray]) -> Iterator[tuple[str, np.ndarray, str]]:
    """Each rule on the model keys' arrays ``v`` as ``(name, holds, requirement)``, in the order they are checked;
    ``requirement`` may name other parameters as ``{a1}`` (filled with the offending row's values).

    With every dimensional input 0 (not ``M`` or ``K``) or of magnitude in ``[1e-50, 1e50]``, ``omega``, ``F/K``,
    ``F/M`` and ``v0/omega`` lie in ``[1e-100, 1e100]``; each zone adds at most ``4e150`` to ``v**2``, so over
    :data:`~escapement.model.limits.MAX_EVENTS` events every square stays below about ``1e260`` and every non-zero
    product above ``1e-200``: normal float64 numbers with a margin of 1e40.
    """
    with np.errstate(all="ignore"):
        for name, holds in (("M", v["M"] > 0), ("K", v["K"] > 0), ("F", v["F"] >= 0)):
            yield name, holds, f"{SIGNS[name]} ({_UNIT[name]})"
            yield _magnitude(name, v[name], zero=name == "F")  # a force may be 0, a mass or a stiffness not
        yield "b", (v["b"] > 0) & (v["b"] < 2), SIGNS["b"]
        yield "b", v["b"] >= B_SMALLEST, (f">= {B_SMALLEST:.0e} (and < 2), so that the impact law's factor 1 - b "
                                          "keeps b to 4 significant digits")
        for name in _POSITIONS:
            yield _magnitude(name, v[name], zero=True)
        yield "a2", v["a1"] < v["a2"], SIGNS["a2"] + " = {a1!r} " + f"({_UNIT['a2']})"
        yield "a4", v["a4"] < v["a3"], SIGNS["a4"] + " = {a3!r} " + f"({_UNIT['a4']})"


def state_rules(s: Mapping[str, np.ndarray]) -> Iterator[tuple[str, np.ndarray, str]]:
    """The rules on the initial state ``x0`` and ``v0``, as :func:`rules`."""
    with np.errstate(all="ignore"):
        for name in INITIAL_STATE:
            yield _magnitude(name, s[name], zero=True)


def _broadcast(checked: Mapping[str, np.ndarray], given: Mapping[str, object]) -> dict[str, np.ndarray]:
    """The arrays broadcast to one shape; the first that does not fit the ones before it is named."""
    shape: tuple[int, ...] = ()
    for name, array in checked.items():
        try:
            shape = np.broadcast_shapes(shape, array.shape)
        except ValueError as err:
            requirement = f"an array broadcastable with the inputs before it, of shape {shape}"
            raise ParameterError(name, given[name], requirement) from err
    return {name: np.broadcast_to(array, shape) for name, array in checked.items()}


def _check(checks: Iterable, shaped: Mapping[str, np.ndarray]) -> None:
    """Raise for the first rule of ``checks`` that fails, naming the row for arrays."""
    scalar = all(a.ndim == 0 for a in shaped.values())
    for name, holds, requirement in checks:
        if not np.all(holds):
            row = None if scalar else int(np.flatnonzero(~np.ravel(holds))[0])
            at = {k: float(np.ravel(a)[row or 0]) for k, a in shaped.items()}
            raise ParameterError(name, at[name], requirement.format(**at), row=row)


def validate_arrays(values: Mapping[str, object], single: bool = False, state: bool = False) -> dict[str, np.ndarray]:
    """Every model key and, with ``state``, ``x0`` and ``v0``, checked and broadcast to one shape of float64 arrays."""
    for key in REQUIRED_KEYS + (tuple(INITIAL_STATE) if state else ()):
        if values.get(key) is None:
            raise ParameterError(key, None, "given")
    take = (lambda name, value: np.asarray(real_number(name, value))) if single else real_array
    checked = {name: take(name, values[name]) for name in REQUIRED_KEYS}
    for name, mirror in SYMMETRIC_DEFAULTS.items():
        checked[name] = -checked[mirror] if values.get(name) is None else take(name, values[name])
    checked = {k: checked[k] for k in MODEL_KEYS}
    if state:
        checked.update({name: take(name, values[name]) for name in INITIAL_STATE})
    shaped = _broadcast(checked, {k: values.get(k) for k in checked})
    _check(rules(shaped), shaped)
    if state:
        _check(state_rules(shaped), shaped)
    return {name: np.array(array) for name, array in shaped.items()}


@dataclass(frozen=True)
class Parameters:
    """Physical parameters of the escapement model, each checked when made (:func:`rules`) and stored as a float.

    ``a3`` and ``a4`` default to the symmetric geometry; give them to study the paper's asymmetric map, Eq. (16).

    Parameters
    ----------
    {parameters}
    release_force : {'after_impact', 'eq5'}, default 'after_impact'
        Where the force acts before the first impact (the paper is silent): in a zone entered through its impact
        only, or on S2 of Eq. (5) as printed from the release on (run by the event solvers only).
    past_accumulation : {'stop', 'continue'}, default 'stop'
        What follows an accumulation of impacts (b > 1): the run stops, or goes on from rest at the impact position.

    Raises
    ------
    ParameterError
        If a value is not a finite real number or breaks a rule; the message names it and the rule.

    Examples
    --------
    >>> from escapement import Parameters
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)  # the paper's Fig. 3 (a) (Sec. 4)
    >>> p
    Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05, a3=0.1, a4=-0.05)
    >>> p.symmetric, p.omega, round(p.natural_period, 6)
    (True, 1.0, 6.283185)
    """

    M: float
    K: float
    F: float
    b: float
    a1: float
    a2: float
    a3: float | None = None
    a4: float | None = None
    release_force: str = CHOICES["release_force"][0]
    past_accumulation: str = CHOICES["past_accumulation"][0]

    def __post_init__(self) -> None:
        checked = validate_arrays({name: getattr(self, name) for name in MODEL_KEYS}, single=True)
        for name, value in checked.items():
            object.__setattr__(self, name, float(value))
        for name, allowed in CHOICES.items():
            check_choice(name, getattr(self, name), allowed)

    @classmethod
    def from_mapping(cls, values: Mapping[str, object]) -> Parameters:
        """From a mapping with the model keys (others are ignored); a missing key is named."""
        if missing := [key for key in REQUIRED_KEYS if key not in values]:
            raise ParameterError(missing[0], None, "given (it is missing)")
        return cls(**{k: values[k] for k in (*MODEL_KEYS, *CHOICES) if values.get(k) is not None})

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
    def paper_signs(self) -> bool:
        """True for the paper's signs ``a1 < 0 < a3``: each impact on its jump set ``x * xdot < 0``."""
        return self.a1 < 0.0 < self.a3

    @property
    def symmetric(self) -> bool:
        """True for the paper's symmetric geometry a3 = -a1, a4 = -a2."""
        return self.a3 == -self.a1 and self.a4 == -self.a2

    @property
    def chosen(self) -> dict[str, str]:
        """The model's choices made otherwise than by default."""
        return {name: getattr(self, name) for name, allowed in CHOICES.items() if getattr(self, name) != allowed[0]}

    def as_dict(self) -> dict[str, float]:
        """Every parameter by the paper's symbol."""
        return {n: getattr(self, n) for n in MODEL_KEYS}

    def __repr__(self) -> str:
        """The call that makes these parameters (zero without a sign: ``a4`` of ``a2 = 0`` is stored as -0.0)."""
        values = [f"{name}={getattr(self, name) + 0.0!r}" for name in MODEL_KEYS]
        return f"{type(self).__name__}({', '.join(values + [f'{k}={v!r}' for k, v in self.chosen.items()])})"


def parameters_section(kind: str = "float") -> str:
    """The numpydoc entries of the parameters, of type ``kind``, from the table: long name, units, rule, default."""
    lines = []
    for name, q in PARAMETERS.items():
        mirror = SYMMETRIC_DEFAULTS.get(name)
        units = "dimensionless" if q.dimensionless else q.unit_label
        rule = f" ({SIGNS[name]})" if name in SIGNS else ""
        default = f"; default -{mirror}" if mirror else ""
        lines += [f"{name} : {kind}{', optional' if mirror else ''}",
                  f"    {q.long_name[:1].upper()}{q.long_name[1:]}, {units}{rule}{default}."]
    return "\n    ".join(lines)


if Parameters.__doc__:  # None when docstrings are stripped (python -OO)
    Parameters.__doc__ = Parameters.__doc__.replace("{parameters}", parameters_section())


@dataclass(frozen=True)
class ParameterArrays:
    """The parameters of the ensemble's runs, a row per element of each flat float64 array (:func:`validate_arrays`)."""

    M: np.ndarray
    K: np.ndarray
    F: np.ndarray
    b: np.ndarray
    a1: np.ndarray
    a2: np.ndarray
    a3: np.ndarray
    a4: np.ndarray

    @property
    def omega(self) -> np.ndarray:
        """sqrt(K/M) of each run, rad/s."""
        return np.sqrt(self.K / self.M)

    @property
    def zone_offset(self) -> np.ndarray:
        """F/K of each run, m."""
        return self.F / self.K


def check_initial_state(x0: object, v0: object) -> tuple[float, float]:
    """The initial displacement and velocity, checked (:func:`state_rules`), as floats."""
    state = {name: np.asarray(real_number(name, value)) for name, value in zip(INITIAL_STATE, (x0, v0))}
    _check(state_rules(state), state)
    return float(state["x0"]), float(state["v0"])
