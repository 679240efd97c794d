"""What a run is asked to do, checked before any work by :func:`run_spec`, the first step of every solver entry
point: its parameters, release and limits, and the memory its result may take (:func:`check_budget`)."""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .arguments import ParameterError, ParameterTypeError, check_count, check_flag, real_number
from .automaton import CHOICES
from .parameters import ParameterArrays, Parameters, check_initial_state, validate_arrays
from .printing import texts
from .quantities import MODEL_KEYS

__all__ = ["EVENTS_PER_CYCLE", "MAX_CYCLES", "MAX_DIGITS", "MAX_EVENTS", "MAX_MEMORY_BUDGET", "MEMORY_BUDGET",
           "MIN_DIGITS", "MemoryBudgetError", "RunLimits", "RunSpec", "check_budget", "check_count", "check_flag",
           "events_for", "run_spec"]

EVENTS_PER_CYCLE, DEFAULT_MAX_EVENTS_FOR_TIME = 4, 10_000_000
MAX_CYCLES = 1_000_000_000  #: the most cycles a run may ask for (the workflow's schema allows 10**8)
MAX_EVENTS = 5_000_000_000  #: the most events a run may take: room for the default of :data:`MAX_CYCLES` cycles
MIN_DIGITS, MAX_DIGITS = 17, 1000  #: the high-precision solver's digits: more than float64's 16, at most 1000
MEMORY_BUDGET = 2_000_000_000  #: the bytes a result may hold by default: 2 GB, a quarter of a laptop's 8 GB
MAX_MEMORY_BUDGET = 1_000_000_000_000  #: the largest memory budget a caller may give: 1 TB


class MemoryBudgetError(ParameterError):
    """A run whose stored output would exceed its memory budget, with the estimate and the budget in bytes."""

    def __init__(self, name: str, value: object, requirement: str, estimate: int, budget: int) -> None:
        super().__init__(name, value, requirement)
        self.estimate, self.budget = estimate, budget


def events_for(n_cycles: int) -> int:
    """The events of ``n_cycles`` cycles with a margin for the first ones."""
    return EVENTS_PER_CYCLE * (n_cycles + 2) + 8


@dataclass(frozen=True)
class RunLimits:
    """A run ends at the first of ``n_cycles`` complete cycles, the time ``t_end`` (s), or ``max_events`` events."""

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
        default = DEFAULT_MAX_EVENTS_FOR_TIME if self.n_cycles is None else events_for(self.n_cycles)
        events = default if self.max_events is None else check_count("max_events", self.max_events, MAX_EVENTS)
        object.__setattr__(self, "max_events", events)
        budget = MEMORY_BUDGET if self.memory_budget is None else self.memory_budget
        object.__setattr__(self, "memory_budget", check_count("memory_budget", budget, MAX_MEMORY_BUDGET))

    def check_memory(self, event_bytes: float, cycle_bytes: float, stores: str, remedy: str,
                     fixed_bytes: int = 0) -> int:
        """The bytes a run stores at most, if within the budget (:func:`check_budget`, on the count that binds)."""
        if self.n_cycles is not None and events_for(self.n_cycles) <= self.max_events:
            count = ("n_cycles", self.n_cycles, lambda n: fixed_bytes + events_for(n) * event_bytes + n * cycle_bytes)
        else:
            count = ("max_events", self.max_events,
                     lambda n: fixed_bytes + n * event_bytes + n // EVENTS_PER_CYCLE * cycle_bytes)
        return check_budget(self.memory_budget, stores, [count], remedy)


@dataclass(frozen=True)
class RunSpec:
    """A run as asked, every part checked (:func:`run_spec`); an ensemble's a row per trajectory."""

    params: Parameters | ParameterArrays
    x0: float | np.ndarray  #: m
    v0: float | np.ndarray  #: m/s
    limits: RunLimits


def run_spec(params: Parameters | Mapping[str, object], x0: object, v0: object = 0.0, *,
             n_cycles: int | None = None, t_end: float | None = None, max_events: int | None = None,
             memory_budget: int | None = None, rows: Callable[[int, int], float] | None = None,
             choices: bool = False) -> RunSpec:
    """The checked run, or the first invalid argument refused, named: ``params``, the release, then the limits.

    With ``rows`` (the ensemble's bytes for a number of trajectories and of cycles), ``params`` maps the model keys
    to numbers or arrays: the counts are checked first, then the memory from the inputs' shapes alone, then every
    row. A model's choice other than the default is refused unless the solver runs it (``choices``).
    """
    if rows is None:
        if not isinstance(params, Parameters):
            raise ParameterTypeError("params", params,
                                     "an escapement.Parameters (make one with Parameters(M=..., ...))")
        for name, value in params.chosen.items() if not choices else ():
            raise ParameterError(name, value, f"{CHOICES[name][0]!r} for this solver: only the event solvers "
                                 "(solve_exact, iter_cycles) run the model's other choices")
        x, v = check_initial_state(x0, v0)
        return RunSpec(params, x, v, RunLimits(n_cycles, t_end, max_events, memory_budget))
    limits = RunLimits(n_cycles, t_end, max_events, memory_budget)
    given = {**params, "x0": x0, "v0": v0}
    try:
        n = math.prod(np.broadcast_shapes(*(np.shape(value) for value in given.values() if value is not None)))
    except ValueError:  # shapes that do not broadcast: the validation names the input
        n = None
    if n is not None:
        cycles = limits.n_cycles
        check_budget(limits.memory_budget, f"the cycle tables of {n:_} trajectories", [
            ("n_cycles", cycles, lambda k: rows(n, k)), ("trajectories", n, lambda m: rows(m, cycles))])
    flat = {name: array.ravel() for name, array in validate_arrays(given, state=True).items()}
    return RunSpec(ParameterArrays(**{k: flat[k] for k in MODEL_KEYS}), flat["x0"], flat["v0"], limits)


def check_budget(budget: int, stores: str, counts: Sequence[tuple[str, int, Callable[[int], float]]],
                 remedy: str = "") -> int:
    """The bytes of a run, ``size(value)`` of the first of ``counts`` (each ``(name, value, size)``), if within
    ``budget``; else a :class:`MemoryBudgetError` naming the first count that fits at 1 with the most that fits."""
    estimate = int(math.ceil(counts[0][2](counts[0][1])))
    if estimate <= budget:
        return estimate
    if budget < 10**7:  # in bytes and, from 10 MB, in GB with the digits that tell them apart
        sizes = f"{estimate:_} bytes, over the memory budget of {budget:_} byte{'' if budget == 1 else 's'}"
    else:
        estimate_gb, budget_gb = texts([estimate / 1e9, budget / 1e9], 3)
        sizes = f"{estimate:_} bytes ({estimate_gb} GB), over the memory budget of {budget:_} bytes ({budget_gb} GB)"
    over = f"it would store {stores}, an estimated {sizes}"
    for name, value, size in counts:
        if size(1) <= budget:
            fits = bisect.bisect_right(range(1, value), budget, key=size)  # size grows with the count
            remedy = f"; {remedy}" if remedy else ""
            raise MemoryBudgetError(name, value, f"at most {fits:_} for the run to fit its memory budget: "
                                    f"{over}{remedy}", estimate, budget)
    least = int(math.ceil(size(1)))
    raise MemoryBudgetError("memory_budget", budget, f"at least {least:_} bytes, those of a run of {name} = 1 "
                            f"({over})", estimate, budget)
