"""The escapement error: the limit cycle's rate (seconds gained per day) against its amplitude, decomposed as Airy
(1830) did: an impulse symmetric about the equilibrium leaves the period unchanged to first order, one before it
shortens it, one after lengthens it. The period is ``T = 2 pi / w + dT1 + dT2``, the impacts' phase jumps and the
zones' time less their phase advance (the corrected Eqs. (24)-(25)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ..model.parameters import Parameters
from ..model.status import Status
from ..paper import corrected
from ..paper.corrected import SECONDS_PER_DAY, daily_rate, first_order_zone_change
from ..solvers.exact import solve_exact

__all__ = ["SECONDS_PER_DAY", "LimitCycleRate", "daily_rate", "first_order_zone_change", "limit_cycle_rate",
           "rate_against_amplitude"]


@dataclass(frozen=True)
class LimitCycleRate:
    """The limit cycle of one configuration: its amplitude, period and rate, and the decomposition."""

    F: float  #: force, N
    largest_displacement: float  #: largest displacement of the limit cycle (its amplitude), m
    velocity: float  #: fixed point of the map (16): velocity before the impact at a1, m/s
    period: float  #: period measured by the exact solver from the fixed point, s
    period_formula: float  #: 2 pi / w + dT1 + dT2 (corrected Eqs. (24)-(25)), s
    impacts: float  #: dT1: phase jumps of the two impacts, s
    zones: float  #: dT2: zone time less phase advance, both zones, s
    rate: float  #: seconds per day gained (negative: lost)
    rate_impacts: float  #: the part of the rate due to dT1, s/day (first order: -86400 dT1 / T0)
    rate_zones: float  #: the part due to dT2, s/day
    status: Status = Status.COMPLETED  #: COMPLETED for a limit cycle; else how the cycle ends (the fields NaN)
    message: str = "a limit cycle"  #: what ended it, naming the configuration


def limit_cycle_rate(p: Parameters) -> LimitCycleRate:
    """The limit cycle of ``p``, measured with the exact solver over one cycle from the fixed point of the map (16)
    and decomposed; without one its fields are NaN and ``status`` says how the motion ends."""
    v = corrected.fixed_point(p)
    if not math.isfinite(v):
        return _no_limit_cycle(p, Status.STOPPED, f"F = {p.F!r} N with a1..a4 = {p.a1}, {p.a2}, {p.a3}, {p.a4}: "
                                                  "the map (16) has no fixed point, every velocity decays to rest")
    release = -math.hypot(p.a1, v / p.omega)  # at rest on the free arc that meets a1 with v
    run = solve_exact(p, release, n_cycles=1, record_trajectory=False)
    if run.status != Status.COMPLETED:
        return _no_limit_cycle(p, run.status, f"F = {p.F!r} N: the cycle from the fixed point leaves the regime: "
                                              f"{run.message}")
    vel = corrected.cycle_velocities(v, p)
    mirror = Parameters(M=p.M, K=p.K, F=p.F, b=p.b, a1=-p.a3, a2=-p.a4, a3=-p.a1, a4=-p.a2)
    impacts = corrected.impact_phase_jump(p.a1, v, p) + corrected.impact_phase_jump(mirror.a1, -vel["v4"], mirror)
    zones = corrected.zone_period_change(v, p) + corrected.zone_period_change(-vel["v4"], mirror)
    t0 = 2.0 * math.pi / p.omega
    period = float(run.cycles.period[0])
    return LimitCycleRate(p.F, float(run.cycles.largest_displacement[0]), v, period, t0 + impacts + zones, impacts,
                          zones, daily_rate(period, t0), -SECONDS_PER_DAY * impacts / t0, -SECONDS_PER_DAY * zones / t0)


def _no_limit_cycle(p: Parameters, status: Status, message: str) -> LimitCycleRate:
    measured = [f.name for f in fields(LimitCycleRate) if f.name not in ("F", "status", "message")]
    return LimitCycleRate(F=p.F, **dict.fromkeys(measured, math.nan), status=status, message=message)


def rate_against_amplitude(base: Parameters, forces: np.ndarray) -> list[LimitCycleRate]:
    """:func:`limit_cycle_rate` for each force in ``forces`` (N), the rest of ``base`` unchanged."""
    return [limit_cycle_rate(Parameters(**{**base.as_dict(), "F": float(F)})) for F in forces]
