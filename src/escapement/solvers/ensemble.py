"""The exact solver for many trajectories at once, in lock-step: each pass moves every running trajectory by one
event. The trajectories whose first event is the same share their state at every pass: sorted by it, each such group
moves as one slice of the arrays.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
from numpy.typing import ArrayLike

from ..model import automaton
from ..model.automaton import RELEASE
from ..model.events import EventKind
from ..model.kinematics import arc_maximum, compensated_add, crossing, rebound_accumulation_time, time_to_rest
from ..model.limits import RunSpec, check_flag, run_spec
from ..model.parameters import ParameterArrays, parameters_section
from ..model.quantities import MODEL_KEYS
from ..model.status import Status
from .describe import CYCLE_COLUMNS, CycleTable
from .kernel import A1, row, rows
from .result import EnsembleSolution

__all__ = ["CELL_BYTES", "ROW_BYTES", "ensemble_bytes", "solve_ensemble"]

CELL_BYTES = 48  #: bytes per trajectory and cycle: four tables of floats, a fifth while reordered (measured 40)
ROW_BYTES = 1000  #: bytes per trajectory whatever its cycles: rows, state and a pass's arrays (measured about 700)
_RUNNING = -1


def ensemble_bytes(n_trajectories: int, n_cycles: int) -> int:
    """The bytes :func:`solve_ensemble` takes at most for ``n_trajectories`` runs of ``n_cycles`` cycles."""
    return n_trajectories * (CELL_BYTES * n_cycles + ROW_BYTES)


@dataclass
class _Group:
    """Trajectories whose states agree at every pass (a slice while all run), and what they share."""

    members: slice | np.ndarray
    state: int
    first: int
    impacts: int = 0

    def indices(self) -> np.ndarray:
        m = self.members
        return np.arange(m.start, m.stop) if isinstance(m, slice) else m


def solve_ensemble(M: ArrayLike, K: ArrayLike, F: ArrayLike, b: ArrayLike, a1: ArrayLike, a2: ArrayLike,
                   a3: ArrayLike | None = None, a4: ArrayLike | None = None, x0: ArrayLike = 1.0, v0: ArrayLike = 0.0,
                   *, n_cycles: int, max_events: int | None = None, largest_displacement: bool = True,
                   memory_budget: int | None = None) -> EnsembleSolution:
    """Integrate every trajectory for ``n_cycles`` complete cycles (or until it leaves the regime).

    The inputs are numbers or arrays broadcast to one shape, an element a trajectory (a row of the result), each
    row checked as :class:`escapement.Parameters` and the run's size (:func:`ensemble_bytes`) against its budget.

    Parameters
    ----------
    {parameters}
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
        One row per trajectory: outcomes, end times (s), the cycle table of shape ``(N, n_cycles)``.

    Examples
    --------
    >>> from escapement import solve_ensemble
    >>> runs = solve_ensemble(M=1.0, K=1.0, F=[0.5, 1.0], b=0.1, a1=-0.1, a2=0.05, x0=1.0, n_cycles=3)  # two forces
    >>> runs.cycles.period[:, -1].round(4)  # s
    array([6.2991, 6.2979])
    """
    given = dict(zip(MODEL_KEYS, (M, K, F, b, a1, a2, a3, a4)))
    spec = run_spec(given, x0, v0, n_cycles=n_cycles, max_events=max_events, memory_budget=memory_budget,
                    rows=ensemble_bytes)
    largest_displacement = check_flag("largest_displacement", largest_displacement)
    with np.errstate(invalid="ignore", divide="ignore"):
        return _Ensemble(spec, largest_displacement).run()


if solve_ensemble.__doc__:  # None when docstrings are stripped (python -OO)
    solve_ensemble.__doc__ = solve_ensemble.__doc__.replace("{parameters}", parameters_section("float or array_like"))


class _Ensemble:
    """One ensemble run: its trajectories sorted by their first event, its groups, its rows."""

    def __init__(self, spec: RunSpec, amplitude: bool) -> None:
        self.n_cycles, self.max_events, self.amplitude = spec.limits.n_cycles, spec.limits.max_events, amplitude
        first = _first_events(spec)
        self.order = np.argsort(first, kind="stable")
        p = ParameterArrays(**{k: getattr(spec.params, k)[self.order] for k in MODEL_KEYS})
        n, cells = len(first), (self.n_cycles, len(first))
        # a row per trajectory (first events' order): its state, its cycle so far, how it ended; the cycle tables
        self.s = SimpleNamespace(
            omega=p.omega, factor=automaton.impact_factor(p.b), x=spec.x0[self.order], v=spec.v0[self.order],
            t=np.zeros(n), t_err=np.zeros(n), elapsed=np.zeros(n), cycle_max=np.zeros(n),
            status=np.full(n, _RUNNING, dtype=np.int8), t_final=np.full(n, np.nan), turning=np.full(n, np.nan),
            margin=np.full(n, np.nan), t_acc=np.full(n, np.nan), **{c: np.full(cells, np.nan) for c in CYCLE_COLUMNS})
        self.rebounds = bool(automaton.reverses(1.0, self.s.factor).any())  # some impacts reverse the velocity
        # the rows of the arcs after each state, where each arc starts and its centre; each event kind's position
        self.rows = rows(p)
        release = automaton.ARCS[RELEASE]
        self.release_rows = {kind: row(p, self.s.x, release.mode, kind) for kind in release.watched}
        self.position = {kind: automaton.position(kind, p) * np.ones(n) for kind in EventKind}
        self.start = {state: self.s.x if state == RELEASE else self.position[state] for state in automaton.ARCS}
        self.centre = {state: automaton.centre(arc.mode, p.zone_offset) * np.ones(n)
                       for state, arc in automaton.ARCS.items()}
        ranked, self.groups = first[self.order], []
        for kind in np.unique(ranked).tolist():
            members = slice(*np.searchsorted(ranked, [kind, kind + 1]).tolist())
            group = _Group(members, RELEASE, kind)
            if kind:
                self.groups.append(group)
            else:  # neither impact is reached from the release
                self._exit(group, np.ones(members.stop - members.start, dtype=bool))

    def run(self) -> EnsembleSolution:
        """Every pass, then the cycle tables put back in the order of the inputs."""
        for _ in range(self.max_events):
            self.groups = [g for g in self.groups if self._pass(g)]
            if not self.groups:
                break
        s = self.s
        for g in self.groups:  # the event bound: those still running end at their last event
            self._leave(g, np.ones(len(g.indices()), dtype=bool), Status.EVENT_LIMIT)
        done = s.status == Status.COMPLETED.code
        checked = [name for name in CYCLE_COLUMNS if self.amplitude or name != "largest_displacement"]
        for name, values in [*((name, getattr(s, name)) for name in checked), ("t_final", s.t_final[None, :])]:
            bad = done & ~np.isfinite(values).all(axis=0)
            if bad.any():  # a bug, not an outcome: the input validation let through what it must refuse
                raise FloatingPointError(f"row {int(self.order[np.flatnonzero(bad)[0]])}: a completed run holds a "
                                         f"non-finite {name}; the input validation (escapement.model.parameters) "
                                         "must refuse the inputs that lead to it")
        back = np.argsort(self.order)  # the inverse permutation
        tables = {}
        for name in CYCLE_COLUMNS:  # one at a time: at most one table more than the four at once
            tables[name] = getattr(s, name).T[back]
            setattr(s, name, None)
        return EnsembleSolution(status=s.status[back], cycles=CycleTable(**tables), t_final=s.t_final[back],
                                exit_turning_point=s.turning[back], exit_margin=s.margin[back],
                                exit_t_accumulation=s.t_acc[back])

    def _pass(self, g: _Group) -> bool:
        """One event of each trajectory of ``g``; False once none of the group runs on."""
        s, m, state = self.s, g.members, g.state
        arc = self.release_rows[g.first] if state == RELEASE else self.rows[state]
        v, omega = s.v[m], s.omega[m]
        reached, dt, v1, angle = crossing(arc.u0[m], arc.q[m], arc.k[m], v, omega, arc.direction, np)
        if not reached.all():  # these leave the regime; the pass goes on with the others
            if not self._exit(g, ~reached):
                return False
            m = g.members
            v, omega, dt, v1, angle = v[reached], omega[reached], dt[reached], v1[reached], angle[reached]
        if self.amplitude:
            reach = arc_maximum(self.centre[state][m], self.start[state][m], v, omega, angle,
                                self.position[arc.following][m], v1)
            s.cycle_max[m] = np.maximum(s.cycle_max[m], reach)
        s.t[m], s.t_err[m] = compensated_add(s.t[m], s.t_err[m], dt)
        s.elapsed[m] = s.elapsed[m] + dt
        v_after = s.factor[m] * v1 if arc.impact else v1  # the impact law at impacts (velocity_after)
        s.v[m] = v_after
        g.state = arc.following
        if g.state == A1:
            self._impact_a1(g, v1)
            if g.impacts == self.n_cycles + 1:
                s.status[m] = Status.COMPLETED.code
                s.t_final[m] = s.t[m] + s.t_err[m]
                return False
        if self.rebounds and arc.impact:
            chatter = automaton.reverses(v1, v_after)
            if chatter.any():
                return self._chattering(g, chatter, v1, v_after)
        return True

    def _impact_a1(self, g: _Group, v_before: np.ndarray) -> None:
        """The impact at a1 of the group's trajectories: the cycle it ends (but the first) and the next begins."""
        s, m, c = self.s, g.members, g.impacts
        if c >= 1:
            s.period[c - 1, m] = s.elapsed[m]
            if self.amplitude:
                s.largest_displacement[c - 1, m] = s.cycle_max[m]
        if c < self.n_cycles:
            s.impact_time[c, m] = s.t[m] + s.t_err[m]
            s.velocity_before_impact[c, m] = v_before
        s.elapsed[m] = 0.0
        s.cycle_max[m] = self.position[EventKind.IMPACT_A1][m]
        g.impacts = c + 1

    def _leave(self, g: _Group, gone: np.ndarray, status: Status) -> bool:
        """The members ``gone`` end with ``status`` (their unfinished cycle is no cycle); True while others run."""
        ids, s = g.indices(), self.s
        left = ids[gone]
        s.status[left] = status.code
        if status is Status.EVENT_LIMIT:
            s.t_final[left] = s.t[left] + s.t_err[left]
        if 1 <= g.impacts <= self.n_cycles:
            s.impact_time[g.impacts - 1, left] = np.nan
            s.velocity_before_impact[g.impacts - 1, left] = np.nan
        g.members = ids[~gone]
        return bool(len(g.members))

    def _exit(self, g: _Group, gone: np.ndarray) -> bool:
        """Members that pass no surface: stopped, or turned back in a zone; True while others run."""
        s, state = self.s, g.state
        ids = g.indices()[gone]
        arc = automaton.ARCS[state]
        centre, x, v, omega = self.centre[state][ids], self.start[state][ids], s.v[ids], s.omega[ids]
        if automaton.EXIT_WITHOUT_EVENT[arc.mode] is Status.STOPPED:  # the swing misses every watched position
            radius = np.hypot(x - centre, v / omega)
            missed = np.min([np.abs(self.position[kind][ids]) for kind in arc.watched], axis=0)
            s.t_final[ids], s.turning[ids], s.margin[ids] = np.inf, radius, missed - radius
            return self._leave(g, gone, Status.STOPPED)
        dt, point = time_to_rest(centre, x, v, omega, np)
        end = self.position[automaton.ZONE_OF[arc.mode][1]][ids]
        s.t_final[ids], s.turning[ids], s.margin[ids] = s.t[ids] + s.t_err[ids] + dt, point, np.abs(end - point)
        return self._leave(g, gone, Status.TURNED_BACK_IN_ZONE)

    def _chattering(self, g: _Group, chatter: np.ndarray, v_before: np.ndarray, v_after: np.ndarray) -> bool:
        """Members whose impact reversed the velocity: the time at which their rebounds accumulate."""
        s, kind = self.s, EventKind(g.state)
        for i, vb, va in zip(g.indices()[chatter], v_before[chatter], v_after[chatter]):
            distance = automaton.rebound_distance(kind, self.position[kind][i])
            s.t_final[i] = s.t[i] + s.t_err[i]
            if distance > 0.0:
                s.t_acc[i] = s.t_final[i] + rebound_accumulation_time(float(s.omega[i]), float(distance),
                                                                      abs(float(va)), abs(float(va / vb)))
        return self._leave(g, chatter, Status.CHATTERING)


def _first_events(spec: RunSpec) -> np.ndarray:
    """Each trajectory's first event: the impact the release reaches first (0: neither)."""
    p, x, v, release = spec.params, spec.x0, spec.v0, automaton.ARCS[RELEASE]
    first, earliest = np.zeros(len(x), dtype=np.intp), np.full(len(x), np.inf)
    for kind in release.watched:
        arc = row(p, x, release.mode, kind)
        reached, dt, _, _ = crossing(arc.u0, arc.q, arc.k, v, p.omega, arc.direction, np)
        sooner = reached & (dt < earliest)
        first, earliest = np.where(sooner, int(kind), first), np.where(sooner, dt, earliest)
    return first
