"""The exact solver for many trajectories at once, one per array element.

The same automaton (:mod:`escapement.model.automaton`), closed forms
(:mod:`escapement.model.kinematics`, on arrays) and parameter rules
(:func:`escapement.model.parameters.validate_arrays`) as the scalar solvers, advanced in
lock-step: every pass of the loop moves each running trajectory to its next event; one that
ends (cycles done, stopped, turned back, chattering) is masked out. Parameters and initial
states broadcast to a common shape ``(N,)``.
"""

from __future__ import annotations

import math

import numpy as np

from ..model import automaton
from ..model.automaton import Awaited, Mode
from ..model.events import EventKind
from ..model.kinematics import VECTOR, arc_maximum, compensated_add, crossing, rebound_accumulation_time
from ..model.limits import MEMORY_BUDGET, MemoryBudgetError, RunLimits
from ..model.parameters import ParameterError, validate_arrays
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .result import CycleTable, EnsembleSolution

__all__ = ["CELL_BYTES", "MAX_CELLS", "ROW_BYTES", "TABLE_BYTES", "ensemble_bytes", "solve_ensemble"]

_RUNNING = -1
#: bytes per trajectory and cycle (a cell of the tables, n_cycles + 1 of them per trajectory), with a margin
#: for the trajectory's own state from 120 cells on: the four tables of 8-byte floats (32 bytes) and the
#: boolean masks of their shape at the end (measured peak: 34.3)
CELL_BYTES = 40
#: below 120 cells, the cells at TABLE_BYTES and each trajectory's state, some 60 floats (measured 500 bytes)
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

    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(limits.max_events):
            running = status == _RUNNING
            if not running.any():
                break
            ii = np.flatnonzero(running)
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
                _exit(ii[ended], md[ended], centre[ended], xs[ended], vs[ended], om[ended], awaited, positions, t, t_err, status, t_final, turning, margin)
            go = ~ended
            jj = ii[go]
            d, k, v_new, target = best_dt[go], kind[go], best["v"][go], best["target"][go]
            if amplitude:
                cycle_max[jj] = np.maximum(cycle_max[jj], arc_maximum(centre[go], xs[go], vs[go], om[go],
                                                                      best["angle"][go], target, VECTOR))
            t[jj], t_err[jj] = compensated_add(t[jj], t_err[jj], d, VECTOR)
            elapsed[jj] += d
            x[jj] = target
            hit1 = k == _A1
            i1 = jj[hit1]
            c = count[i1]
            times[i1, c] = t[i1] + t_err[i1]
            speeds[i1, c] = v_new[hit1]
            later = c > 0
            if amplitude:
                maxima[i1[later], c[later] - 1] = cycle_max[i1[later]]
            periods[i1[later], c[later] - 1] = elapsed[i1[later]]
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
                _chattering(i, EventKind(int(kk)), va, vb, t, t_err, omega, positions, status, t_final, t_acc)
            v[jj] = v_after
            mode[jj] = _NEXT_MODE[k]
            awaited[jj] = _NEXT_AWAITED[k]
        left = status == _RUNNING
        status[left] = Status.EVENT_LIMIT.code
        t_final[left] = t[left] + t_err[left]

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
