"""The closed forms of whole cycles, the engine of :mod:`escapement.solvers.cycles`: from the event loop's first
impact at a1, the return map of ``v**2`` gives each cycle's velocity, one ``crossing`` call the arcs of the
distinct cycles, and TwoSum the impact times; where they do not apply, a string says why.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.cycle_map import CycleMap, cycle_map
from ..model.kinematics import arc_maximum, crossing, two_sum
from ..model.limits import RunLimits, RunSpec
from ..model.parameters import Parameters
from ..model.status import Status
from .describe import CycleTable
from .kernel import A1, PLAN, EventRun, kinds_from, rows

__all__ = ["GRAZING_SPEED_SQ", "Cycles", "closed_form_cycles", "distinct_cycles", "first_impact",
           "prepared", "table_rows"]

#: an arc grazes where it arrives with ``v**2`` at most this times its largest, ``w**2 (x - c)**2 + v0**2``: there
#: the closed form and the event loop would no longer agree to 1e-14
GRAZING_SPEED_SQ = 1e-3
#: ``2**31 + 1``: the split of a period into its 22 leading bits and the rest, for exact products
_SPLIT = float(2**31 + 1)
#: the arcs of a cycle, for messages
_ARCS = ("the force arc a1 -> a2", "the free swing a2 -> a3", "the force arc a3 -> a4", "the free swing a4 -> a1")


def prepared(params: Parameters) -> dict[str, np.ndarray]:
    """The terms of a cycle's four arcs from the impact at a1 (the event loop's rows) as ``(4, 1)`` columns."""
    table = rows(params)
    states = (A1, *PLAN[:-1])  # the event that starts each arc
    plan = [table[state] for state in states]
    columns = {name: np.array([[getattr(row, name)] for row in plan]) for name in ("u0", "q", "k", "direction")}
    columns["target"] = np.array([[automaton.position(row.following, params)] for row in plan])
    columns["centre"] = np.array([[automaton.centre(automaton.ARCS[s].mode, params.zone_offset)] for s in states])
    columns["x_from"] = np.array([[automaton.position(s, params)] for s in states])
    columns["impact"] = np.array([[automaton.is_impact(s)] for s in states])
    return columns


class Cycles(NamedTuple):
    """A run's ``distinct`` cycles (the last stands for every later one at the fixed point), and for the impact
    times the first ``t1``, the last period ``big`` (``big_hi`` its 22 leading bits), the prefix sums ``hi + lo``."""

    v: np.ndarray
    period: np.ndarray
    largest_displacement: np.ndarray
    t1: float
    big: float
    big_hi: float
    hi: np.ndarray
    lo: np.ndarray
    residual: float
    distinct: int
    events_before: int = 0  #: the events up to the first impact at a1, that impact included


def first_impact(params: Parameters, x: float, v: float) -> tuple[float, float, int] | str:
    """Time, velocity and events up to the first impact at a1 (the event loop's), or why there is none."""
    if automaton.reverses(1.0, automaton.impact_factor(params.b)):
        return f"b = {params.b!r}: the impact reverses the velocity (the run chatters)"
    run = EventRun(RunSpec(params, x, v, RunLimits(n_cycles=1)))
    run.advance(run.limits.max_events)
    outcome = run.outcome
    if outcome.status is not Status.COMPLETED:
        return (f"the event solver's first cycle from the release did not complete "
                f"({outcome.status.value}: {outcome.message})")
    t, v_before, _ = run.take()
    i = int(np.flatnonzero(kinds_from(run.first, 0, len(t)) == A1)[0])
    return float(t[i]), float(v_before[i]), i + 1


def _transient(cmap: CycleMap, v1: float, n: int) -> int:
    """The first cycles whose ``v_k**2`` may differ from the float ``v***2`` (the caller checks)."""
    star, delta, mu = cmap.fixed_point_sq, v1 * v1 - cmap.fixed_point_sq, cmap.mu
    if delta == 0.0 or mu == 0.0:
        return min(n, 2)
    if not (star > 0.0 and 0.0 < mu < 1.0 and math.isfinite(delta)):
        return n
    # |delta| mu**(k-1) below a quarter of an ulp of v***2: k - 1 > log(2**-55 v***2 / |delta|) / log(mu)
    ratio = 2.0**-55 * star / abs(delta)
    k = 0 if ratio >= 1.0 else math.ceil(math.log(ratio) / math.log(mu))
    return min(n, k + 3)


def _prefix_sums(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Prefix sums ``D_i = sum_{j<i} d_j`` as ``hi + lo``: ``hi`` is ``cumsum``, ``lo`` the sum of its roundings
    ``r_j = hi_j + d_j - hi_{j+1}``, each exact (TwoSum's error)."""
    hi = np.zeros(len(d) + 1)
    np.cumsum(d, out=hi[1:])
    s, e = two_sum(hi[:-1], d)
    lo = np.zeros_like(hi)
    np.cumsum((s - hi[1:]) + e, out=lo[1:])
    return hi, lo


def _window(values: np.ndarray, start: int, stop: int) -> np.ndarray:
    """Entries ``start .. stop - 1`` of ``values`` extended for ever by repeating its last, as a new array."""
    return values[np.minimum(np.arange(start, stop), len(values) - 1)]


def _arcs(params: Parameters, col: dict[str, np.ndarray], v: np.ndarray):
    """The four arcs of the cycles of velocities ``v`` at a1, as ``crossing`` on ``(4, m)`` arrays."""
    starts = np.empty((len(col["impact"]), len(v)))
    speed = v
    for i, impact in enumerate(col["impact"][:, 0]):
        speed = automaton.velocity_after(speed, params.b) if impact else speed
        starts[i] = speed
        speed = col["direction"][i, 0] * np.sqrt(abs(speed * speed + col["k"][i, 0]))  # as crossing arrives
    reached, dt, arrival, angle = crossing(col["u0"], col["q"], col["k"], starts, params.omega, col["direction"], np)
    return starts, reached, dt, arrival, angle


def distinct_cycles(params: Parameters, col: dict[str, np.ndarray], t1: float, v1: float, n: int,
                     most: int | None = None) -> Cycles | str:
    """The distinct cycles of ``n`` from the first impact at a1 ``(t1, v1)``, or why the closed form does not apply,
    also where more than ``most`` would be evaluated at once; a NaN is a decision here (``np.errstate``)."""
    cmap = cycle_map(params)
    for count in (_transient(cmap, v1, n), n):  # where the bound does not hold, every cycle
        if most is not None and count > most:
            return (f"the transient lasts more than the {most:_} cycles the memory budget holds at once (mu = "
                    f"{cmap.mu!r}): the closed form evaluates it in one piece")
        v_sq = cmap.velocity_sq(v1, np.arange(1, count + 1))
        same = v_sq == cmap.fixed_point_sq
        same[0] = False  # the first is the event solver's v1
        if count == n or same[-1]:
            break
    m = int(np.flatnonzero(~same)[-1]) + 1  # cycles 1 .. m differ from the fixed point; m + 1 .. n are it
    fixed = m < n  # the last distinct cycle stands for cycles m + 1 .. n, at the fixed point
    if fixed:
        m += 1
    positive = v_sq[:m] > 0.0
    negative = None  # the reason at the first cycle whose v**2 is not positive, if the arcs before it hold
    if not positive.all():
        q = int(np.flatnonzero(~positive)[0])  # q >= 1: v_sq[0] is about v1**2 > 0
        negative = f"the closed form's v**2 is not positive at cycle {q + 1} ({float(v_sq[q])!r} m**2/s**2)"
        m, fixed = max(q, 1), False
    v = np.sqrt(v_sq[:m])
    v[0] = v1
    starts, reached, dt, arrival, angle = _arcs(params, col, v)
    omega = params.omega
    largest = (omega * (col["x_from"] - col["centre"])) ** 2 + starts * starts
    ok = reached & (arrival * arrival > GRAZING_SPEED_SQ * largest)
    if not ok.all():
        j = int(np.flatnonzero(~ok.all(axis=0))[0])
        arc = int(np.flatnonzero(~ok[:, j])[0])
        cycle = f"cycles {j + 1} .. {n} (the fixed point)" if fixed and j == m - 1 else f"cycle {j + 1}"
        what = ("cannot reach its end (the run leaves the regime: the escapement stops or the mass turns back "
                "in the zone)" if not reached[arc, j] else
                f"grazes its end (arrives with v**2 = {float(arrival[arc, j] ** 2):.3g} m**2/s**2, at most "
                f"{GRAZING_SPEED_SQ:g} of the arc's largest, {float(largest[arc, j]):.3g})")
        return f"{_ARCS[arc]} of {cycle} {what}"
    if negative is not None:
        return negative
    period = ((dt[0] + dt[1]) + dt[2]) + dt[3]  # the event solver's order
    amplitude = np.max(arc_maximum(col["centre"], col["x_from"], starts, omega, angle, col["target"], arrival), axis=0)
    amplitude = np.maximum(amplitude, col["x_from"][0, 0])  # the impact at a1 begins the cycle
    # the map against the arcs: the arrival at a1 from cycle j is v_{j+1} (and at the fixed point, itself)
    following = np.append(v[1:], v[-1]) if fixed else v[1:]
    predicted = arrival[3, :len(following)]
    residual = float(np.max(np.abs(predicted - following) / following)) if len(following) else 0.0
    big = period[-1]
    hi, lo = _prefix_sums(period - big)
    sigma = big * _SPLIT
    return Cycles(v, period, amplitude, t1, big, sigma - (sigma - big), hi, lo, residual, m)


def table_rows(c: Cycles, start: int, stop: int) -> tuple[CycleTable, float]:
    """Cycles ``start + 1 .. stop`` and the time that ends cycle ``stop``, each from its own ``k`` alone (any window
    is the same numbers): ``t_k = t1 + (k - 1) T + D_{k-1}``, ``D`` the prefix sums of ``T_j - T``."""
    k = np.arange(start, stop + 1, dtype=float)  # k - 1 for cycles start + 1 .. stop, and stop for the end
    s, e1 = two_sum(k * c.big_hi, c.t1)
    s, e2 = two_sum(s, _window(c.hi, start, stop + 1))
    t = s + (((e1 + e2) + k * (c.big - c.big_hi)) + _window(c.lo, start, stop + 1))
    table = CycleTable(impact_time=t[:-1], velocity_before_impact=_window(c.v, start, stop),
                       period=_window(c.period, start, stop),
                       largest_displacement=_window(c.largest_displacement, start, stop))
    return table, float(t[-1])


def closed_form_cycles(spec: RunSpec, most: int | None = None) -> Cycles | str:
    """The distinct cycles of the run ``spec`` (at most ``most`` at once), or why there are none."""
    first = first_impact(spec.params, spec.x0, spec.v0)
    if isinstance(first, str):
        return first
    with np.errstate(all="ignore"):  # a NaN is a decision here, not a warning
        done = distinct_cycles(spec.params, prepared(spec.params), first[0], first[1], spec.limits.n_cycles, most)
    return done if isinstance(done, str) else done._replace(events_before=first[2])
