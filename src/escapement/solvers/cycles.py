"""Per-cycle closed forms: a run's cycle table from the return map of ``v**2``, without walking its events.

The map (derived from the arcs, not fitted). Cycle ``k`` runs from the ``k``-th impact at a1 to the next
through the four arcs the automaton gives (:func:`escapement.solvers.exact.stages`), each a harmonic arc
about its mode's centre:

0. a1 to a2 in the zone (a1, a2), centre ``+F/K``, after the impact ``v -> (1 - b) v``;
1. a2 to a3 free (centre 0), over the top, arriving moving left;
2. a3 to a4 in the zone (a4, a3), centre ``-F/K``, after the impact ``v -> (1 - b) v``;
3. a4 to a1 free, round the bottom, arriving moving right.

On an arc from ``x`` to ``y`` about ``c`` energy gives ``v_y**2 = v_x**2 + k``,
``k = w**2 (x - y)(x + y - 2 c)`` (:attr:`~escapement.solvers.exact.Stage.k`), so with ``f = F/M``

* ``k0 = w**2 (a1**2 - a2**2) + 2 f (a2 - a1)``, ``k1 = w**2 (a2**2 - a3**2)``,
* ``k2 = w**2 (a3**2 - a4**2) + 2 f (a3 - a4)``, ``k3 = w**2 (a4**2 - a1**2)``,

and each impact multiplies ``v**2`` by ``beta = (1 - b)**2``. One cycle:

``v_{k+1}**2 = beta (beta v_k**2 + k0 + k1) + k2 + k3 = mu v_k**2 + c``, with

* ``mu = (1 - b)**4``, ``1 - mu = b (2 - b) (1 + (1 - b)**2)`` (written so: no cancellation as ``b -> 0``);
* ``c = beta (k0 + k1) + k2 + k3 = b (2 - b) w**2 (a3**2 - a1**2) + 2 f [(1 - b)**2 (a2 - a1) + (a3 - a4)]``;
* the fixed point ``v***2 = c / (1 - mu)``; in the symmetric case (``a3 = -a1``, ``a4 = -a2``)
  ``v***2 = 2 f (a2 - a1) / (b (2 - b))``.

The map is linear in ``v**2``, so ``v_k**2 = v***2 + (v_1**2 - v***2) mu**(k-1)`` for every ``k`` at once
(:meth:`CycleMap.velocity_sq`).

Every other per-cycle number follows from ``v_k``. The velocities at the arcs' starts come from energy
(``sqrt(v**2 + k)`` and the impact law: the event solver's arithmetic, operation for operation), and each arc's
time is :func:`~escapement.model.kinematics.crossing`, the clockwise angle (``atan2`` of the cross and dot
products of the start and end states in the phase plane) over ``w``: the four arcs of all the cycles in one call
on a ``(4, m)`` array. The period is their sum in the event solver's order, the amplitude (the largest ``x``
between impact ``k`` and ``k+1``, as :class:`~escapement.solvers.result.CycleTable` defines it) the largest of
``a1`` and the arcs' :func:`~escapement.model.kinematics.arc_maximum`.

Distinct cycles only. From some cycle on, ``v_k**2`` is the float ``v***2`` (the transient is below half an
ulp of it; rounding is monotone, so it stays there), and every cycle from there on is the same float: the arcs
are computed for the distinct cycles only (about ``45 / -log10(mu)`` of them) and the columns filled.

Impact times. ``t_k = t_1 + sum_{j<k} T_j = t_1 + (k-1) T + sum_{j<k} (T_j - T)`` with ``T`` the last
period (the fixed point's once converged): ``T_j - T`` is exact (Sterbenz) and zero once converged; ``(k-1) T``
is an exact product (``T`` split into its 22 leading bits and the rest, ``k < 2**31``) plus a tiny one; the
remainders' prefix sums are compensated (the rounding error of each step of ``cumsum``, by TwoSum, summed
again); and the parts are added with TwoSum. ``t_k`` is then within about an ulp of the exact sum of the floats
``t_1 + sum T_j``, as the event solver's compensated sum of its events' durations is of its own; the two differ
by the periods' rounding, a few ulps.

When it applies. ``t_1`` and ``v_1``, the first impact at a1, come from the event solver's first partial
cycle (from the release: :class:`~escapement.solvers.exact.ClosedFormRun`, the loop of
:func:`~escapement.solvers.exact.solve_exact`, run for one cycle). The event solver makes the whole run
instead (``solve_exact`` with the same arguments; :attr:`CycleRun.fallback` says why) when

* ``b > 1`` (or ``b`` outside ``(0, 2)``): the impact reverses the velocity, the run chatters;
* the first partial cycle does not complete (the run stops, turns back in a zone or chatters before);
* a cycle's closed form leaves the regime: ``v_k**2`` not positive (NaN velocity), or an arc that cannot
  reach its end (a free swing whose turning point lies short of the next impact position: the escapement
  stops; a force arc that cannot reach a2 or a4: it turns back in the zone);
* or grazes: an arc arrives with ``v**2 <= GRAZING_SPEED_SQ (w**2 (x - c)**2 + v0**2)``, a speed within 3 %
  of the arc's largest (``w`` times its radius). Near a turning point the arrival phase amplifies the rounding
  of the velocity (by about the ratio of those speeds), and the closed form and the event solver, whose
  velocities differ by a few ulps, would no longer agree to 1e-14.

:func:`cross_check` (or ``solve_cycles(..., check=True)``) compares a run with ``solve_exact`` on every
quantity and raises :class:`CrossCheckError` beyond a relative 1e-14. That holds down to ``b`` of about 0.015
(the largest difference over a grid of forces and zones: 8.7e-15 at ``b = 0.015``, 1.3e-14 at ``b = 0.01``):
the event solver's own rounding, carried from cycle to cycle and damped only by ``mu = (1 - b)**4``, grows like
``eps / b`` in the velocity and the amplitude, while the closed form's does not (against 50 digits at
``b = 0.001``: the event solver 1.9e-14, the closed form 2.0e-15). The periods and impact times agree to a few
ulps at every ``b``.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.events import EventKind
from ..model.kinematics import VECTOR, arc_maximum, crossing
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .driver import check_memory
from .exact import SEGMENT, ClosedFormRun, solve_exact, stages
from .result import CycleTable, Exit, Solution
from .stream import DEFAULT_CHUNK, ChunkIterator, CycleStream, StreamSummary, check_chunk, iter_cycles

__all__ = [
    "CHUNK_BYTES_PER_CYCLE",
    "CLOSED_FORM",
    "CROSS_CHECK_RTOL",
    "GRAZING_SPEED_SQ",
    "CrossCheckError",
    "CycleChunks",
    "CycleMap",
    "CycleRun",
    "compare_tables",
    "cross_check",
    "cycle_map",
    "iter_closed_form_cycles",
    "solve_cycles",
]

#: the method's name (in :attr:`CycleRun.method` and the benchmark's rows)
CLOSED_FORM = "closed-form cycles"
#: an arc grazes where it arrives with ``v**2`` at most this times its largest, ``w**2 (x - c)**2 + v0**2``
GRAZING_SPEED_SQ = 1e-3
#: the relative difference :func:`cross_check` accepts on every quantity
CROSS_CHECK_RTOL = 1e-14
#: bytes per cycle at the peak of a run whose every cycle is distinct (the transient's arcs and work arrays, 357
#: measured with tracemalloc); a run that reaches the fixed point takes less (its columns and the impact times'
#: work arrays, about 100)
PEAK_BYTES_PER_CYCLE = 400
#: bytes per cycle of a streamed chunk: its rows and the impact times' work arrays (about 96 measured)
CHUNK_BYTES_PER_CYCLE = 128
#: the columns of a cycle table, in order
COLUMNS = ("impact_time", "velocity_before_impact", "period", "amplitude")
#: the arcs of a cycle, in words, for the reasons of a fallback
_ARCS = ("the force arc a1 -> a2", "the free swing a2 -> a3", "the force arc a3 -> a4", "the free swing a4 -> a1")
_A1 = int(EventKind.IMPACT_A1)
#: Veltkamp's splitter for 22 leading bits: (k - 1) T_hi is exact for k < 2**31
_SPLIT = float(2**31 + 1)


class CrossCheckError(AssertionError):
    """The closed-form cycles and the event solver disagree beyond the tolerance (:func:`cross_check`)."""


@dataclass(frozen=True)
class CycleMap:
    """The return map of the velocity before the impact at a1, linear in its square:
    ``v_{k+1}**2 = mu v_k**2 + c`` (see the module's docstring for the derivation).

    Examples
    --------
    >>> from escapement import Parameters
    >>> from escapement.solvers.cycles import cycle_map
    >>> m = cycle_map(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05))
    >>> round(m.mu, 12), round(m.c, 12), round(m.fixed_point_sq, 12)  # 1, m**2/s**2, m**2/s**2
    (0.6561, 0.543, 1.578947368421)
    """

    mu: float  #: ``(1 - b)**4``, the multiplier of ``v**2``
    c: float  #: the constant, m**2/s**2
    one_minus_mu: float  #: ``1 - mu = b (2 - b) (1 + (1 - b)**2)``
    log_mu: float  #: ``ln mu = 4 log1p(-b)`` (``-inf`` at ``b = 1``)

    @property
    def fixed_point_sq(self) -> float:
        """``v***2 = c / (1 - mu)``, m**2/s**2 (not positive: no fixed point)."""
        return self.c / self.one_minus_mu

    @property
    def fixed_point(self) -> float:
        """``v*``, m/s; NaN where ``v***2 <= 0``."""
        sq = self.fixed_point_sq
        return math.sqrt(sq) if sq > 0.0 else math.nan

    def velocity_sq(self, v1: float, k) -> np.ndarray:
        """``v_k**2 = v***2 + (v1**2 - v***2) mu**(k-1)`` for the cycle numbers ``k`` (1 for the first).

        ``mu**(k-1)`` as ``exp((k-1) ln mu)``, ``ln mu = 4 log1p(-b)``: the power of the rounded ``mu`` would
        carry its rounding ``k - 1`` times (a relative ``4 (k-1) eps``, up to ``eps / (e b)`` of ``v**2`` on the
        transient as ``b -> 0``), the exponential only that of ``(k-1) ln mu``."""
        star = self.fixed_point_sq
        steps = np.asarray(k, dtype=float) - 1.0
        decay = np.exp(steps * self.log_mu) if math.isfinite(self.log_mu) else np.power(self.mu, steps)
        return star + (v1 * v1 - star) * decay


def cycle_map(params: Parameters) -> CycleMap:
    """The constants of the return map ``v_{k+1}**2 = mu v_k**2 + c`` for any geometry (module docstring).

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).

    Returns
    -------
    CycleMap
        ``mu = (1 - b)**4``, ``c`` (m**2/s**2) and ``1 - mu``; the fixed point ``c / (1 - mu)``.
    """
    b, w2, f = params.b, params.omega2, params.f
    beta = (1.0 - b) * (1.0 - b)
    b2 = b * (2.0 - b)  # 1 - beta, without cancellation
    c = (b2 * w2 * ((params.a3 - params.a1) * (params.a3 + params.a1))
         + 2.0 * f * (beta * (params.a2 - params.a1) + (params.a3 - params.a4)))
    log_mu = 4.0 * math.log1p(-b) if b < 1.0 else -math.inf
    return CycleMap(mu=beta * beta, c=c, one_minus_mu=b2 * (1.0 + beta), log_mu=log_mu)


@dataclass(frozen=True, repr=False)
class CycleRun:
    """A run's cycle table from :func:`solve_cycles`: from the closed forms, or from the event solver where
    they do not apply (:attr:`fallback` says why; :attr:`solution` is then ``solve_exact``'s whole run)."""

    params: Parameters
    x0: float  #: initial displacement, m
    v0: float  #: initial velocity, m/s
    n_cycles: int  #: the cycles asked for
    status: Status
    message: str
    cycles: CycleTable  #: impact time (s), velocity before impact (m/s), period (s), amplitude (m)
    t_final: float  #: time of the impact at a1 that ends the last cycle (the event solver's t_final), s
    method: str  #: ``"closed-form cycles"``, or ``"exact"`` on a fallback
    fallback: str | None  #: why the event solver made the whole run; None where the closed form did
    cycle_map: CycleMap
    #: largest relative difference between the closed form's ``v_{k+1}`` and the arcs' arrival at a1 from
    #: ``v_k`` (the map against the energy of the arcs; NaN on a fallback)
    map_residual: float = math.nan
    distinct_cycles: int = 0  #: cycles whose arcs were computed (the rest repeat the fixed point's)
    exit: Exit = Exit()
    solution: Solution | None = None  #: the event solver's run, on a fallback

    @property
    def fell_back(self) -> bool:
        """True where the event solver made the whole run."""
        return self.fallback is not None

    @property
    def success(self) -> bool:
        """True when the requested cycles were reached."""
        return self.status.success

    def __repr__(self) -> str:
        how = self.method if self.fallback is None else f"{self.method}, fell back: {self.fallback}"
        return (f"<CycleRun> {self.status.value} ({how}): {len(self.cycles)} of {self.n_cycles} cycles, "
                f"t_final = {self.t_final:.6g} s, fixed point {self.cycle_map.fixed_point:.6g} m/s")


class _Prepared(NamedTuple):
    """What a run needs from its parameters alone: the map, the stages of a cycle, whether the event that
    starts each is an impact, and the stages' surfaces as ``(4, 1)`` columns."""

    cycle_map: CycleMap
    plan: tuple
    jumps: tuple
    columns: dict


_PREPARED: dict[bytes, _Prepared | None] = {}
_PREPARED_SIZE = 256
_BITS = struct.Struct(f"{len(MODEL_KEYS)}d").pack  # the parameters' bits (0.0 and -0.0 apart)


def _prepared(params: Parameters) -> _Prepared | None:
    """The four stages of a cycle from the impact at a1 (:func:`~escapement.solvers.exact.stages`), with the
    map; None where the automaton's cycle is not those four arcs (it always is: kept as a guard). Kept for
    :data:`_PREPARED_SIZE` parameter sets."""
    key = _BITS(*params.as_dict().values())
    if key in _PREPARED:
        return _PREPARED[key]
    if len(_PREPARED) >= _PREPARED_SIZE:
        _PREPARED.clear()
    table = stages(params)
    plan, jumps, kind, found = [], [], _A1, None
    for _ in range(4):
        stage = table[kind]
        if stage is None:
            break
        plan.append(stage)
        jumps.append(bool(automaton.is_impact(kind)))
        kind = stage.next_kind
    else:
        if kind == _A1 and not any(stage.at_a1 for stage in plan[:-1]):
            columns = {name: np.array([[getattr(stage, name)] for stage in plan])
                       for name in ("centre", "x_from", "target", "direction")}
            found = _Prepared(cycle_map(params), tuple(plan), tuple(jumps), columns)
    _PREPARED[key] = found
    return found


class _Cycles(NamedTuple):
    """A closed-form run's distinct cycles (``distinct`` of them; the last stands for every later cycle once
    at the fixed point) and what its impact times need: the first ``t1``, the last period ``big`` and its 22
    leading bits ``big_hi``, the compensated prefix sums ``hi + lo`` of the periods less ``big``."""

    v: np.ndarray
    period: np.ndarray
    amplitude: np.ndarray
    t1: float
    big: float
    big_hi: float
    hi: np.ndarray
    lo: np.ndarray
    residual: float
    distinct: int


def _first_impact(params: Parameters, x: float, v: float) -> tuple[float, float, int] | str:
    """Time and velocity of the first impact at a1 from the release, by the event solver's loop run for one
    cycle, and the events up to it, that impact included (the run's events less the cycle's four); or why
    the run does not complete it."""
    run = ClosedFormRun(params, x, v, RunLimits(n_cycles=1), keep_events=False)
    run.advance(SEGMENT)
    outcome = run.outcome
    if outcome is None or outcome.status is not Status.COMPLETED or not run.cycle_columns[0]:
        said = "did not end" if outcome is None else f"{outcome.status.value}: {outcome.message}"
        return f"the event solver's first cycle from the release did not complete ({said})"
    return float(run.cycle_columns[0][0]), float(run.cycle_columns[1][0]), int(run.events) - 4


def _start(params: Parameters, prep: _Prepared | None, x: float, v: float) -> tuple[float, float, int] | str:
    """The first impact at a1 (:func:`_first_impact`), or why the closed form does not apply from the start."""
    if not 0.0 < params.b <= 1.0:
        return f"b = {params.b!r} is outside (0, 1]: the impact reverses the velocity (the run chatters)"
    if prep is None:
        return "the automaton's cycle is not the four arcs a1 -> a2 -> a3 -> a4 -> a1"
    return _first_impact(params, x, v)


def _transient(cmap: CycleMap, v1: float, n: int) -> int:
    """How many of the first cycles to evaluate ``v_k**2`` for: past them it is the float ``v***2`` (checked
    by the caller, who evaluates them all where this bound does not hold)."""
    star, delta, mu = cmap.fixed_point_sq, v1 * v1 - cmap.fixed_point_sq, cmap.mu
    if delta == 0.0 or mu == 0.0:
        return min(n, 2)
    if not (star > 0.0 and 0.0 < mu < 1.0 and math.isfinite(delta)):
        return n
    # |delta| mu**(k-1) below a quarter of an ulp of v***2: k - 1 > log(2**-55 v***2 / |delta|) / log(mu)
    ratio = 2.0**-55 * star / abs(delta)
    k = 0 if ratio >= 1.0 else math.ceil(math.log(ratio) / math.log(mu))
    return min(n, k + 3)


def _two_sum(a, b):
    """Knuth's TwoSum on arrays: ``s + e == a + b`` exactly, ``s = fl(a + b)``."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _prefix_sums(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exclusive prefix sums ``D_i = sum_{j<i} d_j``, ``i = 0 .. len(d)``, as ``hi + lo``, compensated: ``hi`` is
    ``cumsum``, and with ``r_j = hi_j + d_j - hi_{j+1}`` exactly (TwoSum of ``hi_j + d_j``, less ``hi_{j+1}``,
    which is that sum's rounding: the difference is exact) ``D_i = hi_i + sum_{j<i} r_j``; ``lo`` is that sum."""
    hi = np.zeros(len(d) + 1)
    np.cumsum(d, out=hi[1:])
    before, after = hi[:-1], hi[1:]
    s, e = _two_sum(before, d)
    lo = np.zeros_like(hi)
    np.cumsum((s - after) + e, out=lo[1:])
    return hi, lo


def _window(values: np.ndarray, start: int, stop: int) -> np.ndarray:
    """Entries ``start .. stop - 1`` of ``values`` extended for ever by repeating its last."""
    if len(values) >= stop:
        return values[start:stop]
    out = np.empty(stop - start)
    head = values[start:] if start < len(values) else values[:0]
    out[:len(head)] = head
    out[len(head):] = values[-1]
    return out


def _arcs(params: Parameters, prep: _Prepared, v: np.ndarray):
    """The four arcs of the cycles that start with the velocities ``v`` before the impact at a1, in one
    :func:`~escapement.model.kinematics.crossing` call on ``(4, m)`` arrays: ``(start velocities, reached,
    times, arrival velocities, angles)``. The arrival of each arc, the start of the next, is computed as
    ``crossing`` computes it (``d sqrt(v**2 + k)``), the impact law applied where the event is an impact."""
    b = params.b
    starts = np.empty((4, len(v)))
    speed = v
    for i, (stage, jump) in enumerate(zip(prep.plan, prep.jumps)):
        speed = automaton.velocity_after(speed, b, True) if jump else speed
        starts[i] = speed
        speed = np.sqrt(np.maximum(speed * speed + stage.k, 0.0))
        if stage.direction < 0.0:  # d * sqrt(): the sign, exactly
            speed = -speed
    col = prep.columns
    reached, dt, arrival, angle = crossing(col["centre"], col["x_from"], starts, params.omega, col["target"],
                                           col["direction"], VECTOR)
    return starts, reached, dt, arrival, angle


def _distinct_cycles(params: Parameters, prep: _Prepared, t1: float, v1: float, n: int,
                     most: int | None = None) -> _Cycles | str:
    """The distinct cycles of ``n`` from the first impact at a1 ``(t1, v1)``, or why the closed form does not
    apply (a string): also where more than ``most`` cycles would have to be evaluated at once (a streamed
    run's memory budget: the transient, not the run, sets how many). Under ``np.errstate(all="ignore")``: a
    NaN is a decision here, not a warning."""
    cmap, col = prep.cycle_map, prep.columns
    star = cmap.fixed_point_sq
    count = _transient(cmap, v1, n)
    longer = (f"the transient lasts more than the {most:_} cycles the memory budget holds at once (mu = "
              f"{cmap.mu!r}): the closed form evaluates it in one piece") if most is not None else ""
    if most is not None and count > most:
        return longer
    v_sq = cmap.velocity_sq(v1, np.arange(1, count + 1))
    same = v_sq == star
    same[0] = False  # the first is the event solver's v1
    if count < n and not same[-1]:  # the bound did not hold: every cycle
        if most is not None and n > most:
            return longer
        count = n
        v_sq = cmap.velocity_sq(v1, np.arange(1, n + 1))
        same = v_sq == star
        same[0] = False
    differ = np.flatnonzero(~same)
    m = int(differ[-1]) + 1  # cycles 1 .. m differ from the fixed point; m + 1 .. n are it
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
    starts, reached, dt, arrival, angle = _arcs(params, prep, v)
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
    amplitude = np.max(arc_maximum(col["centre"], col["x_from"], starts, omega, angle, col["target"], VECTOR),
                       axis=0)
    amplitude = np.maximum(amplitude, prep.plan[-1].target)  # the impact at a1 begins the cycle
    # the map against the arcs: the arrival at a1 from cycle j is v_{j+1} (and at the fixed point, itself)
    following = np.append(v[1:], v[-1]) if fixed else v[1:]
    predicted = arrival[3, :len(following)]
    residual = float(np.max(np.abs(predicted - following) / following)) if len(following) else 0.0
    big = period[-1]
    hi, lo = _prefix_sums(period - big)
    sigma = big * _SPLIT
    return _Cycles(v, period, amplitude, t1, big, sigma - (sigma - big), hi, lo, residual, m)


def _rows(c: _Cycles, start: int, stop: int) -> tuple[CycleTable, float]:
    """Cycles ``start + 1 .. stop`` of the run (table rows ``start .. stop - 1``), and the time of the impact
    at a1 that ends cycle ``stop``. Impact times: ``t_k = t1 + (k - 1) T + D_{k-1}``, ``D`` the prefix sums of
    ``T_j - T``; each entry from its own ``k`` alone, so that any window of cycles is the same numbers."""
    k = np.arange(start, stop + 1, dtype=float)  # k - 1 for cycles start + 1 .. stop, and stop for the end
    s, e1 = _two_sum(k * c.big_hi, c.t1)
    s, e2 = _two_sum(s, _window(c.hi, start, stop + 1))
    t = s + (((e1 + e2) + k * (c.big - c.big_hi)) + _window(c.lo, start, stop + 1))
    table = CycleTable(impact_time=t[:-1], velocity_before_impact=_window(c.v, start, stop),
                       period=_window(c.period, start, stop), amplitude=_window(c.amplitude, start, stop))
    return table, float(t[-1])


def solve_cycles(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int,
    memory_budget: int | None = None,
    check: bool = False,
    rtol: float = CROSS_CHECK_RTOL,
) -> CycleRun:
    """The cycle table of :func:`~escapement.solvers.exact.solve_exact` for ``n_cycles`` cycles from the
    closed forms of each cycle, in a few vectorised NumPy calls (see the module's docstring).

    The first partial cycle (from the release to the first impact at a1) is the event solver's; every cycle
    from there follows from the return map ``v_{k+1}**2 = mu v_k**2 + c``. Where the closed form does not
    apply (``b > 1``, a run that stops, turns back or chatters, a grazing arc) the event solver makes the
    whole run, ``solve_exact(params, x0, v0, n_cycles=n_cycles, record_trajectory=False)``, whose numbers
    the result then holds exactly; :attr:`CycleRun.fallback` says why.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles (cycle ``k`` runs from the ``k``-th impact at a1 to the next).
    memory_budget : int, optional
        The most bytes the result and its work arrays may take (default
        :data:`~escapement.model.limits.MEMORY_BUDGET`), :data:`PEAK_BYTES_PER_CYCLE` a cycle.
    check : bool, default False
        Compare with ``solve_exact`` on every quantity (:func:`cross_check`); raise :class:`CrossCheckError`
        beyond ``rtol``.
    rtol : float, default 1e-14
        The relative difference the check accepts.

    Returns
    -------
    CycleRun
        ``status``, ``message``, ``cycles`` (impact time in s, velocity before impact in m/s, period in s,
        amplitude in m), ``t_final`` (s), ``method``, ``fallback`` and the map's constants.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0``, ``n_cycles`` or ``memory_budget`` is invalid, or
        (:class:`~escapement.model.limits.MemoryBudgetError`) the run would exceed ``memory_budget``.
    CrossCheckError
        With ``check``, if a quantity differs from ``solve_exact``'s by more than ``rtol`` (relative).

    Examples
    --------
    >>> from escapement import Parameters
    >>> from escapement.solvers.cycles import solve_cycles
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> run = solve_cycles(p, x0=1.0, n_cycles=50, check=True)
    >>> run.method, run.status.value, len(run.cycles)
    ('closed-form cycles', 'completed', 50)
    >>> round(float(run.cycles.period[-1]), 4)  # s
    6.2957
    >>> chattering = solve_cycles(Parameters(M=1.0, K=1.0, F=1.0, b=1.5, a1=-0.1, a2=0.05), x0=1.0, n_cycles=5)
    >>> chattering.method, chattering.status.value, chattering.fell_back
    ('exact', 'chattering', True)
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, memory_budget=memory_budget)
    n = limits.n_cycles
    check_memory(limits, 0.0, PEAK_BYTES_PER_CYCLE, "its cycle table and the closed form's work arrays",
                 "stream the cycles in constant memory with escapement.solvers.iter_cycles")
    prep = _prepared(params)
    cmap = cycle_map(params) if prep is None else prep.cycle_map
    first = _start(params, prep, x, v)
    reason = first if isinstance(first, str) else None
    if reason is None:
        with np.errstate(all="ignore"):
            done = _distinct_cycles(params, prep, first[0], first[1], n)
        reason = done if isinstance(done, str) else None
    if reason is not None:
        exact = solve_exact(params, x, v, n_cycles=n, record_trajectory=False, memory_budget=memory_budget)
        run = CycleRun(params, x, v, n, exact.status, exact.message, exact.cycles, exact.t_final, "exact", reason,
                       cmap, exit=exact.exit, solution=exact)
    else:
        table, t_final = _rows(done, 0, n)
        run = CycleRun(params, x, v, n, Status.COMPLETED, f"completed {n} cycles", table, t_final, CLOSED_FORM,
                       None, cmap, map_residual=done.residual, distinct_cycles=done.distinct)
    if check:
        cross_check(run, rtol)
    return run


class CycleChunks(ChunkIterator):
    """:func:`solve_cycles`'s cycle table in chunks (see :func:`iter_closed_form_cycles`); once it is
    exhausted, :attr:`summary` says how the run ended."""

    def __init__(self, cycles: _Cycles | None, events_before: int, n: int, chunk: int,
                 fallback: CycleStream | None, reason: str | None, cmap: CycleMap) -> None:
        self._cycles, self._events_before, self._n, self._chunk = cycles, events_before, n, chunk
        self._fallback, self._done = fallback, 0
        self.method = "exact" if fallback is not None else CLOSED_FORM  #: which solver makes the chunks
        self.fallback = reason  #: why the event solver makes the run; None where the closed forms do
        self.cycle_map = cmap
        self.distinct_cycles = 0 if cycles is None else cycles.distinct  #: cycles whose arcs were computed
        self.map_residual = math.nan if cycles is None else cycles.residual  #: as :attr:`CycleRun.map_residual`

    def __next__(self) -> CycleTable:
        if self._fallback is not None:
            try:
                return next(self._fallback)
            except StopIteration:
                self._summary = self._fallback.summary
                raise
        if self._done >= self._n:
            raise StopIteration
        stop = min(self._done + self._chunk, self._n)
        with np.errstate(all="ignore"):
            table, t_end = _rows(self._cycles, self._done, stop)
        # a chunk owns its arrays, as the event solver's do: a window inside the transient is a view of it
        table = CycleTable(impact_time=table.impact_time, **{
            name: getattr(table, name).copy() for name in COLUMNS if name != "impact_time"})
        self._done = stop
        if stop == self._n:  # a cycle is four events: the impacts at a1 and a3 and the ends of their zones
            self._summary = StreamSummary(Status.COMPLETED, f"completed {self._n} cycles", Exit(), t_end, self._n,
                                          self._events_before + 4 * self._n)
        return table


def iter_closed_form_cycles(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int,
    chunk: int = DEFAULT_CHUNK,
    memory_budget: int | None = None,
) -> CycleChunks:
    """The cycle table of :func:`solve_cycles` for the same arguments, in chunks of at most ``chunk`` cycles,
    in memory that does not grow with the run: the distinct cycles are computed once, and each chunk's
    rows from them (every row from its own cycle number alone, so the chunks put together are
    ``solve_cycles``'s table number for number). The distinct cycles are those of the transient (about
    ``45 / -log10(mu)``, whatever the run's length); where they would not fit the memory budget, or the
    closed form does not apply, the event solver streams the run
    (:func:`~escapement.solvers.stream.iter_cycles`) and :attr:`CycleChunks.fallback` says why.

    Parameters
    ----------
    params : Parameters
        The model's parameters (SI units: kg, N/m, N, 1, m).
    x0 : float
        Initial displacement at ``t = 0+``, m.
    v0 : float, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles (cycle ``k`` runs from the ``k``-th impact at a1 to the next).
    chunk : int, default 100_000
        The most cycles a chunk holds.
    memory_budget : int, optional
        The most bytes a chunk (:data:`CHUNK_BYTES_PER_CYCLE` a cycle) and the transient's distinct cycles
        (:data:`PEAK_BYTES_PER_CYCLE` a cycle while they are computed) may take together (default
        :data:`~escapement.model.limits.MEMORY_BUDGET`).

    Returns
    -------
    CycleChunks
        An iterator of :class:`~escapement.solvers.result.CycleTable` chunks (impact time in s, velocity
        before impact in m/s, period in s, amplitude in m); its ``summary`` (status, message, end time)
        once exhausted, ``method`` and ``fallback``.

    Raises
    ------
    TypeError
        If ``params`` is not a :class:`~escapement.Parameters`.
    ParameterError
        If ``x0``, ``v0``, ``n_cycles``, ``chunk`` or ``memory_budget`` is invalid, or
        (:class:`~escapement.model.limits.MemoryBudgetError`) a chunk would exceed ``memory_budget``.

    Examples
    --------
    >>> import numpy as np
    >>> from escapement import Parameters
    >>> from escapement.solvers.cycles import iter_closed_form_cycles, solve_cycles
    >>> p = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
    >>> chunks = iter_closed_form_cycles(p, x0=1.0, n_cycles=250, chunk=100)
    >>> times = [c.impact_time for c in chunks]  # s
    >>> [len(t) for t in times], chunks.method, chunks.summary.status.value
    ([100, 100, 50], 'closed-form cycles', 'completed')
    >>> bool(np.array_equal(np.concatenate(times), solve_cycles(p, x0=1.0, n_cycles=250).cycles.impact_time))
    True
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, memory_budget=memory_budget)
    n = limits.n_cycles
    chunk, estimate = check_chunk(chunk, CHUNK_BYTES_PER_CYCLE, limits.memory_budget)
    prep = _prepared(params)
    cmap = cycle_map(params) if prep is None else prep.cycle_map
    first = _start(params, prep, x, v)
    reason = first if isinstance(first, str) else None
    if reason is None:
        with np.errstate(all="ignore"):
            done = _distinct_cycles(params, prep, first[0], first[1], n,
                                    most=(limits.memory_budget - estimate) // PEAK_BYTES_PER_CYCLE)
        reason = done if isinstance(done, str) else None
    if reason is not None:
        stream = iter_cycles(params, x, v, n_cycles=n, chunk=chunk, memory_budget=memory_budget)
        return CycleChunks(None, 0, n, chunk, stream, reason, cmap)
    return CycleChunks(done, first[2], n, chunk, None, None, cmap)


def _relative(a, b) -> np.ndarray:
    """``|a - b| / |b|`` elementwise (0 where both are 0, inf where only ``b`` is; NaN stays NaN)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        gap = np.abs(a - b)
        return np.where(b != 0.0, gap / np.abs(b), np.where(gap == 0.0, 0.0, np.inf))


def compare_tables(table: CycleTable, reference: CycleTable) -> dict[str, float]:
    """The largest relative difference of each column of ``table`` from ``reference`` over the cycles both
    hold (NaN where a value is NaN; 0.0 for no common cycle)."""
    n = min(len(table), len(reference))
    out = {}
    for name in COLUMNS:
        gaps = _relative(getattr(table, name)[:n], getattr(reference, name)[:n])
        out[name] = float(np.max(gaps)) if n else 0.0
    return out


def cross_check(run: CycleRun, rtol: float = CROSS_CHECK_RTOL) -> dict[str, float]:
    """Compare ``run`` with :func:`~escapement.solvers.exact.solve_exact` for the same arguments: the same
    outcome and number of cycles, and every quantity of every cycle (and ``t_final``) within ``rtol``
    (relative). Returns the largest relative difference of each; raises :class:`CrossCheckError` naming the
    quantity, the cycle and both values otherwise."""
    exact = solve_exact(run.params, run.x0, run.v0, n_cycles=run.n_cycles, record_trajectory=False)
    if exact.status is not run.status or len(exact.cycles) != len(run.cycles):
        raise CrossCheckError(f"{run.method}: {run.status.value} after {len(run.cycles)} cycles, but solve_exact: "
                              f"{exact.status.value} after {len(exact.cycles)} cycles ({exact.message})")
    gaps = compare_tables(run.cycles, exact.cycles)
    gaps["t_final"] = float(_relative(run.t_final, exact.t_final))
    for name, gap in gaps.items():
        if not gap <= rtol:
            if name == "t_final":
                where, mine, theirs = "t_final", run.t_final, exact.t_final
            else:
                column, reference = getattr(run.cycles, name), getattr(exact.cycles, name)
                each = _relative(column, reference)
                i = int(np.argmax(np.where(np.isnan(each), np.inf, each)))
                where, mine, theirs = f"{name} of cycle {i + 1}", column[i], reference[i]
            raise CrossCheckError(f"{run.method} and solve_exact disagree on the {where}: {float(mine)!r} against "
                                  f"{float(theirs)!r}, a relative difference of {gap:.3g} > rtol = {rtol:g}")
    return gaps
