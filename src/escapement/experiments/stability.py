"""One chunk of the stability and existence map over (b, F): the fixed point of the simulated return
map, the period there, the measured multiplier beside Eq. (21)'s and how the cycle from the fixed
point ended, at every cell (ensemble solver); and, kept apart from the numbers, the cost per
trajectory of the ensemble against looping the scalar solver. :func:`escapement.io.scenes.stability_dataset`
makes the dataset of a chunk.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..model.parameters import Parameters, validate_arrays
from ..model.quantities import MODEL_KEYS
from ..paper.poincare import ensemble_return_map, return_map, stability_grid
from ..paper.printed import multiplier_21_of

__all__ = ["StabilityChunk", "stability_chunk"]

#: the map's axes
AXES = ("b", "F")


@dataclass(frozen=True)
class StabilityChunk:
    """One chunk of the map, each array of shape ``(len(b_values), len(F_values))``.

    Attributes
    ----------
    b_values, F_values : numpy.ndarray
        The axes: impact coefficients and forces (N).
    multiplier : numpy.ndarray
        The multiplier measured from the simulated return map.
    multiplier_eq21 : numpy.ndarray
        ``(1 - b)**4`` of Eq. (21).
    fixed_point : numpy.ndarray
        Fixed point of the simulated return map, m/s.
    period : numpy.ndarray
        Period of the cycle at the fixed point, s.
    status : numpy.ndarray
        How the cycle from the fixed point ended, as :attr:`~escapement.model.status.Status.code`.
    constants : dict of str to float
        The other parameters, the same at every cell (``a3``, ``a4`` resolved to their defaults).
    timings : dict of str to float
        ``ensemble_seconds_per_trajectory`` and ``scalar_seconds_per_trajectory``.
    """

    b_values: np.ndarray
    F_values: np.ndarray
    multiplier: np.ndarray
    multiplier_eq21: np.ndarray
    fixed_point: np.ndarray
    period: np.ndarray
    status: np.ndarray
    constants: dict[str, float]
    timings: dict[str, float]


def _multiplier_21_grid(b: np.ndarray) -> np.ndarray:
    """Eq. (21) at every cell, computed once per distinct ``b`` (the same float on every machine)."""
    values, index = np.unique(b, return_inverse=True)
    return np.array([multiplier_21_of(float(v)) for v in values])[index].reshape(b.shape)


def stability_chunk(model: Mapping, b_values: Sequence[float], F_values: Sequence[float],
                    speed_sample: int = 100) -> StabilityChunk:
    """Fixed point and measured multiplier over the grid ``b_values x F_values``.

    Parameters
    ----------
    model : mapping
        The parameters other than ``b`` and ``F`` (``M``, ``K``, ``a1``, ``a2``; ``a3``, ``a4`` optional).
    b_values, F_values : sequence of float
        The axes of the chunk.
    speed_sample : int
        How many cells, evenly spread, the scalar solver is timed on.

    Returns
    -------
    StabilityChunk
        The map's arrays and the cost per trajectory of both solvers.
    """
    model = dict(model)
    b_values = np.asarray(b_values, dtype=float)
    F_values = np.asarray(F_values, dtype=float)
    bb, ff = np.meshgrid(b_values, F_values, indexing="ij")
    grid = stability_grid(model, bb.ravel(), ff.ravel())

    # The cost of one return-map evaluation per trajectory: the ensemble over the whole chunk, and
    # the scalar solver looped over an even sample of it, both at the fixed points, in this one run.
    v = np.where(np.isfinite(grid["fixed_point"]), grid["fixed_point"], 1.0)
    start = time.perf_counter()
    ensemble_return_map(model, bb.ravel(), ff.ravel(), v)
    ensemble_per_trajectory = (time.perf_counter() - start) / bb.size
    pick = np.linspace(0, bb.size - 1, min(speed_sample, bb.size)).astype(int)
    start = time.perf_counter()
    for i in pick:
        return_map(Parameters(**{**model, "F": ff.ravel()[i], "b": bb.ravel()[i]}), v[i], strict=False)
    scalar_per_trajectory = (time.perf_counter() - start) / len(pick)

    # b and F are the axes; the other parameters (a3, a4 resolved to their defaults) are constants
    resolved = validate_arrays({**model, "b": bb.ravel(), "F": ff.ravel()})
    constants = {k: np.ravel(resolved[k])[0] for k in MODEL_KEYS if k not in AXES}
    shape = bb.shape
    return StabilityChunk(
        b_values=b_values,
        F_values=F_values,
        multiplier=np.asarray(grid["multiplier"]).reshape(shape),
        multiplier_eq21=_multiplier_21_grid(bb),
        fixed_point=np.asarray(grid["fixed_point"]).reshape(shape),
        period=np.asarray(grid["period"]).reshape(shape),
        status=np.asarray(grid["status"]).reshape(shape),
        constants=constants,
        timings={"ensemble_seconds_per_trajectory": ensemble_per_trajectory,
                 "scalar_seconds_per_trajectory": scalar_per_trajectory},
    )
