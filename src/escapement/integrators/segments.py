"""The reference solver's backends: one segment of the motion, ending at the first surface it watches, by SciPy's
``solve_ivp`` or SUNDIALS CVODE, and the crossing of a surface inside it (hand-written: neither library reports a
crossing that a step passes together with the turning point just beyond it)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TypeAlias

import numpy as np

from ..model.arguments import sample_times
from ..model.printing import number, texts

__all__ = ["MAX_STEP_HALF_PERIODS", "ROOT_TOLERANCE", "CvodeIntegrator", "DenseSegments", "Hit", "SciPyIntegrator",
           "Segment", "Watch"]

#: a segment's dense output (SciPy's ``OdeSolution``): the state ``(x, v)`` at a time
Dense: TypeAlias = Callable[[float], np.ndarray]
#: the longest step, in half periods: the velocity's zeros are half a period apart, so a step holds at most one
MAX_STEP_HALF_PERIODS = 0.9
#: relative and absolute tolerance of the root finding on a dense output (scipy's own for events)
ROOT_TOLERANCE = 4.0 * np.finfo(float).eps


@dataclass(frozen=True)
class Watch:
    """An event a segment watches: ``x`` reaching ``position`` (None: ``v`` vanishing) moving in ``direction``."""

    position: float | None
    direction: int

    def value(self, y: Sequence[float]) -> float:
        """The watched quantity at the state ``y = (x, v)``: zero at the event."""
        return y[1] if self.position is None else y[0] - self.position

    @property
    def crossing(self) -> int:
        """Sign of the slope of ``value`` at the event."""
        return -self.direction if self.position is None else self.direction


@dataclass(frozen=True)
class Hit:
    """An event a segment met: its time, its watch's index and the state ``(x, v)`` there."""

    t: float
    index: int
    y: tuple[float, float]


@dataclass(frozen=True)
class Segment:
    """``x'' = -omega2 (x - centre)`` from ``y0`` at ``t0`` to ``t1`` at most, ending at the first of ``watches``."""

    omega2: float
    centre: float
    t0: float
    y0: tuple[float, float]
    t1: float
    watches: tuple[Watch, ...]

    @property
    def max_step(self) -> float:
        """The longest step, below half a period (see :data:`MAX_STEP_HALF_PERIODS`)."""
        return MAX_STEP_HALF_PERIODS * math.pi / math.sqrt(self.omega2)


class SciPyIntegrator:
    """One segment with ``scipy.integrate.solve_ivp``."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray, dense: bool) -> None:
        # loaded when a reference run starts: a job that runs only the exact solver does not pay for it (0.7 s)
        from scipy.integrate import solve_ivp
        from scipy.optimize import brentq

        self._solve_ivp, self._brentq = solve_ivp, brentq
        self.method, self.rtol, self.atol, self.dense = method, rtol, atol, dense
        self.name = f"solve_ivp {method} rtol={rtol:g}"

    def segment(self, seg: Segment, dense: bool | None = None) -> tuple[Hit | None, Dense | None]:
        """The first event of the segment (None: none before ``t1``) and, if kept, the dense output."""
        omega2, centre, dense = seg.omega2, seg.centre, self.dense if dense is None else dense
        functions = [lambda _t, y, w=w: w.value(y) for w in seg.watches]
        for event, w in zip(functions, seg.watches):
            event.terminal, event.direction = True, w.crossing
        implicit = {"jac": [[0.0, 1.0], [-omega2, 0.0]]} if self.method in ("Radau", "BDF", "LSODA") else {}
        sol = self._solve_ivp(lambda _t, y: [y[1], -omega2 * (y[0] - centre)], (seg.t0, seg.t1), list(seg.y0),
                              method=self.method, rtol=self.rtol, atol=self.atol, events=functions or None,
                              dense_output=dense, max_step=seg.max_step, **implicit)
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at t = {seg.t0:.12g} s: {sol.message}")
        hits = [Hit(float(te[0]), i, (float(ye[0][0]), float(ye[0][1])))
                for i, (te, ye) in enumerate(zip(sol.t_events or [], sol.y_events or [])) if len(te)]
        return min(hits, key=lambda hit: hit.t, default=None), (sol.sol if dense else None)

    def crossing(self, seg: Segment, dense: Dense | None, end: Hit, index: int) -> Hit:
        """Where ``x`` reaches ``seg.watches[index]`` before ``end``, on the segment's dense output (integrated again,
        the same steps, if it was not kept)."""
        if dense is None:
            again, dense = self.segment(seg, True)
            if again != end:
                raise RuntimeError(f"solve_ivp is not repeatable at t = {seg.t0:.12g} s: {again} != {end}")
        position = seg.watches[index].position
        t = self._brentq(lambda t: float(dense(t)[0]) - position, seg.t0, end.t, xtol=ROOT_TOLERANCE,
                         rtol=ROOT_TOLERANCE)
        y = dense(t)
        return Hit(float(t), index, (float(y[0]), float(y[1])))


class CvodeIntegrator:
    """One segment with SUNDIALS CVODE (scikit-sundae), Adams or BDF, with its root finding."""

    def __init__(self, method: str, rtol: float, atol: np.ndarray) -> None:
        from sksundae.cvode import CVODE  # optional: only the benchmark needs it

        self._cvode = CVODE
        self.method, self.rtol, self.atol = method, rtol, atol
        self.name = f"CVODE {method} rtol={rtol:g}"

    def _solve(self, seg: Segment, watches: tuple[Watch, ...], directions: list[int], t_from: float, y_from,
               t_to: float) -> Hit | None:
        omega2, centre = seg.omega2, seg.centre

        def rhs(_t, y, yp):
            yp[0], yp[1] = y[1], -omega2 * (y[0] - centre)

        def events(_t, y, out):
            for i, w in enumerate(watches):
                out[i] = w.value(y)

        events.terminal, events.direction = [True] * len(watches), directions
        solver = self._cvode(rhs, method=self.method, rtol=self.rtol, atol=self.atol, eventsfn=events,
                             num_events=len(watches), max_num_steps=1_000_000, max_step=seg.max_step)
        result = solver.solve([t_from, t_to], np.array(y_from, dtype=float))
        if not result.success:
            raise RuntimeError(f"CVODE failed at t = {t_from:.12g} s: {result.message}")
        if result.t_events is None or len(result.t_events) == 0:
            return None
        index = int(np.flatnonzero(result.i_events[0])[0])
        y = result.y_events[0]
        return Hit(float(result.t_events[0]), index, (float(y[0]), float(y[1])))

    def segment(self, seg: Segment) -> tuple[Hit | None, None]:
        """The first event of the segment (None: none before ``t1``); CVODE keeps no dense output."""
        return self._solve(seg, seg.watches, [w.crossing for w in seg.watches], seg.t0, seg.y0, seg.t1), None

    def crossing(self, seg: Segment, dense: Dense | None, end: Hit, index: int) -> Hit:
        """Where ``x`` reaches ``seg.watches[index]`` before ``end``, integrating back from ``end`` (one crossing)."""
        watch = seg.watches[index]
        back = self._solve(seg, (watch,), [0], end.t, end.y, seg.t0)
        if back is None:
            raise RuntimeError(f"CVODE found no crossing of x = {watch.position!r} m between t = {seg.t0:.12g} s "
                               f"and t = {end.t:.12g} s, where the segment passed it")
        return Hit(back.t, index, back.y)


@dataclass(frozen=True, repr=False)
class DenseSegments:
    """The motion as solve_ivp's dense output, one interpolant per segment."""

    t_start: np.ndarray
    interpolants: tuple
    centre: np.ndarray
    omega: float
    t_final: float

    def __repr__(self) -> str:
        """One line: the number of segments and the time span, never the arrays."""
        n = len(self.t_start)
        if not n:
            return f"<DenseSegments> no segments, omega = {number(self.omega, 'rad/s')}"
        start, end = texts([self.t_start[0], self.t_final])
        return (f"<DenseSegments> {n} segment{'' if n == 1 else 's'} of dense output from t = {start} s to "
                f"t_final = {end} s, omega = {number(self.omega, 'rad/s')}")

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement, velocity and acceleration at times ``t`` (NaN outside [0, t_final])."""
        t = sample_times("t", t)
        x, v, a = (np.full(t.shape, np.nan) for _ in range(3))
        idx = np.searchsorted(self.t_start, t, side="right") - 1
        valid = (idx >= 0) & (t >= 0.0) & (t <= self.t_final)
        for i in np.unique(idx[valid]):
            sel = valid & (idx == i)
            y = self.interpolants[i](t[sel])
            x[sel], v[sel] = y[0], y[1]
            a[sel] = -(self.omega**2) * (y[0] - self.centre[i])
        return x, v, a
