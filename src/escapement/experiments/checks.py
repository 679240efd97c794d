"""The runs of the claims register: per case, the measured fixed point, period and multipliers.

Each case (a configured mapping with ``group``, ``label``, the model keys and ``x0``) is released
from rest and run ``n_cycles`` cycles; its Poincare map is measured at the last cycle
(:func:`escapement.paper.poincare.measure_cycle`) beside the fixed point of Eq. (16) and the
multiplier of Eq. (21), with the first cycle's period, the largest speed on the last cycle and
both Floquet multipliers of the flow. The result is a table of plain columns, one value per case;
:func:`escapement.io.scenes.checks_dataset` makes the dataset of it. :func:`added_cases` gives the
runs at common forces of Fig. 5, from several releases and over a sweep of the force.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..model.parameters import Parameters, check_initial_state
from ..model.quantities import MODEL_KEYS
from ..paper.corrected import fixed_point
from ..paper.poincare import measure_cycle
from ..paper.printed import multiplier_21
from .arguments import positive_int

__all__ = ["added_cases", "measure_cases"]


def measure_cases(cases: Sequence[Mapping], n_cycles: int) -> dict[str, list | np.ndarray]:
    """Measure every case of the claims register.

    Parameters
    ----------
    cases : sequence of mapping
        Each with ``group``, ``label``, the model keys and ``x0`` (``v0`` 0 if absent).
    n_cycles : int
        Cycles to run from each release.

    Returns
    -------
    dict
        One column per name, one value per case: ``label``, ``group``, ``outcome``,
        ``outcome_message``, ``x0`` (m), ``velocity`` (m/s), ``period`` (s), ``amplitude`` (m),
        ``multiplier``, ``multiplier_eq21``, ``fixed_point_eq16`` (m/s), ``cycles_to_converge``
        (int32; -1 where none), ``first_period`` (s), ``largest_speed`` (m/s), ``floquet_major``,
        ``floquet_minor`` and each model parameter by its key.

    Raises
    ------
    ParameterError
        If a case's parameters or release are invalid, or ``n_cycles`` is not a positive integer.
    """
    n_cycles = positive_int("n_cycles", n_cycles)
    runs = []
    for case in cases:
        params = Parameters.from_mapping(case)
        x0, _ = check_initial_state(case["x0"], case.get("v0", 0.0))
        runs.append((case, params, x0, measure_cycle(params, x0, n_cycles)))
    columns = {
        "label": [c["label"] for c, *_ in runs],
        "group": [c["group"] for c, *_ in runs],
        "outcome": [m.outcome for *_, m in runs],
        "outcome_message": [m.message for *_, m in runs],
        "x0": [x0 for _, _, x0, _ in runs],
        "velocity": [m.velocity for *_, m in runs],
        "period": [m.period for *_, m in runs],
        "amplitude": [m.amplitude for *_, m in runs],
        "multiplier": [m.multiplier for *_, m in runs],
        "multiplier_eq21": [multiplier_21(p) for _, p, _, _ in runs],
        "fixed_point_eq16": [fixed_point(p) for _, p, _, _ in runs],
        "cycles_to_converge": np.array([m.cycles_to_converge for *_, m in runs], dtype=np.int32),
        "first_period": [m.first_period for *_, m in runs],
        "largest_speed": [m.largest_speed for *_, m in runs],
        "floquet_major": [m.floquet[0] for *_, m in runs],
        "floquet_minor": [m.floquet[1] for *_, m in runs],
    }
    for key in MODEL_KEYS:
        columns[key] = [getattr(p, key) for _, p, _, _ in runs]
    return columns


def _numbers(name: str, value) -> list[float]:
    """``value`` as a non-empty list of numbers (one number is a list of one)."""
    values = value if isinstance(value, list) else [value]
    if not values or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        raise ValueError(f"{name} = {value!r} must be a number or a non-empty list of numbers")
    return [float(v) for v in values]


def _case(model: Mapping, **keys) -> dict:
    """A case: the model block's values, then ``keys``, sorted by key (as the configuration's scenes)."""
    return dict(sorted({**{k: v for k, v in model.items() if not isinstance(v, dict)}, **keys}.items()))


def added_cases(model: Mapping, checks: Mapping, fig5: Mapping) -> list[dict]:
    """The runs that hold all but one parameter fixed, for the claims that compare runs.

    * ``common_force``: each spring constant of Fig. 5 (``fig5.K``, from its panel's ``x0``) at each force
      of the figure (``fig5.F``), so that the spring constants are compared at one force;
    * ``release``: at ``checks.releases.F``, from each ``checks.releases.x0`` (none if ``checks`` has no
      ``releases``);
    * ``force``: each ``checks.forces.F`` from ``checks.forces.x0``, at the model's geometry (none if
      ``checks`` has no ``forces``).

    Parameters
    ----------
    model, checks, fig5 : mapping
        The configuration's ``model``, ``checks`` and ``fig5`` blocks.

    Returns
    -------
    list of dict
        One case per run, with ``group`` and ``label`` (the order above).

    Raises
    ------
    ValueError
        If a block lacks a key or gives a value that is not a number or a list of numbers, or if a
        per-panel list of Fig. 5 is not as long as ``fig5.K``.
    """
    for name, block, keys in (("checks.releases", checks.get("releases", {"F": 0, "x0": 0}), ("F", "x0")),
                              ("checks.forces", checks.get("forces", {"F": 0, "x0": 0}), ("F", "x0")),
                              ("fig5", fig5, ("K", "F", "x0"))):
        missing = [k for k in keys if k not in block]
        if missing:
            raise ValueError(f"{name} = {dict(block)!r} must give {', '.join(missing)}")
    spring = _numbers("fig5.K", fig5["K"])
    panels = {}
    for key in ("F", "x0"):
        values = _numbers(f"fig5.{key}", fig5[key])
        if isinstance(fig5[key], list) and len(values) != len(spring):
            raise ValueError(f"fig5.{key} = {fig5[key]!r} must be one number or one per K ({len(spring)})")
        panels[key] = values if isinstance(fig5[key], list) else values * len(spring)
    cases = [_case(model, K=k, F=force, x0=x0, group="common_force", label=f"K={k:g},F={force:g}")
             for force in sorted(set(panels["F"])) for k, x0 in zip(spring, panels["x0"])]
    if "releases" in checks:
        force = _numbers("checks.releases.F", checks["releases"]["F"])
        if len(force) != 1:
            raise ValueError(f"checks.releases.F = {checks['releases']['F']!r} must be one number")
        cases += [_case(model, F=force[0], x0=x0, group="release", label=f"F={force[0]:g},x0={x0:g}")
                  for x0 in _numbers("checks.releases.x0", checks["releases"]["x0"])]
    if "forces" in checks:
        x0 = _numbers("checks.forces.x0", checks["forces"]["x0"])
        if len(x0) != 1:
            raise ValueError(f"checks.forces.x0 = {checks['forces']['x0']!r} must be one number")
        cases += [_case(model, F=f, x0=x0[0], group="force", label=f"F={f:g},x0={x0[0]:g}")
                  for f in _numbers("checks.forces.F", checks["forces"]["F"])]
    return cases
