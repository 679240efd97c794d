"""Measuring the Poincare map of the simulated motion: fixed point, period, multiplier.

The multiplier is measured, not taken from Eq. (21): the exact solver is released
from rest at the left turning point of the free swing that meets a1 with a given
velocity v, so that its first impact is at (a1, v); one cycle later it returns
P(v).  A central difference of P at the measured fixed point gives mu_2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..model.status import Status
from ..solvers.ensemble import solve_ensemble
from ..solvers.exact import solve_exact

__all__ = ["CycleMeasurement", "NoReturn", "ensemble_return_map", "measure_cycle", "return_map", "stability_grid"]

#: relative step of the central difference: truncation ~ h**2, rounding ~ 1e-16 / h
RELATIVE_STEP = 1e-5


class NoReturn(ValueError):
    """The motion from the section leaves the regime before it returns to the section."""


def return_map(params: Parameters, v: float, strict: bool = True) -> tuple[float, float]:
    """``(v_in, P(v_in))``: the velocity of the first impact at a1 (v up to rounding) and of the next.

    When the motion leaves the regime first, raise :class:`NoReturn` (``strict``) or return NaN
    for ``P(v_in)``.
    """
    release = -math.hypot(params.a1, v / params.omega)
    run = solve_exact(params, release, 0.0, n_cycles=2, record_trajectory=False)
    if run.status != Status.COMPLETED or len(run.cycles) < 2:
        if not strict:
            first = run.events.of_kind(EventKind.IMPACT_A1)
            return (float(run.events.v_before[first[0]]) if len(first) else math.nan), math.nan
        raise NoReturn(f"no return to the section from v = {v!r}: {run.message}")
    return float(run.cycles.velocity_before_impact[0]), float(run.cycles.velocity_before_impact[1])


@dataclass(frozen=True)
class CycleMeasurement:
    outcome: str
    message: str
    velocity: float  #: velocity before impact after n_cycles (the measured fixed point)
    period: float
    amplitude: float
    multiplier: float  #: dP/dv at the measured fixed point, by a central difference
    cycles_to_converge: int  #: first cycle whose velocity is within 1e-9 (relative) of the last


def measure_cycle(params: Parameters, x0: float, n_cycles: int = 300) -> CycleMeasurement:
    """Run ``n_cycles`` from release at ``x0`` and measure the map at where it ends."""
    run = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=False)
    nan = math.nan
    if run.status != Status.COMPLETED:
        return CycleMeasurement(run.status.value, run.message, nan, nan, nan, nan, -1)
    v = run.cycles.velocity_before_impact
    star = float(v[-1])
    lo_in, lo_out = return_map(params, star * (1 - RELATIVE_STEP))
    hi_in, hi_out = return_map(params, star * (1 + RELATIVE_STEP))
    close = abs(v - star) <= 1e-9 * abs(star)
    first = int(close.argmax()) + 1 if close.any() else -1
    return CycleMeasurement(
        outcome=run.status.value,
        message=run.message,
        velocity=star,
        period=float(run.cycles.period[-1]),
        amplitude=float(run.cycles.amplitude[-1]),
        multiplier=(hi_out - lo_out) / (hi_in - lo_in),
        cycles_to_converge=first,
    )



def ensemble_return_map(model: dict, b, F, v):
    """:func:`return_map` for arrays: ``(v_in, P(v_in), period, status codes)`` at every ``(b, F, v)``."""
    omega = math.sqrt(model["K"] / model["M"])
    out = solve_ensemble(
        model["M"], model["K"], F, b, model["a1"], model["a2"], model.get("a3"), model.get("a4"),
        x0=-np.hypot(model["a1"], np.asarray(v) / omega), n_cycles=2, amplitude=False,
    )
    c = out.cycles
    return c.velocity_before_impact[:, 0], c.velocity_before_impact[:, 1], c.period[:, 0], out.status


def stability_grid(model: dict, b, F, iterations: int = 40):
    """Fixed point and multiplier of the simulated return map at every ``(b, F)``.

    Newton's method on ``P(v) - v`` with the slope from central differences of the
    simulated map (``P`` is convex, so the iteration converges from any positive start).
    Returns a dict of arrays: ``fixed_point``, ``multiplier``, ``period``, ``status``,
    ``newton_converged``.
    """
    b = np.asarray(b, dtype=float)
    F = np.asarray(F, dtype=float)
    omega = math.sqrt(model["K"] / model["M"])

    def slope_at(v):
        lo_in, lo_out, _, _ = ensemble_return_map(model, b, F, v * (1 - RELATIVE_STEP))
        hi_in, hi_out, _, _ = ensemble_return_map(model, b, F, v * (1 + RELATIVE_STEP))
        return (hi_out - lo_out) / (hi_in - lo_in)

    v = np.full(b.shape, omega * abs(model["a1"])) + np.sqrt(2 * F / model["M"] * (model["a2"] - model["a1"]))
    converged = np.zeros(b.shape, dtype=bool)
    for _ in range(iterations):
        v_in, v_out, _, status = ensemble_return_map(model, b, F, v)
        step = (v_out - v_in) / (1.0 - slope_at(v))
        ok = np.isfinite(step) & (status == Status.COMPLETED.code)
        v = np.where(ok, v_in + step, v)
        # 1 / (1 - slope) magnifies rounding as b -> 0, hence a tolerance above 1e-16
        converged = ok & (np.abs(step) <= 1e-12 * np.abs(v))
        if not (ok & ~converged).any():
            break
    v_in, _, period, status = ensemble_return_map(model, b, F, v)
    good = status == Status.COMPLETED.code
    return {
        "fixed_point": np.where(good, v_in, np.nan),
        "multiplier": np.where(good, slope_at(v), np.nan),
        "period": np.where(good, period, np.nan),
        "status": status,
        "newton_converged": converged,
    }
