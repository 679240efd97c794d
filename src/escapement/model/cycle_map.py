"""The return map of a cycle, ``v_{k+1}**2 = mu v_k**2 + c`` in the velocity before the impact at a1, derived
from the arcs of one cycle by energy (the one place its constants are computed)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from . import automaton
from .parameters import Parameters

__all__ = ["CycleMap", "cycle_map"]


@dataclass(frozen=True)
class CycleMap:
    """The return map ``v_{k+1}**2 = mu v_k**2 + c`` of the velocity before the impact at a1 (:func:`cycle_map`)."""

    mu: float  #: ``r**4``, the multiplier of ``v**2`` (``r = 1 - b``, the impact law's factor)
    c: float  #: the constant, m**2/s**2
    one_minus_mu: float  #: ``1 - mu = (1 - r)(1 + r)(1 + r**2)``
    log_mu: float  #: ``ln mu = 4 log1p(r - 1)`` (``-inf`` at ``r = 0``)

    @property
    def fixed_point_sq(self) -> float:
        """``v***2 = c / (1 - mu)``, m**2/s**2 (not positive: no fixed point)."""
        return self.c / self.one_minus_mu

    @property
    def fixed_point(self) -> float:
        """``v*``, m/s; NaN where ``v***2 <= 0``."""
        sq = self.fixed_point_sq
        return math.sqrt(sq) if sq > 0.0 else math.nan

    def velocity_sq(self, v1: float, k: ArrayLike) -> np.ndarray:
        """``v_k**2 = v***2 + (v1**2 - v***2) mu**(k-1)`` for the cycle numbers ``k`` (1 for the first), the power as
        ``exp((k-1) ln mu)``: a power of the rounded ``mu`` would carry its rounding ``k - 1`` times."""
        star = self.fixed_point_sq
        steps = np.asarray(k, dtype=float) - 1.0
        decay = np.exp(steps * self.log_mu) if math.isfinite(self.log_mu) else np.power(self.mu, steps)
        return star + (v1 * v1 - star) * decay


def cycle_map(params: Parameters) -> CycleMap:
    """The constants of the return map ``v_{k+1}**2 = mu v_k**2 + c`` for any geometry (``c`` in m**2/s**2).

    Over the four arcs of a cycle (a1 to a2 about ``+F/K``, a2 to a3 free, a3 to a4 about ``-F/K``, a4 to a1 free)
    energy gives ``v_y**2 = v_x**2 + w**2 (x - y)(x + y - 2 c)``, and each impact multiplies ``v`` by
    ``r = 1 - b``. With ``f = F/M`` and ``beta = r**2``:

    * ``mu = beta**2``, ``1 - mu = (1 - r)(1 + r)(1 + r**2)`` (``1 - r`` is exact for ``r >= 1/2``: no
      cancellation as ``b -> 0``);
    * ``c = (1 - beta) w**2 (a3**2 - a1**2) + 2 f [beta (a2 - a1) + (a3 - a4)]``;
    * the fixed point ``v***2 = c / (1 - mu)``; in the symmetric case (``a3 = -a1``, ``a4 = -a2``)
      ``v***2 = 2 f (a2 - a1) / (1 - beta) = 2 f (a2 - a1) / (b (2 - b))``.
    """
    w2, f, r = params.omega2, params.f, automaton.impact_factor(params.b)
    beta = r * r
    one_minus_beta = (1.0 - r) * (1.0 + r)
    c = (one_minus_beta * w2 * ((params.a3 - params.a1) * (params.a3 + params.a1))
         + 2.0 * f * (beta * (params.a2 - params.a1) + (params.a3 - params.a4)))
    log_mu = 4.0 * math.log1p(r - 1.0) if r > 0.0 else -math.inf
    return CycleMap(mu=beta * beta, c=c, one_minus_mu=one_minus_beta * (1.0 + beta), log_mu=log_mu)
