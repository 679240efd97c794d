"""How long a run goes on: a number of cycles, an end time, and a bound on events.

Every count a solver takes (``n_cycles``, ``max_events``, the digits of the high-precision
solver) is checked by :func:`~escapement.model.arguments.check_count` (re-exported here with
:func:`~escapement.model.arguments.check_flag`): a positive integer (not a bool), at most a stated
maximum, or a :class:`~escapement.model.arguments.ParameterError` that names it; the end time by
:func:`~escapement.model.arguments.real_number`. The scalar
solvers and the ensemble take their limits through :class:`RunLimits`, so they refuse the same
values with the same message.

A run also has a memory budget (:attr:`RunLimits.memory_budget`, by default
:data:`MEMORY_BUDGET` bytes): a solver estimates, before any work, the bytes its result will
hold (events, cycle table, trajectory) from the limits alone, and refuses a run whose estimate
exceeds the budget with a :class:`MemoryBudgetError` that states both. The exact solver streams
its cycles in constant memory (:func:`escapement.solvers.stream.iter_cycles`) for runs that do
not fit.
"""

from __future__ import annotations

from dataclasses import dataclass

from .arguments import ParameterError, check_count, check_flag, real_number

__all__ = [
    "EVENTS_PER_CYCLE",
    "MAX_CYCLES",
    "MAX_DIGITS",
    "MAX_EVENTS",
    "MAX_MEMORY_BUDGET",
    "MEMORY_BUDGET",
    "MIN_DIGITS",
    "MemoryBudgetError",
    "RunLimits",
    "check_count",
    "check_flag",
]

EVENTS_PER_CYCLE = 4
DEFAULT_MAX_EVENTS_FOR_TIME = 10_000_000
#: the most cycles a run may ask for (the workflow's longest run is 10**6 cycles, its schema allows 10**8)
MAX_CYCLES = 1_000_000_000
#: the most events a run may take: room for the default bound of :data:`MAX_CYCLES` cycles
MAX_EVENTS = 5_000_000_000
#: the significant digits the high-precision solver may work with: more than float64's 16, at most 1000
MIN_DIGITS, MAX_DIGITS = 17, 1000
#: the bytes a run's result may hold unless the caller says otherwise: 2 GB, a quarter of a laptop's 8 GB
MEMORY_BUDGET = 2_000_000_000
#: the largest memory budget a caller may give: 1 TB
MAX_MEMORY_BUDGET = 1_000_000_000_000


class MemoryBudgetError(ParameterError):
    """A run whose stored output would exceed its memory budget; a :class:`ParameterError` that names
    the count which sets the size (``n_cycles``, ``max_events`` or the number of trajectories), with the
    estimate and the budget in bytes."""

    def __init__(self, name: str, value: object, requirement: str, estimate: int, budget: int) -> None:
        super().__init__(name, value, requirement)
        self.estimate = estimate
        self.budget = budget


@dataclass(frozen=True)
class RunLimits:
    """A run ends at the first of: ``n_cycles`` complete cycles (``n_cycles + 1``
    impacts at a1), the time ``t_end``, or ``max_events`` events.

    ``n_cycles`` is at most :data:`MAX_CYCLES` and ``max_events`` at most :data:`MAX_EVENTS`;
    ``max_events`` defaults to the events of ``n_cycles`` cycles with a margin, or to
    10**7 for a run to ``t_end`` alone. ``memory_budget`` (bytes, at most :data:`MAX_MEMORY_BUDGET`)
    defaults to :data:`MEMORY_BUDGET`.
    """

    n_cycles: int | None = None
    t_end: float | None = None
    max_events: int | None = None
    memory_budget: int | None = None

    def __post_init__(self) -> None:
        if self.n_cycles is None and self.t_end is None:
            raise ParameterError("n_cycles", None, "given (a positive integer) when t_end is not")
        if self.n_cycles is not None:
            object.__setattr__(self, "n_cycles", check_count("n_cycles", self.n_cycles, MAX_CYCLES))
        if self.t_end is not None:
            object.__setattr__(self, "t_end", real_number("t_end", self.t_end, lambda t: t > 0, "> 0 (s)"))
        if self.max_events is None:
            bound = DEFAULT_MAX_EVENTS_FOR_TIME
            if self.n_cycles is not None:
                bound = events_for(self.n_cycles)
            object.__setattr__(self, "max_events", bound)
        else:
            object.__setattr__(self, "max_events", check_count("max_events", self.max_events, MAX_EVENTS))
        budget = MEMORY_BUDGET if self.memory_budget is None else self.memory_budget
        object.__setattr__(self, "memory_budget", check_count("memory_budget", budget, MAX_MEMORY_BUDGET))

    @property
    def stored_events(self) -> int:
        """The most events the run can take: ``max_events``, or fewer for ``n_cycles`` cycles."""
        if self.n_cycles is None:
            return self.max_events
        return min(self.max_events, events_for(self.n_cycles))

    @property
    def stored_cycles(self) -> int:
        """The most complete cycles the run can hold: ``n_cycles``, or the cycles that ``stored_events``
        events make (each takes :data:`EVENTS_PER_CYCLE` of them)."""
        most = self.stored_events // EVENTS_PER_CYCLE
        return most if self.n_cycles is None else min(self.n_cycles, most)


def events_for(n_cycles: int) -> int:
    """The events of ``n_cycles`` cycles with a margin for the first ones (the default ``max_events``)."""
    return EVENTS_PER_CYCLE * (n_cycles + 2) + 8
