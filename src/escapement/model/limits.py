"""How long a run goes on: a number of cycles, an end time, and a bound on events."""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Integral, Real

from .parameters import ParameterError

__all__ = ["RunLimits"]

EVENTS_PER_CYCLE = 4
DEFAULT_MAX_EVENTS_FOR_TIME = 10_000_000


@dataclass(frozen=True)
class RunLimits:
    """A run ends at the first of: ``n_cycles`` complete cycles (``n_cycles + 1``
    impacts at a1), the time ``t_end``, or ``max_events`` events."""

    n_cycles: int | None = None
    t_end: float | None = None
    max_events: int | None = None

    def __post_init__(self) -> None:
        if self.n_cycles is None and self.t_end is None:
            raise ParameterError("n_cycles", None, "given (a positive integer) when t_end is not")
        if self.n_cycles is not None:
            if isinstance(self.n_cycles, bool) or not isinstance(self.n_cycles, Integral) or self.n_cycles < 1:
                raise ParameterError("n_cycles", self.n_cycles, "a positive integer")
        if self.t_end is not None:
            if isinstance(self.t_end, bool) or not isinstance(self.t_end, Real):
                raise ParameterError("t_end", self.t_end, "a real number")
            if not (math.isfinite(self.t_end) and self.t_end > 0):
                raise ParameterError("t_end", self.t_end, "finite and > 0 (s)")
            object.__setattr__(self, "t_end", float(self.t_end))
        if self.max_events is None:
            bound = DEFAULT_MAX_EVENTS_FOR_TIME
            if self.n_cycles is not None:
                bound = EVENTS_PER_CYCLE * (int(self.n_cycles) + 2) + 8
            object.__setattr__(self, "max_events", bound)
        elif isinstance(self.max_events, bool) or not isinstance(self.max_events, Integral) or self.max_events < 1:
            raise ParameterError("max_events", self.max_events, "a positive integer")
