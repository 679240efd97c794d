"""The exact event-driven solver.

Between events the motion is a harmonic arc about the current mode's centre, so each event
(impact, end of an impulse zone) comes from a closed form
(:func:`escapement.model.kinematics.crossing`): no step size, no root finding, errors at the
level of floating-point rounding. The escapement's rules come from
:mod:`escapement.model.automaton` through the solver loop :func:`escapement.solvers.driver.drive`.
"""

from __future__ import annotations

import math
from array import array

import numpy as np

from ..model import automaton
from ..model.kinematics import arc_maximum, crossing, time_to_rest
from ..model.limits import RunLimits
from ..model.parameters import Parameters, check_initial_state
from .driver import NO_EVENT, Step, drive
from .result import ArcTable, Solution

__all__ = ["ClosedFormStepper", "solve_exact"]


class ClosedFormStepper:
    """Each event in closed form; keeps the arcs for sampling when asked to."""

    name = "exact"

    def __init__(self, params: Parameters, record_trajectory: bool) -> None:
        self.omega = params.omega
        self.targets = {kind: (automaton.position(kind, params), s.direction) for kind, s in automaton.SURFACES.items()}
        self.record = record_trajectory
        self.arcs = tuple(array("d") for _ in range(4))

    def next_event(self, mode, centre, t, x, v, watched, t_stop) -> Step:
        omega = self.omega
        if self.record:
            for column, value in zip(self.arcs, (t, centre, x, v)):
                column.append(value)
        best = None
        for kind in watched:
            target, direction = self.targets[kind]
            reached, dt, v_new, angle = crossing(centre, x, v, omega, target, direction)
            if reached and (best is None or dt < best[1]):
                best = (kind, dt, v_new, angle, target)
        if best is None:
            if mode == automaton.Mode.FREE:
                return Step(NO_EVENT, math.inf, 0.0, math.hypot(x, v / omega))
            rest_dt, turning_point = time_to_rest(centre, x, v, omega)
            return Step(NO_EVENT, rest_dt, 0.0, turning_point)
        kind, dt, v_new, angle, target = best
        return kind, dt, v_new, arc_maximum(centre, x, v, omega, angle, target), None, None  # a Step

    def trajectory(self, t_final: float) -> ArcTable | None:
        if not self.record:
            return None
        t_start, centre, x_start, v_start = (np.frombuffer(c, dtype=float).copy() for c in self.arcs)
        return ArcTable(t_start, centre, x_start, v_start, self.omega, t_final)


def solve_exact(
    params: Parameters,
    x0: float,
    v0: float = 0.0,
    *,
    n_cycles: int | None = None,
    t_end: float | None = None,
    max_events: int | None = None,
    record_trajectory: bool = True,
) -> Solution:
    """Integrate the escapement model exactly from ``(x0, v0)`` at ``t = 0+``.

    The run ends after ``n_cycles`` complete cycles, at ``t_end``, after ``max_events``
    events, or when the motion leaves the escapement regime; the returned
    :class:`~escapement.solvers.result.Solution` says which, in ``status`` and ``message``.
    With ``record_trajectory=False`` the arcs are not kept (for long runs that need only
    events and cycles).
    """
    if not isinstance(params, Parameters):
        raise TypeError("params must be an escapement.Parameters")
    x, v = check_initial_state(x0, v0)
    limits = RunLimits(n_cycles=n_cycles, t_end=t_end, max_events=max_events)
    return drive(params, x, v, limits, ClosedFormStepper(params, record_trajectory), x0=x, v0=v)
