"""Closed forms derived for this replication, the corrected counterparts of the paper's equations, from the energy
balance and the phase plane. The sine phase ``atan2(x, v/w)`` advances at exactly ``w`` in free flight, so a cycle
lasts ``2 pi / w`` plus the phase jumps of the impacts plus the zone times less their phase advance (Eqs. (24)-(25)).
"""

from __future__ import annotations

import math

from ..model.cycle_map import cycle_map
from ..model.parameters import Parameters

__all__ = ["cycle_velocities", "map_constant", "fixed_point", "period", "impact_phase_jump", "zone_period_change",
           "period_from_perturbations", "velocity_recovery", "existence_threshold", "grazing_release",
           "grazing_limit", "SECONDS_PER_DAY", "daily_rate", "first_order_zone_change", "zone_amplitude"]


def _sqrt(value: float) -> float:
    return math.sqrt(value) if value >= 0.0 else math.nan


def cycle_velocities(v1: float, p: Parameters) -> dict[str, float]:
    """Velocities of one cycle from ``v1`` by energy: the paper's (10)-(15), but (14) with the work ``+f (a3 - a4)``."""
    w2, f, b = p.omega2, p.f, p.b
    v1p = (1 - b) * v1
    v2 = _sqrt(v1p**2 + w2 * (p.a1 - p.a2) * (p.a1 + p.a2) + 2 * (p.a2 - p.a1) * f)
    v4 = -_sqrt(v2**2 + w2 * (p.a2 - p.a3) * (p.a2 + p.a3))
    v4p = (1 - b) * v4
    v5 = -_sqrt(v4p**2 + w2 * (p.a3 - p.a4) * (p.a3 + p.a4) + 2 * (p.a3 - p.a4) * f)
    v1_next = _sqrt(v5**2 + w2 * (p.a4 - p.a1) * (p.a4 + p.a1))
    return {"v1p": v1p, "v2": v2, "v4": v4, "v4p": v4p, "v5": v5, "v1_next": v1_next}


def map_constant(p: Parameters) -> float:
    """``C`` in the map ``v1(k+1)**2 = (1 - b)**4 v1(k)**2 + C`` (Eq. (16) is right)."""
    return cycle_map(p).c


def fixed_point(p: Parameters) -> float:
    """Fixed point of the general map (16): ``sqrt(C / (1 - (1 - b)**4))`` (NaN if none)."""
    return cycle_map(p).fixed_point


def _zone_time(centre: float, x_from: float, x_to: float, v_from: float, w: float) -> float:
    """Time to run through an impulse zone, arccos form (centre outside the zone's start)."""
    radius = math.hypot(x_from - centre, v_from / w)
    return abs(math.acos((x_to - centre) / radius) - math.acos((x_from - centre) / radius)) / w


def period(v1: float, p: Parameters) -> float:
    """Corrected Eq. (23): the period of the cycle from ``v1`` at a1, the last two of the eight arccos terms read
    ``acos(-a4/h5) + acos(-a1/h5)``, as from a4 the mass swings through the left turning point ``-h5`` to a1."""
    w, c = p.omega, p.zone_offset
    vel = cycle_velocities(v1, p)
    h2 = math.hypot(p.a2, vel["v2"] / w)
    h5 = math.hypot(p.a4, vel["v5"] / w)
    return (_zone_time(c, p.a1, p.a2, vel["v1p"], w) + (math.acos(p.a2 / h2) + math.acos(p.a3 / h2)) / w
            + _zone_time(-c, p.a3, p.a4, vel["v4p"], w) + (math.acos(-p.a4 / h5) + math.acos(-p.a1 / h5)) / w)


def impact_phase_jump(position: float, v_before: float, p: Parameters) -> float:
    """Delay caused by an impact at ``position``: the jump of the sine phase over ``w`` (at a1, Eq. (24))."""
    w = p.omega
    v_after = (1 - p.b) * v_before
    return (math.atan2(position, v_before / w) - math.atan2(position, v_after / w)) / w * (1 if v_before > 0 else -1)


def zone_period_change(v1: float, p: Parameters) -> float:
    """Corrected (25): time through the zone (a1, a2) less the sine-phase advance over ``w``."""
    w = p.omega
    vel = cycle_velocities(v1, p)
    zone = _zone_time(p.zone_offset, p.a1, p.a2, vel["v1p"], w)
    return zone - (math.atan2(p.a2, vel["v2"] / w) - math.atan2(p.a1, vel["v1p"] / w)) / w


def period_from_perturbations(v1: float, p: Parameters) -> float:
    """``2 pi / w`` plus both impacts' and both zones' perturbations (the left half mirrored) and the phase's drift."""
    w = p.omega
    vel = cycle_velocities(v1, p)
    mirror = Parameters(M=p.M, K=p.K, F=p.F, b=p.b, a1=-p.a3, a2=-p.a4, a3=-p.a1, a4=-p.a2)
    right = impact_phase_jump(p.a1, v1, p) + zone_period_change(v1, p)
    left = impact_phase_jump(mirror.a1, -vel["v4"], mirror) + zone_period_change(-vel["v4"], mirror)
    drift = (math.atan2(p.a1, vel["v1_next"] / w) - math.atan2(p.a1, v1 / w)) / w
    return p.natural_period + right + left + drift


def velocity_recovery(v1: float, p: Parameters) -> tuple[float, float]:
    """Where (``x``) and when (``t``) in the zone (a1, a2) the velocity regains its value before the impact at a1."""
    w2, f, b = p.omega2, p.f, p.b
    q = (2 * b - b * b) * v1 * v1 - w2 * p.a1**2 + 2 * f * p.a1
    disc = f * f - w2 * q
    if disc < 0:
        return math.nan, math.nan
    root = math.sqrt(disc)
    # The two roots, computed without cancellation: x = (f -/+ root) / w2 = q / (f +/- root).
    for x in sorted(((f + root) / w2, q / (f + root) if f + root != 0 else math.inf)):
        if p.a1 < x <= p.a2:
            return x, _zone_time(p.zone_offset, p.a1, x, (1 - b) * v1, p.omega)
    return math.nan, math.nan


def existence_threshold(p: Parameters) -> float:
    """``F*``: the force at which ``C`` changes sign (N); a limit cycle needs ``F > F*``."""
    b = p.b
    return (2 * b - b * b) * p.K * (p.a1**2 - p.a3**2) / (2 * ((1 - b) ** 2 * (p.a2 - p.a1) + (p.a3 - p.a4)))


def grazing_release(p: Parameters) -> float:
    """``A``: released from rest at ``-A`` the swing after the first impulse turns exactly at a3."""
    a_sq = p.a1**2 + (p.a3**2 - p.a1**2 - 2 * p.f * (p.a2 - p.a1) / p.omega2) / (1 - p.b) ** 2
    if a_sq <= p.a1**2:
        raise ValueError(f"a1..a4 = {p.a1}, {p.a2}, {p.a3}, {p.a4}, F = {p.F}: no release grazes a3 "
                         "(the first impulse alone carries the swing past it)")
    return math.sqrt(a_sq)


def grazing_limit(p: Parameters) -> float:
    """The velocity before the next impact at a1 if the touch at a3 counts as an impact with speed 0."""
    return math.sqrt(p.omega2 * (p.a3**2 - p.a1**2) + 2 * p.f * (p.a3 - p.a4))


SECONDS_PER_DAY = 86_400.0


def daily_rate(period: float, natural_period: float) -> float:
    """Seconds gained per day by a clock counting ``natural_period`` per swing of period ``period``."""
    return SECONDS_PER_DAY * (natural_period / period - 1.0)


def first_order_zone_change(start: float, end: float, amplitude: float, omega: float, f: float) -> float:
    """The first-order time cost of a zone, force per unit mass ``f`` along the motion, on an arc of ``amplitude``."""
    a2 = amplitude * amplitude
    return f * (math.sqrt(a2 - start * start) - math.sqrt(a2 - end * end)) / (omega**3 * a2)


def zone_amplitude(p: Parameters, release: float) -> float:
    """Amplitude of the arc entering the zone (a1, a2) after the impact at a1, released from rest at ``-release``."""
    return math.sqrt(p.a1**2 + (1 - p.b) ** 2 * (release**2 - p.a1**2))
