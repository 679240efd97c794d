"""The runs of the claims register: per case, the measured fixed point, period and multipliers.

Each case (a configured mapping with ``group``, ``label``, the model keys and ``x0``) is released
from rest and run ``n_cycles`` cycles; its Poincare map is measured at the last cycle
(:func:`escapement.paper.poincare.measure_cycle`) beside the fixed point of Eq. (16) and the
multiplier of Eq. (21), with the first cycle's period, the largest speed on the last cycle and
both Floquet multipliers of the flow. The result is a table of plain columns, one value per case;
:func:`escapement.io.scenes.checks_dataset` makes the dataset of it. The cases, among them the runs
at common forces of Fig. 5, from several releases and over a sweep of the force, are the
configuration's (:func:`escapement.pipeline.config.check_cases`).
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

__all__ = ["measure_cases"]


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
        ``outcome_message``, ``x0`` (m), ``velocity`` (m/s), ``period`` (s), ``largest_displacement`` (m),
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
        "largest_displacement": [m.largest_displacement for *_, m in runs],
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
