"""The exact solver for many trajectories at once, one per array element.

The same automaton (:mod:`escapement.model.automaton`) and closed forms (:func:`~escapement.model.kinematics.crossing`,
:func:`~escapement.model.kinematics.arc_maximum` on arrays) as the scalar event loop, advanced in lock-step: the
automaton's rows for every trajectory in one table (:func:`_rows`), and each pass moves every running
trajectory by one event, whatever its state, with the row of that state. A trajectory that ends (cycles
done, stopped, turned back, chattering, its event bound) leaves the passes. Parameters and initial states
broadcast to a common shape ``(N,)``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..model import automaton
from ..model.automaton import RELEASE
from ..model.events import EventKind
from ..model.kinematics import arc_maximum, arc_terms, compensated_add, crossing, rebound_accumulation_time
from ..model.limits import MEMORY_BUDGET, MemoryBudgetError, RunLimits, check_flag
from ..model.parameters import validate_arrays
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .result import CycleTable, EnsembleSolution

__all__ = ["CELL_BYTES", "MAX_CELLS", "ROW_BYTES", "TABLE_BYTES", "ensemble_bytes", "solve_ensemble"]

_RUNNING = -1
#: bytes per trajectory and cycle (a cell of the tables, n_cycles + 1 of them per trajectory), with a margin
#: for the trajectory's own state from 120 cells on: the four tables of 8-byte floats (32 bytes) and the
#: boolean masks of their shape at the end
CELL_BYTES = 40
#: below 120 cells, the cells at TABLE_BYTES and each trajectory's state: its rows (five states, eight numbers
#: each) and some sixty floats of state and work arrays (measured about 860 bytes)
TABLE_BYTES, ROW_BYTES = 35, 1000
#: the most cells the default memory budget allows: 50 million, trajectories * (n_cycles + 1)
MAX_CELLS = MEMORY_BUDGET // CELL_BYTES
_A1 = int(EventKind.IMPACT_A1)


def ensemble_bytes(n_trajectories: int, n_cycles: int) -> int:
    """The bytes :func:`solve_ensemble` takes at most for ``n_trajectories`` runs of ``n_cycles`` cycles."""
    cells = n_cycles + 1
    return n_trajectories * max(CELL_BYTES * cells, TABLE_BYTES * cells + ROW_BYTES)


def solve_ensemble(
    M: ArrayLike, K: ArrayLike, F: ArrayLike, b: ArrayLike, a1: ArrayLike, a2: ArrayLike,
    a3: ArrayLike | None = None, a4: ArrayLike | None = None, x0: ArrayLike = 1.0, v0: ArrayLike = 0.0, *,
    n_cycles: int, max_events: int | None = None, largest_displacement: bool = True, memory_budget: int | None = None,
) -> EnsembleSolution:
    """Integrate every trajectory for ``n_cycles`` complete cycles (or until it leaves the regime).

    Inputs are validated by the rules of :class:`escapement.Parameters` and
    :func:`escapement.model.parameters.check_initial_state`, row by row, and the counts by
    :class:`~escapement.model.limits.RunLimits`, before any work; the first invalid row is named
    in the error. The run's size (:func:`ensemble_bytes`) is at most ``memory_budget`` bytes (default
    :data:`~escapement.model.limits.MEMORY_BUDGET`: ``n_cycles + 1`` times the number of trajectories at most
    :data:`MAX_CELLS`), or a :class:`~escapement.model.limits.MemoryBudgetError` says so before any work.
    With ``largest_displacement=False`` the per-cycle maxima are not computed.

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
    largest_displacement : bool, default True
        Compute the per-cycle maxima of ``x`` (m); NaN without.
    memory_budget : int, optional
        The most bytes the run may take (default :data:`~escapement.model.limits.MEMORY_BUDGET`, 2 GB).

    Returns
    -------
    EnsembleSolution
        One row per trajectory: outcomes, end times (s), the per-cycle table (impact time in s,
        velocity before impact in m/s, period in s, largest displacement in m) of shape ``(N, n_cycles)``.

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
    largest_displacement = check_flag("largest_displacement", largest_displacement)
    given = {**dict(zip(MODEL_KEYS, (M, K, F, b, a1, a2, a3, a4))), "x0": x0, "v0": v0}
    try:  # the number of trajectories from the inputs' shapes alone, before any array is made at that size
        shape = np.broadcast_shapes(*(np.shape(value) for value in given.values() if value is not None))
    except ValueError:  # shapes that do not broadcast: the validation below names the inputs
        shape = None
    if shape is not None:
        _check_memory(math.prod(shape), limits)
    checked = validate_arrays(given, state=True)
    M, K, F, b, a1, a2, a3, a4, x, v = (checked[name].ravel() for name in (*MODEL_KEYS, "x0", "v0"))
    n = len(M)
    n_cycles = limits.n_cycles
    _check_memory(n, limits)
    omega, offset = np.sqrt(K / M), F / K
    values = {"a1": a1, "a2": a2, "a3": a3, "a4": a4}
    positions = {kind: values[s.position] for kind, s in automaton.SURFACES.items()}

    t = np.zeros(n)  # compensated sum of the durations: t + t_err
    t_err = np.zeros(n)
    elapsed = np.zeros(n)  # time since the last impact at a1
    state = np.full(n, RELEASE)
    status = np.full(n, _RUNNING)
    count = np.zeros(n, dtype=int)
    cycle_max = np.full(n, -np.inf)
    # the cycle tables, a row per cycle while they are filled (the trajectories at one cycle side by side), a
    # row per trajectory once transposed at the end
    times = np.full((n_cycles + 1, n), np.nan)
    speeds = np.full((n_cycles + 1, n), np.nan)
    periods = np.full((n_cycles, n), np.nan)
    maxima = np.full((n_cycles, n), np.nan)
    t_final = np.full(n, np.nan)
    turning = np.full(n, np.nan)
    margin = np.full(n, np.nan)
    t_acc = np.full(n, np.nan)

    s = dict(x=x, v=v, t=t, t_err=t_err, elapsed=elapsed, state=state, status=status, count=count,
             cycle_max=cycle_max, times=times, speeds=speeds, periods=periods, maxima=maxima, t_final=t_final,
             turning=turning, margin=margin, t_acc=t_acc, omega=omega, offset=offset, b=b, positions=positions)
    s["rebounds"] = bool(automaton.reverses(1.0, automaton.impact_factor(b)).any())
    with np.errstate(invalid="ignore", divide="ignore"):
        table = _rows(s, x, v)
        every = np.arange(n)
        # each pass moves every running trajectory by one event: after pass p, each has had p + 1 events
        for _ in range(limits.max_events):
            running = status == _RUNNING
            ii = slice(None) if running.all() else np.flatnonzero(running)
            if not len(every[ii]):
                break
            _pass(ii, every[ii], table, s, n_cycles, largest_displacement)
        else:  # the event bound: a trajectory still running after its last event ends there
            limited = status == _RUNNING
            status[limited] = Status.EVENT_LIMIT.code
            t_final[limited] = t[limited] + t_err[limited]

    # Like the scalar table: only complete cycles (an impact that starts an unfinished cycle is dropped).
    times, speeds, periods, maxima = times[:n_cycles].T, speeds[:n_cycles].T, periods.T, maxima.T
    incomplete = np.arange(n_cycles)[None, :] >= (count - 1)[:, None]
    times[incomplete] = np.nan
    speeds[incomplete] = np.nan
    _check_completed_rows(status, times, speeds, periods, maxima if largest_displacement else None, t_final)
    return EnsembleSolution(
        status=status.astype(np.int8),
        cycles=CycleTable(impact_time=times, velocity_before_impact=speeds, period=periods, largest_displacement=maxima),
        t_final=t_final,
        exit_turning_point=turning,
        exit_margin=margin,
        exit_t_accumulation=t_acc,
    )


def _check_memory(n: int, limits: RunLimits) -> None:
    """Refuse ``n`` trajectories of ``limits.n_cycles`` cycles whose estimate (:func:`ensemble_bytes`) exceeds the
    memory budget, naming what to change: the budget where one trajectory of one cycle does not fit, else the
    trajectories or the cycles, with the most that fit."""
    n_cycles, budget = limits.n_cycles, limits.memory_budget
    estimate = ensemble_bytes(n, n_cycles)
    if estimate <= budget:
        return
    where = (f"each trajectory takes max({CELL_BYTES} (n_cycles + 1), {TABLE_BYTES} (n_cycles + 1) + {ROW_BYTES}) "
             f"bytes: an estimated {estimate:_} bytes, over the memory budget of {budget:_} bytes")
    if ensemble_bytes(1, 1) > budget:
        raise MemoryBudgetError("memory_budget", budget, f"at least {ensemble_bytes(1, 1):_} bytes, those of one "
                                f"trajectory of one cycle ({where})", estimate, budget)
    cells = (budget // n) // CELL_BYTES  # the most cells per trajectory, at CELL_BYTES each ...
    if CELL_BYTES * cells < TABLE_BYTES * cells + ROW_BYTES:  # ... or, for fewer, at TABLE_BYTES plus the state
        cells = (budget // n - ROW_BYTES) // TABLE_BYTES
    if cells < 2:
        raise MemoryBudgetError("trajectories", n, f"at most {budget // ensemble_bytes(1, n_cycles):_} for "
                                f"n_cycles = {n_cycles:_} ({where})", estimate, budget)
    raise MemoryBudgetError("n_cycles", n_cycles, f"at most {cells - 1:_} for {n:_} trajectories ({where})",
                            estimate, budget)


def _rows(s: dict, x: np.ndarray, v: np.ndarray) -> dict[str, np.ndarray]:
    """The automaton's rows for every trajectory, each field a column per state, flattened: entry ``state * N +
    i`` is trajectory ``i``'s. Per state the arc's terms, centre, end, direction, next state, and the jump at its
    end (the impact law's factor at an impact, 1 elsewhere); the release's row is that of the surface reached
    first (where neither is, the first watched)."""
    omega, offset, positions = s["omega"], s["offset"], s["positions"]
    ones = np.ones(len(x))
    factor = automaton.impact_factor(s["b"])
    rows: list[dict] = [{} for _ in automaton.ARCS]  # by state: a row's place in the table is its state
    for state, arc in automaton.ARCS.items():
        centre = automaton.centre(arc.mode, offset) * ones
        start = x if state == RELEASE else positions[state]
        best = None
        for kind in arc.watched:
            surface = automaton.SURFACES[kind]
            u0, q, k = arc_terms(centre, start, omega, positions[kind])
            row = dict(u0=u0, q=q, k=k, direction=surface.direction * ones, target=positions[kind] * ones,
                       jump=factor if surface.impact else ones, following=int(kind) * ones, centre=centre)
            if best is not None:  # the earlier of the two, where both are reached
                reached, dt, _, _ = crossing(u0, q, k, v, omega, float(surface.direction), np)
                first, first_dt, _, _ = crossing(best["u0"], best["q"], best["k"], v, omega, best["direction"], np)
                take = reached & ~(first & (first_dt <= dt))
                row = {name: np.where(take, row[name], best[name]) for name in row}
            best = row
        rows[state] = best
    table = {name: np.concatenate([row[name] for row in rows]) for name in rows[0]}
    table["following"] = table["following"].astype(np.intp)
    return table


def _pass(ii, index: np.ndarray, table: dict, s: dict, n_cycles: int, amplitude: bool) -> None:
    """One event of each running trajectory ``ii`` (a slice or their indices; ``index`` the indices): the row of
    its state, its closed form, the regime exits, the impact law, the cycle table at the impacts at a1."""
    flat = s["state"][ii] * len(s["x"]) + index  # the trajectories' rows in the table
    row = {name: column.take(flat) for name, column in table.items()}
    x, v, t, t_err, omega = (s[name][ii] for name in ("x", "v", "t", "t_err", "omega"))
    reached, dt, v1, angle = crossing(row["u0"], row["q"], row["k"], v, omega, row["direction"], np)
    if not reached.all():  # these leave the regime; the pass goes on with the others
        _exits(index[~reached], s)
        ii = index = index[reached]
        x, v, t, t_err, omega, dt, v1, angle = (a[reached] for a in (x, v, t, t_err, omega, dt, v1, angle))
        row = {name: value[reached] for name, value in row.items()}
    if amplitude:
        s["cycle_max"][ii] = np.maximum(s["cycle_max"][ii], arc_maximum(row["centre"], x, v, omega, angle,
                                                                        row["target"], v1))
    s["t"][ii], s["t_err"][ii] = compensated_add(t, t_err, dt)
    s["elapsed"][ii] += dt
    s["x"][ii] = row["target"]
    s["state"][ii] = row["following"]
    v_after = row["jump"] * v1  # the impact law at impacts (velocity_after), the velocity as it is elsewhere
    s["v"][ii] = v_after
    hit = row["following"] == _A1
    if hit.any():
        _impact_a1(index[hit], v1[hit], s, n_cycles, amplitude)
    chatter = automaton.reverses(v1, v_after) if s["rebounds"] else None  # some trajectory's impacts rebound
    if chatter is not None and chatter.any():
        chatter &= s["status"][index] == _RUNNING  # not those that completed their cycles
        for i, vb, va in zip(index[chatter], v1[chatter], v_after[chatter]):
            _chattering(i, EventKind(int(s["state"][i])), va, vb, s)


def _impact_a1(i1: np.ndarray, v_before: np.ndarray, s: dict, n_cycles: int, amplitude: bool) -> None:
    """The trajectories ``i1`` reached the impact at a1: a cycle ends (but the first) and the next begins.
    The tables are written through flat indices (cycle * trajectories + row)."""
    c = s["count"][i1]
    now = s["t"][i1] + s["t_err"][i1]
    cell = c * len(s["x"]) + i1
    s["times"].put(cell, now)
    s["speeds"].put(cell, v_before)
    later = c > 0
    ended = i1[later]
    cell = (c[later] - 1) * len(s["x"]) + ended  # the cycle that ends here
    if amplitude:
        s["maxima"].put(cell, s["cycle_max"][ended])
    s["periods"].put(cell, s["elapsed"][ended])
    s["elapsed"][i1] = 0.0
    s["cycle_max"][i1] = s["x"][i1]
    s["count"][i1] = c + 1
    done = i1[c + 1 >= n_cycles + 1]
    s["status"][done] = Status.COMPLETED.code
    s["t_final"][done] = s["t"][done] + s["t_err"][done]


def _check_completed_rows(status, times, speeds, periods, maxima, t_final) -> None:
    """A completed row holds only finite numbers; otherwise the input validation let through a
    value whose arithmetic leaves the float64 range: raise, naming the row (a bug, not an outcome)."""
    done = status == Status.COMPLETED.code
    columns = {"impact_time": times, "velocity_before_impact": speeds, "period": periods, "t_final": t_final[:, None]}
    if maxima is not None:
        columns["largest_displacement"] = maxima
    for name, values in columns.items():
        bad = done & ~np.isfinite(values).all(axis=1)
        if bad.any():
            raise FloatingPointError(
                f"row {int(np.flatnonzero(bad)[0])}: a completed run holds a non-finite {name}; the input "
                "validation (escapement.model.parameters) must refuse the inputs that lead to it"
            )



def _exits(rows: np.ndarray, s: dict) -> None:
    """Trajectories that pass no surface watched in their state, a state at a time."""
    for st in np.unique(s["state"][rows]):
        _exit(rows[s["state"][rows] == st], int(st), s)


def _exit(rows: np.ndarray, st: int, s: dict) -> None:
    """Trajectories that pass no surface watched in state ``st``: the escapement stopped (free flight), or the
    mass turned back in a zone."""
    arc = automaton.ARCS[st]
    centre = automaton.centre(arc.mode, s["offset"][rows])
    x, v, omega = s["x"][rows], s["v"][rows], s["omega"][rows]
    w = v / omega
    radius = np.hypot(x - centre, w)
    now = s["t"][rows] + s["t_err"][rows]
    if automaton.EXIT_WITHOUT_EVENT[arc.mode] is Status.STOPPED:  # the swing misses every watched position
        missed = np.min([np.abs(s["positions"][kind][rows]) for kind in arc.watched], axis=0)
        s["status"][rows] = Status.STOPPED.code
        s["t_final"][rows] = np.inf
        s["turning"][rows] = radius
        s["margin"][rows] = missed - radius
        return
    # a zone: the motion turns at centre + R moving right, centre - R moving left
    right = v > 0
    start = np.arctan2(w, x - centre)
    to_rest = np.where(v == 0, 0.0, np.where(right, start, start + math.pi)) / omega
    point = np.where(v == 0, x, centre + np.where(right, radius, -radius))
    end = s["positions"][automaton.ZONE_OF[arc.mode][1]][rows]
    s["status"][rows] = Status.TURNED_BACK_IN_ZONE.code
    s["t_final"][rows] = now + to_rest
    s["turning"][rows] = point
    s["margin"][rows] = np.abs(end - point)


def _chattering(i: int, kind: EventKind, v_after: float, v_before: float, s: dict) -> None:
    """A trajectory whose impact reversed the velocity: the time at which the rebounds accumulate."""
    distance = automaton.rebound_distance(kind, s["positions"][kind][i])
    now = s["t"][i] + s["t_err"][i]
    s["status"][i] = Status.CHATTERING.code
    s["t_final"][i] = now
    if distance > 0.0:
        s["t_acc"][i] = now + rebound_accumulation_time(float(s["omega"][i]), float(distance), abs(float(v_after)),
                                                        abs(float(v_after / v_before)))
