"""Existence map of the limit cycle of an asymmetric escapement (Sec. 5 of the paper): over the
force F and the impact position a3 of the second half cycle (the other positions fixed), whether
a run released from a stated state settles on a limit cycle or stops, from simulation (the
vectorised ensemble solver), beside the closed-form boundaries.

The map (16) is ``v1(k+1)**2 = (1 - b)**4 v1(k)**2 + C``: a limit cycle needs ``C > 0``, i.e.
``F > F*`` (:func:`escapement.paper.existence.existence_threshold`). Read at the impact at a3
instead of a1, the same map of the mirror-image escapement (``x -> -x``: a1, a2, a3, a4 become
-a3, -a4, -a1, -a2) needs ``F > F*'``, its threshold: the swing must also reach a3 on the cycle.
``F*`` is positive where ``|a1| > a3``, ``F*'`` where ``a3 > |a1|``; both vanish in the symmetric case.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..model.parameters import Parameters
from ..model.status import Status
from ..paper.existence import existence_threshold
from ..solvers.ensemble import solve_ensemble

__all__ = ["ExistenceMap", "axis_centres", "existence_map", "mirror_image", "thresholds"]


@dataclass(frozen=True)
class ExistenceMap:
    """The map, each 2-d array of shape ``(len(a3_values), len(F_values))``.

    Attributes
    ----------
    a3_values, F_values : numpy.ndarray
        The axes: impact positions a3 (m) and forces (N).
    status : numpy.ndarray
        How each run ended, as :attr:`~escapement.model.status.Status.code`.
    converged : numpy.ndarray
        True where the run completed its cycles and its last two velocities before the impact at a1
        agree within the relative ``tolerance``: a limit cycle reached.
    threshold : numpy.ndarray
        ``F*`` at each a3 (N): ``C = 0`` of the map read at a1.
    threshold_mirror : numpy.ndarray
        ``F*'`` at each a3 (N): ``C = 0`` of the map read at a3 (the mirror image's ``F*``).
    constants : dict of str to float
        The parameters other than a3 and F, and the release ``x0``, ``v0``.
    n_cycles : int
        Cycles each run was given.
    tolerance : float
        The relative tolerance of ``converged``.
    """

    a3_values: np.ndarray
    F_values: np.ndarray
    status: np.ndarray
    converged: np.ndarray
    threshold: np.ndarray
    threshold_mirror: np.ndarray
    constants: dict[str, float]
    n_cycles: int
    tolerance: float


def axis_centres(axis: Mapping) -> np.ndarray:
    """The ``n`` cell centres of ``(start, stop)`` of a configured axis."""
    step = (float(axis["stop"]) - float(axis["start"])) / int(axis["n"])
    return float(axis["start"]) + (np.arange(int(axis["n"])) + 0.5) * step


def mirror_image(p: Parameters) -> Parameters:
    """The escapement reflected by ``x -> -x``: the impact at a3 becomes the first half cycle's."""
    return Parameters(M=p.M, K=p.K, F=p.F, b=p.b, a1=-p.a3, a2=-p.a4, a3=-p.a1, a4=-p.a2)


def thresholds(model: Mapping, a3_values: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """``F*`` and ``F*'`` (N) at each a3, the other parameters from ``model`` (``a4`` default ``-a2``)."""
    out = []
    for a3 in np.asarray(a3_values, dtype=float):
        p = Parameters(**{**_geometry(model), "a3": float(a3), "F": 0.0})
        out.append((existence_threshold(p), existence_threshold(mirror_image(p))))
    pair = np.array(out, dtype=float).reshape(-1, 2)
    return pair[:, 0], pair[:, 1]


def _geometry(model: Mapping) -> dict[str, float]:
    keys = ("M", "K", "b", "a1", "a2")
    geometry = {k: float(model[k]) for k in keys}
    geometry["a4"] = float(model["a4"]) if model.get("a4") is not None else -geometry["a2"]
    return geometry


def existence_map(model: Mapping, a3_values: Sequence[float], F_values: Sequence[float], x0: float,
                  n_cycles: int, tolerance: float, v0: float = 0.0) -> ExistenceMap:
    """Run every ``(a3, F)`` from ``(x0, v0)`` for ``n_cycles`` cycles and classify the outcome.

    Parameters
    ----------
    model : mapping
        ``M``, ``K``, ``b``, ``a1``, ``a2`` and optionally ``a4`` (default ``-a2``); ``a3`` and ``F``
        are the axes (a given ``a3`` or ``F`` is ignored).
    a3_values, F_values : sequence of float
        The axes (m, N).
    x0, v0 : float
        The release: displacement (m) and velocity (m/s) at ``t = 0+``.
    n_cycles : int
        Cycles each run is given.
    tolerance : float
        Relative agreement of the last two velocities before the impact at a1 that counts as converged.

    Returns
    -------
    ExistenceMap
        The outcomes and the closed-form thresholds.
    """
    geometry = _geometry(model)
    a3_values = np.asarray(a3_values, dtype=float)
    F_values = np.asarray(F_values, dtype=float)
    aa, ff = np.meshgrid(a3_values, F_values, indexing="ij")
    run = solve_ensemble(geometry["M"], geometry["K"], ff.ravel(), geometry["b"], geometry["a1"], geometry["a2"],
                         aa.ravel(), geometry["a4"], x0=x0, v0=v0, n_cycles=n_cycles, largest_displacement=False)
    status = np.asarray(run.status).reshape(aa.shape)
    v = run.cycles.velocity_before_impact
    if n_cycles >= 2:
        last, before = v[:, -1], v[:, -2]
        settled = np.abs(last - before) <= tolerance * np.abs(last)
    else:  # one cycle has no second velocity to compare with
        settled = np.zeros(aa.size, dtype=bool)
    converged = (status == Status.COMPLETED.code) & settled.reshape(aa.shape)
    threshold, threshold_mirror = thresholds(geometry, a3_values)
    constants = {k: geometry[k] for k in ("M", "K", "b", "a1", "a2", "a4")}
    constants.update(x0=float(x0), v0=float(v0))
    return ExistenceMap(a3_values=a3_values, F_values=F_values, status=status, converged=converged,
                        threshold=threshold, threshold_mirror=threshold_mirror, constants=constants,
                        n_cycles=int(n_cycles), tolerance=float(tolerance))
