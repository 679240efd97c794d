"""Releases worked out in 50 digits for the tests: initial displacements that put a turning point where a test
needs it."""

from __future__ import annotations

import mpmath

from escapement import Parameters

__all__ = ["release_for_zone_turning_at"]


def release_for_zone_turning_at(p: Parameters, impact: str, turn: mpmath.mpf) -> float:
    """From rest at x0 (50 digits): the free arc reaches the impact position with v**2 = w**2 (x0**2 - a**2),
    the impact keeps (1 - b) of it, and the zone arc about c through (a, v+) turns at ``turn``:
    (v+ / w)**2 = (turn - c)**2 - (a - c)**2."""
    with mpmath.workdps(50):
        a = mpmath.mpf(getattr(p, impact))
        c = mpmath.mpf(p.F) / mpmath.mpf(p.K) * (1 if impact == "a1" else -1)
        w_after_sq = (turn - c) ** 2 - (a - c) ** 2
        return float(-mpmath.sqrt(a**2 + w_after_sq / (1 - mpmath.mpf(p.b)) ** 2) if impact == "a1"
                     else mpmath.sqrt(a**2 + w_after_sq / (1 - mpmath.mpf(p.b)) ** 2))
