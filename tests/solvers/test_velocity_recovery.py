"""Where the limit cycle regains its speed before the impact at a1: the corrected closed form
(:func:`escapement.paper.corrected.velocity_recovery`, a root of a quadratic in x) against the exact solver's
own motion after that impact (its harmonic arcs, sampled), a different method for the same instant."""

from __future__ import annotations

import numpy as np
import pytest

from escapement.model.parameters import Parameters
from escapement.paper.corrected import velocity_recovery
from escapement.solvers.exact import solve_exact


@pytest.mark.parametrize("K, F", [(0.1, 0.5), (1.0, 0.5), (10.0, 0.5), (1.0, 1.0)])
def test_the_solver_regains_the_speed_before_the_impact_where_the_closed_form_says(K, F):
    p = Parameters(M=1.0, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)
    s = solve_exact(p, -1.0, n_cycles=300)  # converged to the limit cycle well within 300 cycles
    t_impact, v1 = s.cycles.impact_time[-2], s.cycles.velocity_before_impact[-2]
    x, dt = velocity_recovery(v1, p)
    assert p.a1 < x <= p.a2 and dt > 0  # inside the zone, after the impact
    (x_at, x_before), (v_at, v_before), _ = s.sample(np.array([t_impact + dt, t_impact + 0.999 * dt]))
    assert x_at == pytest.approx(x, abs=1e-10)
    assert v_at == pytest.approx(v1, abs=1e-10)
    assert v_before < v1  # not regained earlier: after the impact, (1 - b) v1 rises to v1 only there
