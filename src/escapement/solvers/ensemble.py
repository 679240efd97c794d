"""The exact solver for many trajectories at once, one per array element.

The same automaton (:mod:`escapement.model.automaton`), closed forms
(:mod:`escapement.model.kinematics`, on arrays) and parameter rules
(:func:`escapement.model.parameters.validate_arrays`) as the scalar solvers, advanced in
lock-step, in two kinds of passes, as the scalar loop (:class:`escapement.solvers.exact.ClosedFormRun`):

* a per-event pass (:func:`_pass`) moves each running trajectory to its next event, whatever its mode:
  every watched surface, the regime exits, the impact law; one that ends (cycles done, stopped, turned
  back, chattering, its event bound) is masked out. It takes the first events of every trajectory, and
  every arc the other kind of pass leaves;
* once every running trajectory sits at an impact at a1 (or waits there), their cycles run in lock-step
  (:func:`_cycles`): per cycle the four arcs of every trajectory at once, from the automaton's single
  watched surface of each mode (:data:`_PLAN`), with the arithmetic of the per-event pass and the checks of
  the scalar loop's unrolled cycles; a trajectory whose arc leaves that common path goes back to the
  per-event passes before that arc. Some 30 operations on arrays per arc and no per-event bookkeeping;
  :func:`escapement.studies.floor.ensemble_floor` measures it against a bare NumPy loop over the same
  closed forms (:func:`escapement.studies.floor.numpy_cycles`).

Parameters and initial states broadcast to a common shape ``(N,)``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..model import automaton
from ..model.automaton import Awaited, Mode
from ..model.events import EventKind
from ..model.kinematics import VECTOR, arc_maximum, compensated_add, crossing, rebound_accumulation_time
from ..model.limits import MEMORY_BUDGET, MemoryBudgetError, RunLimits
from ..model.parameters import ParameterError, validate_arrays
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .exact import GRAZING
from .result import CycleTable, EnsembleSolution

__all__ = ["CELL_BYTES", "MAX_CELLS", "ROW_BYTES", "TABLE_BYTES", "ensemble_bytes", "solve_ensemble"]

_RUNNING = -1
TWO_PI = 2.0 * math.pi
#: bytes per trajectory and cycle (a cell of the tables, n_cycles + 1 of them per trajectory), with a margin
#: for the trajectory's own state from 120 cells on: the four tables of 8-byte floats (32 bytes) and the
#: boolean masks of their shape at the end (measured peak: 34.3)
CELL_BYTES = 40
#: below 120 cells, the cells at TABLE_BYTES and each trajectory's state, some 70 floats with the compact copy
#: the cycles in lock-step take of it (measured 630 bytes for 20 000 trajectories of one cycle)
TABLE_BYTES, ROW_BYTES = 35, 600
#: the most cells the default memory budget allows: 50 million, trajectories * (n_cycles + 1)
MAX_CELLS = MEMORY_BUDGET // CELL_BYTES
_A1, _A3 = int(EventKind.IMPACT_A1), int(EventKind.IMPACT_A3)
_IMPACT = np.array(automaton.IMPACT_TABLE)
_CENTRE_SIGN = np.array(automaton.CENTRE_SIGN)
_NEXT_MODE = np.zeros(5, dtype=int)
_NEXT_AWAITED = np.zeros(5, dtype=int)
for _kind in EventKind:
    _NEXT_MODE[_kind], _NEXT_AWAITED[_kind] = automaton.transition(_kind)
#: row (mode * 4 + awaited code) -> whether each event kind is watched, from the automaton
_WATCH = np.zeros((len(Mode) * 4, 5), dtype=bool)
for _mode in Mode:
    for _awaited in Awaited:
        for _kind in automaton.watched(_mode, _awaited):
            _WATCH[_mode * 4 + _awaited, _kind] = True


#: the automaton's own impact law and test of a rebound, for which the cycles run in lock-step (_cycles)
_PAPER_LAW, _PAPER_REVERSES = automaton.velocity_after, automaton.reverses


class _Arc(NamedTuple):
    """An arc of the cycle from an impact at a1, from the automaton (as :func:`escapement.solvers.exact.stages`
    builds it for one trajectory): the event it starts from and the one it ends at, the centre's sign, the
    directions of motion at its ends, whether it passes the top of its circle and ends at an impact."""

    start_kind: int
    end_kind: int
    centre_sign: float
    start: float
    direction: float
    top: bool
    impact: bool


def _cycle_arcs() -> tuple[_Arc, ...]:
    """The arcs from an impact at a1 to the next, each mode after an event watching one surface."""
    arcs, kind = [], int(EventKind.IMPACT_A1)
    for _ in range(len(EventKind)):
        mode, awaited = automaton.transition(kind)
        (nxt,) = automaton.watched(mode, awaited)
        start, end = automaton.SURFACES[kind].direction, automaton.SURFACES[nxt].direction
        arcs.append(_Arc(kind, int(nxt), float(_CENTRE_SIGN[mode]), float(start), float(end), start > 0 > end,
                         automaton.is_impact(nxt)))
        kind = int(nxt)
        if kind == _A1:
            return tuple(arcs)
    raise RuntimeError("the automaton's cycle does not return to the impact at a1")


_PLAN = _cycle_arcs()
_FIRST_TOP = next((i for i, arc in enumerate(_PLAN) if arc.top), len(_PLAN))


def ensemble_bytes(n_trajectories: int, n_cycles: int) -> int:
    """The bytes :func:`solve_ensemble` takes at most for ``n_trajectories`` runs of ``n_cycles`` cycles."""
    cells = n_cycles + 1
    return n_trajectories * max(CELL_BYTES * cells, TABLE_BYTES * cells + ROW_BYTES)


def solve_ensemble(
    M, K, F, b, a1, a2, a3=None, a4=None, x0=1.0, v0=0.0, *, n_cycles: int, max_events=None, amplitude: bool = True,
    memory_budget: int | None = None,
) -> EnsembleSolution:
    """Integrate every trajectory for ``n_cycles`` complete cycles (or until it leaves the regime).

    Inputs are validated by the rules of :class:`escapement.Parameters` and
    :func:`escapement.model.parameters.check_initial_state`, row by row, and the counts by
    :class:`~escapement.model.limits.RunLimits`, before any work; the first invalid row is named
    in the error. The run's size (:func:`ensemble_bytes`) is at most ``memory_budget`` bytes (default
    :data:`~escapement.model.limits.MEMORY_BUDGET`: ``n_cycles + 1`` times the number of trajectories at most
    :data:`MAX_CELLS`), or a :class:`~escapement.model.limits.MemoryBudgetError` says so before any work.
    With ``amplitude=False`` the per-cycle maxima are not computed.

    The model's inputs and the initial state are numbers or arrays, broadcast to one shape; each
    element is one trajectory (the result's rows follow the flattened shape).

    Parameters
    ----------
    M : float or array_like
        Mass, kg.
    K : float or array_like
        Spring constant, N/m.
    F : float or array_like
        Force of the escapement over an impulse zone, N.
    b : float or array_like
        Impact coefficient, dimensionless, in ``(0, 2)``.
    a1 : float or array_like
        Impact position of the first half cycle (moving right), m.
    a2 : float or array_like
        End of the first impulse zone, m.
    a3 : float or array_like, optional
        Impact position of the second half cycle (moving left), m; default ``-a1``.
    a4 : float or array_like, optional
        End of the second impulse zone, m; default ``-a2``.
    x0 : float or array_like, default 1
        Initial displacement at ``t = 0+``, m.
    v0 : float or array_like, default 0
        Initial velocity at ``t = 0+``, m/s.
    n_cycles : int
        Complete cycles to run.
    max_events : int, optional
        Bound on the number of events of each trajectory.
    amplitude : bool, default True
        Compute the per-cycle maxima of ``x`` (m); NaN without.
    memory_budget : int, optional
        The most bytes the run may take (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    EnsembleSolution
        One row per trajectory: outcomes, end times (s), the per-cycle table (impact time in s,
        velocity before impact in m/s, period in s, amplitude in m) of shape ``(N, n_cycles)``.

    Raises
    ------
    ParameterError
        If an input is invalid (the message names it and the row), or
        (:class:`~escapement.model.limits.MemoryBudgetError`) the run would exceed ``memory_budget``.

    Examples
    --------
    Two forces (N) at once:

    >>> from escapement import solve_ensemble
    >>> runs = solve_ensemble(M=1.0, K=1.0, F=[0.5, 1.0], b=0.1, a1=-0.1, a2=0.05, x0=1.0, n_cycles=3)
    >>> runs.cycles.period.shape, bool(runs.success.all())
    ((2, 3), True)
    >>> runs.cycles.period[:, -1].round(4)  # s
    array([6.2991, 6.2979])
    """
    limits = RunLimits(n_cycles=n_cycles, max_events=max_events, memory_budget=memory_budget)
    if not isinstance(amplitude, bool | np.bool_):
        raise ParameterError("amplitude", amplitude, "True or False")
    given = {**dict(zip(MODEL_KEYS, (M, K, F, b, a1, a2, a3, a4))), "x0": x0, "v0": v0}
    checked = validate_arrays(given, state=True)
    M, K, F, b, a1, a2, a3, a4, x, v = (checked[name].ravel() for name in (*MODEL_KEYS, "x0", "v0"))
    n = len(M)
    n_cycles = limits.n_cycles
    budget = limits.memory_budget
    estimate = ensemble_bytes(n, n_cycles)
    if estimate > budget:
        where = (f"each trajectory takes max({CELL_BYTES} (n_cycles + 1), {TABLE_BYTES} (n_cycles + 1) + {ROW_BYTES}) "
                 f"bytes: an estimated {estimate:_} bytes, over the memory budget of {budget:_} bytes")
        cells = (budget // n) // CELL_BYTES  # the most cells per trajectory, at CELL_BYTES each ...
        if CELL_BYTES * cells < TABLE_BYTES * cells + ROW_BYTES:  # ... or, for fewer, at TABLE_BYTES plus the state
            cells = (budget // n - ROW_BYTES) // TABLE_BYTES
        if cells < 2:
            raise MemoryBudgetError("trajectories", n, f"at most {budget // ensemble_bytes(1, n_cycles):_} for "
                                    f"n_cycles = {n_cycles:_} ({where})", estimate, budget)
        raise MemoryBudgetError("n_cycles", n_cycles, f"at most {cells - 1:_} for {n:_} trajectories ({where})",
                                estimate, budget)
    omega, offset = np.sqrt(K / M), F / K
    positions = {kind: {"a1": a1, "a2": a2, "a3": a3, "a4": a4}[s.position] for kind, s in automaton.SURFACES.items()}

    t = np.zeros(n)  # compensated sum of the durations: t + t_err
    t_err = np.zeros(n)
    elapsed = np.zeros(n)  # time since the last impact at a1
    mode = np.full(n, int(Mode.FREE))
    awaited = np.full(n, int(Awaited.EITHER))
    status = np.full(n, _RUNNING)
    count = np.zeros(n, dtype=int)
    cycle_max = np.full(n, -np.inf)
    times = np.full((n, n_cycles + 1), np.nan)
    speeds = np.full((n, n_cycles + 1), np.nan)
    periods = np.full((n, n_cycles), np.nan)
    maxima = np.full((n, n_cycles), np.nan)
    t_final = np.full(n, np.nan)
    turning = np.full(n, np.nan)
    margin = np.full(n, np.nan)
    t_acc = np.full(n, np.nan)

    events = np.zeros(n, dtype=np.int64)  # each trajectory's events so far
    parked = np.zeros(n, dtype=bool)  # at an impact at a1, waiting for the cycles in lock-step (_cycles)
    # the cycles in lock-step take the paper's impact law with b < 1 (no rebound), as the scalar loop's
    eligible = (automaton.velocity_after is _PAPER_LAW and automaton.reverses is _PAPER_REVERSES) & (1.0 - b > 0.0)
    state = dict(x=x, v=v, t=t, t_err=t_err, elapsed=elapsed, mode=mode, awaited=awaited, status=status, count=count,
                 events=events, parked=parked, eligible=eligible, cycle_max=cycle_max, times=times, speeds=speeds,
                 periods=periods, maxima=maxima, t_final=t_final, turning=turning, margin=margin, t_acc=t_acc,
                 omega=omega, offset=offset, b=b, positions=positions)
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(2 * limits.max_events + 2):  # each pass moves every running trajectory by an event or more
            running = status == _RUNNING
            movers = running & ~parked
            if movers.any():
                _pass(np.flatnonzero(movers), state, n_cycles, limits.max_events, amplitude)
            elif running.any():  # every running trajectory parked: their cycles, a group per count of cycles
                rows = np.flatnonzero(parked)
                for cycle in np.unique(count[rows]):
                    _cycles(rows[count[rows] == cycle], state, n_cycles, limits.max_events, amplitude)
            else:
                break
        else:
            raise RuntimeError("the ensemble's loop did not end within its bound of passes")

    # Like the scalar table: only complete cycles (an impact that starts an unfinished cycle is dropped).
    incomplete = np.arange(n_cycles)[None, :] >= (count - 1)[:, None]
    times, speeds = times[:, :n_cycles], speeds[:, :n_cycles]
    times[incomplete] = np.nan
    speeds[incomplete] = np.nan
    _check_completed_rows(status, times, speeds, periods, maxima if amplitude else None, t_final)
    return EnsembleSolution(
        status=status.astype(np.int8),
        cycles=CycleTable(impact_time=times, velocity_before_impact=speeds, period=periods, amplitude=maxima),
        t_final=t_final,
        exit_turning_point=turning,
        exit_margin=margin,
        exit_t_accumulation=t_acc,
    )


def _pass(ii: np.ndarray, s: dict, n_cycles: int, max_events: int, amplitude: bool) -> None:
    """One event of each trajectory ``ii`` (running, not parked): the automaton's watched surfaces by
    :func:`~escapement.model.kinematics.crossing` on arrays, the regime exits, the impact law, the cycle
    table at the impacts at a1. A trajectory still running at its ``max_events``-th event ends there; one at
    an impact at a1 with a whole cycle's events to go is parked for :func:`_cycles`."""
    x, v, t, t_err, elapsed, mode, awaited = (s[k] for k in ("x", "v", "t", "t_err", "elapsed", "mode", "awaited"))
    status, count, events, cycle_max, t_final = (s[k] for k in ("status", "count", "events", "cycle_max", "t_final"))
    omega, offset, b, positions = s["omega"], s["offset"], s["b"], s["positions"]
    xs, vs, om, md = x[ii], v[ii], omega[ii], mode[ii]
    centre = _CENTRE_SIGN[md] * offset[ii]
    # each row's watched surfaces, at most two: the first and, in free flight awaiting
    # either impact, the second
    best_dt = np.full(len(ii), np.inf)
    best = {name: np.zeros(len(ii)) for name in ("v", "angle", "target")}
    kind = np.zeros(len(ii), dtype=int)
    for candidate in EventKind:
        surface = automaton.SURFACES[candidate]
        on = _WATCH[md * 4 + awaited[ii], candidate]
        if not on.any():
            continue
        target = positions[candidate][ii]
        reached, dt, v_new, angle = crossing(centre, xs, vs, om, target, float(surface.direction), VECTOR)
        take = on & reached & (dt < best_dt)
        best_dt = np.where(take, dt, best_dt)
        kind = np.where(take, int(candidate), kind)
        for name, value in (("v", v_new), ("angle", angle), ("target", target)):
            best[name] = np.where(take, value, best[name])
    ended = kind == 0
    if ended.any():
        _exit(ii[ended], md[ended], centre[ended], xs[ended], vs[ended], om[ended], awaited, positions, t, t_err,
              status, t_final, s["turning"], s["margin"])
    go = ~ended
    jj = ii[go]
    d, k, v_new, target = best_dt[go], kind[go], best["v"][go], best["target"][go]
    if amplitude:
        cycle_max[jj] = np.maximum(cycle_max[jj], arc_maximum(centre[go], xs[go], vs[go], om[go], best["angle"][go],
                                                              target, VECTOR))
    t[jj], t_err[jj] = compensated_add(t[jj], t_err[jj], d, VECTOR)
    elapsed[jj] += d
    x[jj] = target
    events[jj] += 1
    hit1 = k == _A1
    i1 = jj[hit1]
    c = count[i1]
    s["times"][i1, c] = t[i1] + t_err[i1]
    s["speeds"][i1, c] = v_new[hit1]
    later = c > 0
    if amplitude:
        s["maxima"][i1[later], c[later] - 1] = cycle_max[i1[later]]
    s["periods"][i1[later], c[later] - 1] = elapsed[i1[later]]
    elapsed[i1] = 0.0
    cycle_max[i1] = x[i1]
    count[i1] += 1
    done = np.zeros(len(jj), dtype=bool)
    done[hit1] = count[i1] >= n_cycles + 1
    status[jj[done]] = Status.COMPLETED.code
    t_final[jj[done]] = t[jj[done]] + t_err[jj[done]]
    v_after = automaton.velocity_after(v_new, b[jj], _IMPACT[k])
    chatter = ~done & automaton.reverses(v_new, v_after)
    for i, kk, va, vb in zip(jj[chatter], k[chatter], v_after[chatter], v_new[chatter]):
        _chattering(i, EventKind(int(kk)), va, vb, t, t_err, omega, positions, status, t_final, s["t_acc"])
    v[jj] = v_after
    mode[jj] = _NEXT_MODE[k]
    awaited[jj] = _NEXT_AWAITED[k]
    # the event bound: a trajectory still running after its last event ends there
    limited = (status[jj] == _RUNNING) & (events[jj] >= max_events)
    status[jj[limited]] = Status.EVENT_LIMIT.code
    t_final[jj[limited]] = t[jj[limited]] + t_err[jj[limited]]
    # at an impact at a1 with a whole cycle's events to go: the cycles in lock-step take over
    s["parked"][jj] = hit1 & (status[jj] == _RUNNING) & s["eligible"][jj] & (events[jj] + len(_PLAN) <= max_events)


def _cycles(rows: np.ndarray, s: dict, n_cycles: int, max_events: int, amplitude: bool) -> None:
    """The cycles of the trajectories ``rows``, each at an impact at a1 and at the same count of cycles, in
    lock-step: per cycle the four arcs of :data:`_PLAN` of every one at once, on compact arrays of their own.

    Each arc is :func:`~escapement.model.kinematics.crossing` on arrays (the same operations), taken where
    the scalar loop's unrolled cycles take it (:meth:`escapement.solvers.exact.ClosedFormRun._cycles`): the
    surface is reached, the motion starts in the arc's direction, and the amplitude's shortcut holds (the
    angle below the stage's bound, the arrival away from a turning point), so the arc's largest ``x`` is
    ``c + hypot(u0, w0)`` over the top and ``max(x_from, target)`` elsewhere, the number of
    :func:`~escapement.model.kinematics.arc_maximum`. A trajectory that leaves that path, or whose event bound
    leaves no whole cycle, goes back to the per-event passes, its state that of the event before the arc; one
    that completes its cycles ends. Until then the state in ``s`` is not updated: the lanes carry it."""
    positions, omega = s["positions"], s["omega"][rows]
    cycle_start = positions[_A1][rows]  # the largest x so far at the impact at a1
    entered = cycle = int(s["count"][rows[0]])  # the impacts at a1 so far, the same for every lane
    lane = dict(rows=rows, omega=omega, v=s["v"][rows], t=s["t"][rows], t_err=s["t_err"][rows],
                events=s["events"][rows], start=cycle_start)  # each cycle from entry on takes len(_PLAN) events
    lane["stop"] = cycle + np.minimum(n_cycles + 1 - cycle, (max_events - lane["events"]) // len(_PLAN))
    # per arc: the surface terms k, u, q, the grazing bound, the bound of the angle (a number where it is
    # the same for all), the centre (over the top), the larger end (from the first arc over the top on); the
    # impact law's factor, one for every impact
    lane["factor"] = 1.0 - s["b"][rows] * True
    consts = []
    floor = cycle_start
    for i, arc in enumerate(_PLAN):
        x_from, target = positions[arc.start_kind][rows], positions[arc.end_kind][rows]
        centre = arc.centre_sign * s["offset"][rows]
        q = target - centre
        if arc.top or arc.start != arc.direction:
            cap = np.inf  # over the top, or round the bottom
        else:  # straight on: less than half a turn where it moves towards its target
            cap = np.where(target > x_from if arc.start > 0 else target < x_from, math.pi, -np.inf)
        ends = np.maximum(x_from, target)
        if i < _FIRST_TOP:
            floor = np.maximum(floor, ends)
        consts.append(dict(k=(omega * omega) * ((x_from - target) * (x_from + target - 2.0 * centre)),
                           u=x_from - centre, q=q, g=GRAZING * (q * q), cap=cap, centre=centre if arc.top else None,
                           ends=ends if i > _FIRST_TOP and not arc.top else None))
    del x_from, target, centre, q, cap, ends
    lane["floor"] = floor  # the largest x of the arcs before the first over the top

    def leave(keep: np.ndarray, arc: int, elapsed, cycle_max) -> None:
        """The lanes not in ``keep`` go back to the per-event passes before arc ``arc``; the rest stay."""
        out = ~keep
        r = lane["rows"][out]
        kind = _PLAN[arc].start_kind if arc < len(_PLAN) else _A1
        s["x"][r] = positions[kind][r]
        s["v"][r], s["t"][r], s["t_err"][r] = lane["v"][out], lane["t"][out], lane["t_err"][out]
        s["elapsed"][r] = elapsed[out]
        if amplitude:
            if arc < len(_PLAN) and arc <= _FIRST_TOP:  # the constant part of the amplitude so far
                cycle_max = lane["start"]
                for before in _PLAN[:arc]:
                    cycle_max = np.maximum(cycle_max, np.maximum(positions[before.start_kind][lane["rows"]],
                                                                 positions[before.end_kind][lane["rows"]]))
            s["cycle_max"][r] = cycle_max[out]
        s["mode"][r], s["awaited"][r] = _NEXT_MODE[kind], _NEXT_AWAITED[kind]
        s["count"][r] = cycle
        s["events"][r] = lane["events"][out] + len(_PLAN) * (cycle - entered) + arc % len(_PLAN)
        s["parked"][r] = False
        for name, value in lane.items():
            lane[name] = value[keep]
        for c in consts:
            for name, value in c.items():
                if isinstance(value, np.ndarray):
                    c[name] = value[keep]

    times, speeds, periods, maxima, status = s["times"], s["speeds"], s["periods"], s["maxima"], s["status"]

    def cells() -> tuple:
        """The lanes' rows, and where they are in the cycle tables: a slice where they are consecutive."""
        rows = lane["rows"]
        return rows, slice(rows[0], rows[-1] + 1) if rows[-1] - rows[0] == len(rows) - 1 else rows

    rows, at = cells()
    for _ in range(n_cycles + 1):  # each pass completes a cycle of every lane, or ends a lane
        v, ts, te = lane["v"], lane["t"], lane["t_err"]
        elapsed = np.zeros(len(v))
        cycle_max = None  # from the first arc over the top on (before it, lane["floor"])
        for i, (arc, c) in enumerate(zip(_PLAN, consts)):
            omega, u, q = lane["omega"], c["u"], c["q"]
            v1 = v * v
            v1 += c["k"]
            np.sqrt(v1, out=v1)  # v_sq > 0 is w1**2 > g below: g >= 0, and sqrt gives NaN below 0
            if arc.direction < 0:
                np.negative(v1, out=v1)
            w0 = v / omega
            w1 = v1 / omega
            angle = np.arctan2(w0 * q - u * w1, u * q + w0 * w1)
            angle[angle <= 0.0] += TWO_PI
            w1 *= w1
            ok = w1 > c["g"]
            ok &= w0 > 0.0 if arc.start > 0 else w0 < 0.0
            ok &= angle < c["cap"]
            if not ok.all():
                leave(ok, i, elapsed, cycle_max)
                if not len(lane["rows"]):
                    return
                v, ts, te = lane["v"], lane["t"], lane["t_err"]  # the lanes left, as leave() kept them
                elapsed, v1, w0, angle = elapsed[ok], v1[ok], w0[ok], angle[ok]
                if cycle_max is not None:
                    cycle_max = cycle_max[ok]
                omega, u, q = lane["omega"], c["u"], c["q"]
                rows, at = cells()
            angle /= omega  # the duration
            if amplitude and i >= _FIRST_TOP:
                m = c["centre"] + np.hypot(u, w0) if arc.top else c["ends"]
                cycle_max = np.maximum(lane["floor"] if cycle_max is None else cycle_max, m)
            # compensated_add: ts >= 0 and the duration > 0, so |ts| >= |dt| is ts >= dt, which holds
            # for every lane but in the first arcs of a run
            new = ts + angle
            big = ts >= angle
            te += (ts - new) + angle if big.all() else np.where(big, (ts - new) + angle, (angle - new) + ts)
            ts = new
            elapsed += angle
            v = v1 * lane["factor"] if arc.impact else v1
            lane["v"], lane["t"], lane["t_err"] = v, ts, te
        # the impact at a1 ends the cycle
        now = ts + te
        times[at, cycle], speeds[at, cycle], periods[at, cycle - 1] = now, v1, elapsed
        if amplitude:
            maxima[at, cycle - 1] = lane["floor"] if cycle_max is None else cycle_max
        cycle += 1
        finished = cycle >= lane["stop"]
        if finished.any():
            completed = finished & (cycle >= n_cycles + 1)
            status[rows[completed]] = Status.COMPLETED.code
            # as after an event of the per-event passes: one still running at its last event ends there
            limited = finished & ~completed & (lane["events"] + len(_PLAN) * (cycle - entered) >= max_events)
            status[rows[limited]] = Status.EVENT_LIMIT.code
            ended = completed | limited
            s["t_final"][rows[ended]] = now[ended]
            leave(~finished, len(_PLAN), np.zeros(len(rows)), lane["start"])
            if not len(lane["rows"]):
                return
            rows, at = cells()
    raise RuntimeError("the cycles in lock-step did not end within n_cycles + 1 passes")

def _check_completed_rows(status, times, speeds, periods, maxima, t_final) -> None:
    """A completed row holds only finite numbers; otherwise the input validation let through a
    value whose arithmetic leaves the float64 range: raise, naming the row (a bug, not an outcome)."""
    done = status == Status.COMPLETED.code
    columns = {"impact_time": times, "velocity_before_impact": speeds, "period": periods, "t_final": t_final[:, None]}
    if maxima is not None:
        columns["amplitude"] = maxima
    for name, values in columns.items():
        bad = done & ~np.isfinite(values).all(axis=1)
        if bad.any():
            raise FloatingPointError(
                f"row {int(np.flatnonzero(bad)[0])}: a completed run holds a non-finite {name}; the input "
                "validation (escapement.model.parameters) must refuse the inputs that lead to it"
            )


def _exit(rows, mode, centre, x, v, omega, awaited, positions, t, t_err, status, t_final, turning, margin):
    """Rows that pass no watched surface: the escapement stopped, or the mass turned back in a zone."""
    free = mode == Mode.FREE
    w = v / omega
    radius = np.hypot(x - centre, w)
    now = t[rows] + t_err[rows]
    # free flight: the swing of this radius misses the awaited impact positions
    r = rows[free]
    missed = np.full(len(r), np.inf)
    for kind in (EventKind.IMPACT_A1, EventKind.IMPACT_A3):
        on = _WATCH[int(Mode.FREE) * 4 + awaited[r], kind]
        missed = np.where(on, np.minimum(missed, np.abs(positions[kind][r])), missed)
    status[r] = Status.STOPPED.code
    t_final[r] = np.inf
    turning[r] = radius[free]
    margin[r] = missed - radius[free]
    # a zone: the motion turns at centre + R moving right, centre - R moving left
    z = ~free
    r = rows[z]
    right = v[z] > 0
    start = np.arctan2(w[z], x[z] - centre[z])
    to_rest = np.where(v[z] == 0, 0.0, np.where(right, start, start + math.pi)) / omega[z]
    point = np.where(v[z] == 0, x[z], centre[z] + np.where(right, radius[z], -radius[z]))
    end = np.where(mode[z] == Mode.ZONE_RIGHT, positions[EventKind.ZONE_END_A2][r], positions[EventKind.ZONE_END_A4][r])
    status[r] = Status.TURNED_BACK_IN_ZONE.code
    t_final[r] = now[z] + to_rest
    turning[r] = point
    margin[r] = np.abs(end - point)


def _chattering(i, kind, v_after, v_before, t, t_err, omega, positions, status, t_final, t_acc):
    """A row whose impact reversed the velocity: the time at which the rebounds accumulate."""
    distance = automaton.rebound_distance(kind, positions[kind][i])
    now = t[i] + t_err[i]
    status[i] = Status.CHATTERING.code
    t_final[i] = now
    if distance > 0.0:
        t_acc[i] = now + rebound_accumulation_time(float(omega[i]), float(distance), abs(float(v_after)),
                                                   abs(float(v_after / v_before)))
