"""The replicated periods, the number that contradicts the paper, against a closed form derived here, evaluated in
40-digit arithmetic with no code of the package. The symmetric escapement of Sec. 4 (a3 = -a1, a4 = -a2, omega =
sqrt(K/M), f = F/M) on its limit cycle: energy over one cycle gives the fixed point of the velocity before the impact at
a1, v*^2 = 2 (a2 - a1) f / (2b - b^2) (Eq. (19)). A harmonic arc about a centre c is u = x - c = R cos(theta),
v = -omega R sin(theta), theta growing at the rate omega, so the time between two states of one arc is the difference
of theta = atan2(-v / omega, u) over omega (on the branch where it grows). One half cycle:

* the impulse zone, centred at c = f / omega^2, from a1 with v0 = (1 - b) v* to a2 with
  v1^2 = v0^2 + omega^2 ((a1 - c)^2 - (a2 - c)^2), both moving right (theta in (-pi, 0));
* free flight about 0 from a2 (moving right, theta in (-pi, 0)) past a3, through the right turning
  point, back to a3 moving left (theta in (0, pi)), with v3^2 = v1^2 + omega^2 (a2^2 - a3^2);

and by the symmetry the other half is its mirror image, so T = 2 (t_zone + t_free), and v3 = v*.
"""

from __future__ import annotations

import mpmath
import pytest

from escapement.model.parameters import Parameters
from escapement.solvers.exact import solve_exact


def limit_cycle(F: str, M: str = "1", K: str = "1", b: str = "0.1", a1: str = "-0.1", a2: str = "0.05"):
    """``(T, v*)`` of the symmetric limit cycle, from the derivation above, in 40 digits."""
    with mpmath.workdps(40):
        return _limit_cycle(*(mpmath.mpf(x) for x in (F, M, K, b, a1, a2)))


def _limit_cycle(F, M, K, b, a1, a2):
    w, f, a3 = mpmath.sqrt(K / M), F / M, -a1
    v_star = mpmath.sqrt(2 * (a2 - a1) * f / (2 * b - b * b))
    c = f / w**2
    v0 = (1 - b) * v_star
    v1 = mpmath.sqrt(v0**2 + w**2 * ((a1 - c) ** 2 - (a2 - c) ** 2))
    t_zone = (mpmath.atan2(-v1 / w, a2 - c) - mpmath.atan2(-v0 / w, a1 - c)) / w
    v3 = mpmath.sqrt(v1**2 + w**2 * (a2**2 - a3**2))
    t_free = (mpmath.atan2(v3 / w, a3) - mpmath.atan2(-v1 / w, a2)) / w
    assert abs(v3 - v_star) < mpmath.mpf(10) ** -35  # the half cycle ends where it began, mirrored
    return 2 * (t_zone + t_free), v_star


def test_the_closed_form_gives_the_periods_an_independent_simulator_gives():
    # an independent referee's simulator (40-digit mpmath, checked against solve_ivp) gives 6.29567362967 s
    # (case a) and 6.30073853677 s (case b), against 2 pi = 6.283185307 s
    assert float(limit_cycle("1")[0]) == pytest.approx(6.29567362967, abs=5e-12)
    assert float(limit_cycle("0.5")[0]) == pytest.approx(6.30073853677, abs=5e-12)


@pytest.mark.parametrize("F, x0", [("1", -1.0), ("0.5", -3.0), ("2", 1.0), ("0.2", -0.5)])
def test_the_exact_solver_converges_to_the_closed_form_limit_cycle(F, x0):
    """300 cycles leave (1 - b)^(4*300) ~ 1e-55 of the start's distance from the limit cycle: what remains
    is rounding, a few units in the last place of a period summed from a few thousand events."""
    period, v_star = limit_cycle(F)
    run = solve_exact(Parameters(M=1, K=1, F=float(F), b=0.1, a1=-0.1, a2=0.05), x0, n_cycles=300,
                      record_trajectory=False)
    assert float(run.cycles.period[-1]) == pytest.approx(float(period), rel=1e-12)
    assert float(run.cycles.velocity_before_impact[-1]) == pytest.approx(float(v_star), rel=1e-13)
