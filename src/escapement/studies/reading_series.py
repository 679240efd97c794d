"""The series a candidate reading of the paper's figures would plot, read from one exact run: the cycles of a
Poincare section, a quantity over a time window or the phase points as a plot would draw them, with the exact
extremes of every arc and the one-sided values at every event. :class:`Runs` makes each run once.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..model.arguments import check_choice, check_count, real_number
from ..model.events import EventKind
from ..model.parameters import Parameters
from ..solvers.exact import solve_exact
from ..solvers.result import Solution

__all__ = ["SECTIONS", "Runs", "SectionCycles", "critical_times", "phase_series", "section_cycles", "window_series"]

#: the Poincare sections: the impact at a1 (the paper's), or its mirror image, the impact at a3
SECTIONS: dict[str, EventKind] = {"a1": EventKind.IMPACT_A1, "a3": EventKind.IMPACT_A3}


class Runs:
    """One exact run from rest per ``(F, K, x0)`` of ``model``: :meth:`need` states what a reading reads before any
    run is made, :meth:`get` solves once for the most that was stated."""

    def __init__(self, model: Mapping) -> None:
        self.model = dict(model)
        self._needs: dict[tuple[float, float, float], tuple[int, float]] = {}
        self._runs: dict[tuple[float, float, float], Solution] = {}
        self.solved = 0  #: the runs made (each key once)

    def need(self, F: float, K: float, x0: float, n_cycles: int = 0, t_end: float = 0.0) -> None:
        """Record that a reading reads ``n_cycles`` complete cycles and the motion up to ``t_end``."""
        check_count("n_cycles", n_cycles, 10**9, minimum=0)
        real_number("t_end", t_end, lambda t: t >= 0, ">= 0")
        key = (float(F), float(K), float(x0))
        stated = self._needs.get(key, (0, 0.0))
        n, t = max(stated[0], n_cycles), max(stated[1], float(t_end))
        # a run is made for the needs stated before it; restating no more is fine, even for a run that left the regime
        if key in self._runs and (n, t) != stated:
            raise ValueError(f"the run F = {F:g} N, K = {K:g} N/m, x0 = {x0:+g} m is already made; "
                             f"state every need (n_cycles = {n_cycles}, t_end = {t_end:g}) before the first get")
        self._needs[key] = (n, t)

    def get(self, F: float, K: float, x0: float) -> Solution:
        """The run of ``(F, K, x0)``, solved on first use for every need stated."""
        key = (float(F), float(K), float(x0))
        if key not in self._needs:
            raise KeyError(f"no need stated for F = {F:g} N, K = {K:g} N/m, x0 = {x0:+g} m")
        if key not in self._runs:
            p = Parameters.from_mapping({**self.model, "F": key[0], "K": key[1]})
            n, t = self._needs[key]
            cycles = max(n, math.ceil(t / p.natural_period) + 2 if t > 0 else 0, 1)
            run = solve_exact(p, key[2], n_cycles=cycles)
            self.solved += 1
            # a cycle is shorter than the natural period by far less than two cycles; else it is made once more
            while run.success and run.t_final < t:
                cycles += math.ceil((t - run.t_final) / p.natural_period) + 2
                run = solve_exact(p, key[2], n_cycles=cycles)
                self.solved += 1
            self._runs[key] = run
        return self._runs[key]

    def outcome(self, F: float, K: float, x0: float, n_cycles: int = 0, t_end: float = 0.0) -> str:
        """``completed`` when the run holds what a reading reads (``n_cycles``, ``t_end``), else how it ended."""
        run = self.get(F, K, x0)
        if len(run.cycles) >= n_cycles and run.t_final >= t_end:
            return "completed"
        return run.status.value if not run.success else f"{run.status.value}: ended at {run.t_final:g} s"


def critical_times(run: Solution, lo: float, hi: float) -> np.ndarray:
    """The times in ``[lo, hi]`` at which an arc of ``run`` has a phase that is a multiple of pi/2: the extremes of
    ``x``, ``v`` and the acceleration."""
    arcs = run.trajectory
    if arcs is None:
        raise ValueError("the run kept no trajectory; solve with record_trajectory=True")
    start = np.asarray(arcs.t_start, dtype=float)
    end = np.append(start[1:], arcs.t_final)
    keep = (end >= lo) & (start <= hi)
    start, end = start[keep], end[keep]
    u0 = np.asarray(arcs.x_start)[keep] - np.asarray(arcs.centre)[keep]
    w = arcs.omega
    # x - centre = A cos(w (t - start) - phi): critical where w (t - start) = phi + k pi/2
    phi = np.arctan2(np.asarray(arcs.v_start)[keep] / w, u0)
    quarter = 0.5 * math.pi
    k_first = np.ceil(-phi / quarter).astype(int)
    k_last = np.floor((w * (np.minimum(end, hi) - start) - phi) / quarter).astype(int)
    times = [s + (p + np.arange(a, b + 1) * quarter) / w for s, p, a, b in zip(start, phi, k_first, k_last) if b >= a]
    if not times:
        return np.empty(0)
    t = np.concatenate(times)
    return np.sort(t[(t >= lo) & (t <= hi)])


def _centres_at_events(run: Solution, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The centre of oscillation just before and just after each event of ``index``."""
    arcs = run.trajectory
    t_event = run.events.t[index]
    after = np.searchsorted(arcs.t_start, t_event, side="left")
    if np.any(after >= len(arcs.t_start)) or not np.array_equal(arcs.t_start[after], t_event):
        raise ValueError("an event has no arc starting at its time")
    return arcs.centre[after - 1], arcs.centre[after]


def _grid(run: Solution, lo: float, hi: float, samples_per_second: float):
    """The times a plot samples over ``[lo, hi]``, the events there, and the order of the samples and events."""
    n = max(2, int(round((hi - lo) * samples_per_second)) + 1)
    t = np.union1d(np.linspace(lo, hi, n), critical_times(run, lo, hi))
    index = np.flatnonzero((run.events.t >= lo) & (run.events.t <= hi))
    return t, index, np.argsort(np.concatenate([t, np.repeat(run.events.t[index], 2)]), kind="stable")


def _joined(values: np.ndarray, before: np.ndarray, after: np.ndarray, order: np.ndarray) -> np.ndarray:
    return np.concatenate([values, np.ravel(np.column_stack([before, after]))])[order]


def window_series(run: Solution, lo: float, hi: float, samples_per_second: float, quantity: str
                  ) -> tuple[np.ndarray, np.ndarray]:
    """``(t, values)`` of ``quantity`` ("displacement", "velocity" or "acceleration") over ``[lo, hi]`` as a plot
    would draw it, and at each event in the window its values just before and just after (at the event's time)."""
    quantities = ("displacement", "velocity", "acceleration")
    check_choice("quantity", quantity, quantities)
    t, index, order = _grid(run, lo, hi, samples_per_second)
    values = run.sample(t)[quantities.index(quantity)]
    if quantity == "displacement":
        before = after = run.events.x[index]
    elif quantity == "velocity":
        before, after = run.events.v_before[index], run.events.v_after[index]
    else:
        w2 = run.params.omega2
        c_before, c_after = _centres_at_events(run, index)
        before = -w2 * (run.events.x[index] - c_before)
        after = -w2 * (run.events.x[index] - c_after)
    return np.concatenate([t, np.repeat(run.events.t[index], 2)])[order], _joined(values, before, after, order)


def phase_series(run: Solution, lo: float, hi: float, samples_per_second: float) -> tuple[np.ndarray, np.ndarray]:
    """``(x, v)`` over ``[lo, hi]`` as a plot would draw it, each event a vertical jump at its position."""
    t, index, order = _grid(run, lo, hi, samples_per_second)
    x, v, _ = run.sample(t)
    ev = run.events
    return _joined(x, ev.x[index], ev.x[index], order), _joined(v, ev.v_before[index], ev.v_after[index], order)


@dataclass(frozen=True)
class SectionCycles:
    """Per cycle ``k`` of a section (from its impact k to impact k + 1); ``speed`` and ``h0`` one per impact."""

    speed: np.ndarray  #: |v| just before impact k at the section, m/s
    h0: np.ndarray  #: the amplitude sqrt(a**2 + (v / omega)**2) of the free arc ending in impact k, m
    period: np.ndarray  #: time from impact k to impact k + 1, s
    right: np.ndarray  #: the largest x of cycle k (the right turning point), m
    left: np.ndarray  #: the largest -x of cycle k (|x| at the left turning point), m


def section_cycles(run: Solution, section: str) -> SectionCycles:
    """The cycles of ``run`` at the Poincare section ``section`` ("a1" or "a3"), the turning points exact."""
    check_choice("section", section, SECTIONS)
    ev = run.events
    i = ev.of_kind(SECTIONS[section])
    t, x, v = (np.asarray(a, dtype=float)[i] for a in (ev.t, ev.x, ev.v_before))
    speed = np.abs(v)
    h0 = np.hypot(x, speed / run.params.omega)
    tc = critical_times(run, 0.0, run.t_final)
    xc = run.sample(tc)[0]
    right, left = np.empty(max(len(t) - 1, 0)), np.empty(max(len(t) - 1, 0))
    for k in range(len(t) - 1):
        lo, hi = np.searchsorted(tc, [t[k], t[k + 1]], side="left")
        inside = np.concatenate([[x[k], x[k + 1]], xc[lo:hi]])
        right[k], left[k] = inside.max(), -inside.min()
    return SectionCycles(speed, h0, np.diff(t), right, left)
