"""The checks of Sec. 2, the system model: the period mainly set by the spring and changed by the impacts
and the impulses, each measured from the simulated phases of a Fig. 3 case.
"""

from __future__ import annotations

import math

import xarray as xr

from ..model.events import EventKind
from .evidence import Evidence, Verdict, check, events_of, fig3_scenes, fmt, params_of, within


def phase_shares(ds: xr.Dataset) -> dict[str, float]:
    """The last cycle's period split by the sine phase ``atan2(x, v/w)`` of its simulated events, which free flight
    advances at ``w``: ``T = 2 pi/w + impacts + impulses + drift``; ``residual`` is the simulated period less that."""
    p, w = params_of(ds), params_of(ds).omega
    t, x, before, after = (ds[f"event_{k}"].values for k in ("time", "position", "velocity_before", "velocity_after"))
    start = events_of(ds, EventKind.IMPACT_A1)[-2]
    if list(ds["event_kind"].values[start:start + 5]) != [1, 2, 3, 4, 1]:
        raise ValueError("the last cycle's events must be a1, a2, a3, a4, a1")

    def phase(i: int, v: float) -> float:
        return math.atan2(x[i], v / w)

    def turned(a: float, b: float) -> float:
        """The phase from ``a`` to ``b``, in (-pi, pi]."""
        return math.pi - (math.pi - (b - a)) % (2 * math.pi)

    # an impact slows the motion at a fixed position: the phase steps back (a delay)
    impacts = sum(turned(phase(i, after[i]), phase(i, before[i])) for i in (start, start + 2)) / w
    impulses = sum((t[i + 1] - t[i]) - turned(phase(i, after[i]), phase(i + 1, before[i + 1])) / w
                   for i in (start, start + 2))
    end = start + 4
    drift, period = turned(phase(start, before[start]), phase(end, before[end])) / w, t[end] - t[start]
    return {"period": period, "natural": p.natural_period, "impacts": float(impacts), "impulses": float(impulses),
            "drift": drift, "residual": period - (p.natural_period + impacts + impulses + drift)}


def _shares_text(s: dict, case: str) -> str:
    change = s["period"] - s["natural"]
    return (f"T = {fmt(s['period'])} s against 2 pi/w = {fmt(s['natural'])} s (case {case}, last cycle): "
            f"{fmt(change, 4)} s ({fmt(100 * change / s['natural'], 3)}%), of which the impacts "
            f"{fmt(s['impacts'], 4)} s and the impulses {fmt(s['impulses'], 4)} s")


@check(scenes=fig3_scenes, args=("case",),
       threshold="'mainly determined' taken as a period within the tolerance of 2 pi sqrt(M/K)")
def period_mainly_spring(claim, ev: Evidence) -> Verdict:
    """Sec. 2: ``|T - 2 pi/w| / (2 pi/w)`` within the tolerance."""
    s = phase_shares(ev.fig3[claim["args"]["case"]])
    return Verdict(_shares_text(s, claim["args"]["case"]),
                   within(abs(s["period"] - s["natural"]) / s["natural"], claim["tolerance"]))


@check(scenes=fig3_scenes, args=("case",))
def period_shares(claim, ev: Evidence) -> Verdict:
    """Sec. 2: the impacts and the impulses each change the period by a share far above the residual."""
    s = phase_shares(ev.fig3[claim["args"]["case"]])
    both = bool(abs(s["impacts"]) > 1e3 * abs(s["residual"]) and abs(s["impulses"]) > 1e3 * abs(s["residual"]))
    return Verdict(_shares_text(s, claim["args"]["case"]), both, note=(
        "measured from the simulated events: the jump of the sine phase atan2(x, v/w) at each impact (a delay) and "
        "each zone's time less its phase advance (an advance); the free flight advances the phase at w, so the shares "
        f"and the cycle's phase drift {fmt(s['drift'], 2)} s sum to the simulated period within "
        f"{fmt(s['residual'], 2)} s"))
