"""The long run: the errors of the exact solver, of the per-cycle closed forms and of ``solve_ivp``
against a 50-digit reference as the cycles add up (:func:`escapement.studies.long_run.long_run`),
with the wall time of each method kept apart from the numbers (it varies from run to run).
:func:`escapement.io.scenes.long_run_dataset` makes the dataset of the errors.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..model.parameters import Parameters
from ..studies.long_run import long_run
from .arguments import positive_int

__all__ = ["LongRun", "run_long"]


@dataclass(frozen=True)
class LongRun:
    """The errors of one long run and the wall time of each method.

    Attributes
    ----------
    errors : dict
        What :func:`escapement.studies.long_run.long_run` returns: the sampled cycles, each method's
        errors, the deviations from the limit cycle and the reference's limit cycle.
    n_cycles, ivp_cycles : int
        The cycles of the closed forms and of ``solve_ivp``.
    ivp_method : str
        The ``solve_ivp`` method.
    ivp_rtol : float
        Its relative tolerance.
    timings : dict of str to float
        ``exact_seconds``, ``closed_form_seconds`` and ``ivp_seconds``: the wall times, s.
    """

    errors: dict
    n_cycles: int
    ivp_method: str
    ivp_rtol: float
    ivp_cycles: int
    timings: dict[str, float]


def run_long(params: Parameters, x0: float, n_cycles: int, ivp_method: str, ivp_rtol: float,
             ivp_cycles: int) -> LongRun:
    """Errors over ``n_cycles`` (``ivp_cycles`` for ``solve_ivp``) against 50 digits.

    Parameters
    ----------
    params : Parameters
        The model.
    x0 : float
        Release position (from rest), m.
    n_cycles : int
        Cycles of the closed forms (the exact solver runs up to its own check count of them).
    ivp_method : str
        The ``solve_ivp`` method.
    ivp_rtol : float
        Its relative tolerance.
    ivp_cycles : int
        Cycles of ``solve_ivp``.

    Returns
    -------
    LongRun
        The errors and the wall times.

    Raises
    ------
    ParameterError
        If a count is not a positive integer, or too small for the transient to have decayed.
    """
    n_cycles = positive_int("n_cycles", n_cycles)
    ivp_cycles = positive_int("ivp_cycles", ivp_cycles)
    errors = long_run(params, x0, n_cycles, ivp_method, ivp_rtol, ivp_cycles)
    timings = {"exact_seconds": errors["exact_wall_s"], "closed_form_seconds": errors["closed_form_wall_s"],
               "ivp_seconds": errors["ivp_wall_s"]}
    return LongRun(errors, n_cycles, ivp_method, ivp_rtol, ivp_cycles, timings)
