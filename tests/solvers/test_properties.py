"""Properties over random valid parameters (hypothesis; derandomised in CI)."""

import numpy as np
from hypothesis import assume, given, settings
from strategies import initial_displacement, initial_velocity, parameters

from escapement.model.events import EventKind
from escapement.solvers.exact import solve_exact

CYCLE = [int(k) for k in (EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4)]


@settings(max_examples=100)
@given(p=parameters(), x0=initial_displacement, v0=initial_velocity)
def test_event_order_is_impact_then_zone_end_then_the_other_impact(p, x0, v0):
    kinds = list(solve_exact(p, x0, v0, n_cycles=5).events.kind)
    if kinds:
        start = CYCLE.index(kinds[0])
        assert kinds[0] in (CYCLE[0], CYCLE[2])  # the first event is an impact
        assert kinds == [CYCLE[(start + i) % 4] for i in range(len(kinds))]


@settings(max_examples=100)
@given(p=parameters(), x0=initial_displacement, v0=initial_velocity)
def test_energy_balance_per_half_cycle(p, x0, v0):
    ev = solve_exact(p, x0, v0, n_cycles=5).events
    impacts = np.flatnonzero((ev.kind == 1) | (ev.kind == 3))
    assume(len(impacts) >= 2)
    energy = 0.5 * p.M * ev.v_before**2 + 0.5 * p.K * ev.x**2
    scale = np.max(np.abs(energy[impacts]))
    for i, j in zip(impacts[:-1], impacts[1:]):
        loss = 0.5 * p.M * (ev.v_before[i] ** 2 - ev.v_after[i] ** 2)
        work = p.F * ((p.a2 - p.a1) if ev.kind[i] == 1 else (p.a3 - p.a4))
        assert abs(energy[j] - (energy[i] - loss + work)) <= 1e-12 * max(scale, abs(work))
