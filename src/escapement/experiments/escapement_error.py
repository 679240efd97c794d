"""The escapement error: the limit cycle's rate against its amplitude, for every force and impulse
zone (:func:`escapement.studies.escapement_error.rate_against_amplitude`), with the largest
difference between the corrected Eqs. (24)-(25) and the exact solver's period.
:func:`escapement.io.studies.escapement_error_dataset` makes the dataset of it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..model.parameters import Parameters
from ..studies.escapement_error import SECONDS_PER_DAY, rate_against_amplitude

__all__ = ["RATE_FIELDS", "EscapementError", "escapement_error"]

#: the fields of each limit cycle's rate (:class:`~escapement.studies.escapement_error.LimitCycleRate`) kept
RATE_FIELDS = ("amplitude", "velocity", "period", "period_formula", "rate", "rate_impacts", "rate_zones")


@dataclass(frozen=True)
class EscapementError:
    """The rate of the limit cycle over impulse zones and forces.

    Attributes
    ----------
    zones : dict of str to tuple of float
        Each zone's name and its ``(a1, a2)`` of the first half cycle, m.
    forces : numpy.ndarray
        The forces, N.
    values : dict of str to numpy.ndarray
        Each field of :data:`RATE_FIELDS`, of shape ``(len(zones), len(forces))``.
    max_period_difference : float
        The largest relative difference between the corrected Eqs. (24)-(25) and the exact period.
    seconds_per_day : float
        The seconds in a day the rate counts.
    model : dict of str to float
        The parameters other than ``F`` and the zone's positions.
    """

    zones: dict[str, tuple[float, float]]
    forces: np.ndarray
    values: dict[str, np.ndarray]
    max_period_difference: float
    seconds_per_day: float
    model: dict[str, float]


def escapement_error(base: Parameters, forces: Sequence[float], zones: Mapping[str, Sequence[float]]
                     ) -> EscapementError:
    """The limit cycle's rate for every force and every impulse zone.

    Parameters
    ----------
    base : Parameters
        The rest of the model.
    forces : sequence of float
        The forces, N.
    zones : mapping of str to sequence of float
        Each zone's name and ``[a1, a2]`` of the first half cycle, m; the second half cycle's zone is
        its mirror image, ``a3 = -a1``, ``a4 = -a2``.

    Returns
    -------
    EscapementError
        The rates and their decomposition.

    Raises
    ------
    ValueError
        If a configuration has no limit cycle.
    """
    names = list(zones)
    forces = np.asarray(forces, dtype=float)
    values = {name: np.empty((len(names), len(forces))) for name in RATE_FIELDS}
    for i, zone in enumerate(names):
        a1, a2 = (float(a) for a in zones[zone])
        p = Parameters(**{**base.as_dict(), "a1": a1, "a2": a2, "a3": -a1, "a4": -a2})
        for j, cycle in enumerate(rate_against_amplitude(p, forces)):
            for name in RATE_FIELDS:
                values[name][i, j] = getattr(cycle, name)
    worst = float(np.max(np.abs(values["period_formula"] - values["period"]) / values["period"]))
    model = {k: v for k, v in base.as_dict().items() if k not in ("F", "a1", "a2", "a3", "a4")}
    return EscapementError({z: (float(zones[z][0]), float(zones[z][1])) for z in names}, forces, values, worst,
                           SECONDS_PER_DAY, model)
