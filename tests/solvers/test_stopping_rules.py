"""The solvers' stopping rules, each at its exact boundary and one ulp or one event either side: an event, or a turn
back inside a zone, on the end time ``t_end``; ``n_cycles``; ``max_events``; in :func:`solve_exact`, in the stream
of its cycles (whose blocks resume the loop) and in the ensemble; and the largest counts a run may ask for.

The times are closed forms written here: from rest at ``x0`` the free arc ``x(t) = x0 cos(w t)`` reaches ``a1``
at ``arccos(a1 / x0) / w``, and in the zone after the impact at a1 the arc about ``F / K`` turns where its velocity
vanishes. The counts are the automaton's cycle (a1, a2, a3, a4): ``n`` cycles from the left are ``4 n + 1`` events.
"""

from __future__ import annotations

import numpy as np
import pytest

from escapement import EventKind, Parameters, ParameterError, Status, iter_cycles, solve_ensemble, solve_exact
from escapement.model.limits import MAX_CYCLES, MAX_EVENTS, MemoryBudgetError
from escapement.solvers.kernel import BLOCK_EVENTS as PASS_EVENTS

#: Fig. 3 (a) as the configuration runs it (w = 1 rad/s), released from rest at x0 = -1 m
FIG3A = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
X0 = -1.0
#: a weak force and a long zone: from rest at -0.3 m the mass turns back inside (a1, a2) after the first impact
WEAK = Parameters(M=1.0, K=1.0, F=0.01, b=0.1, a1=-0.1, a2=0.5)
X0_WEAK = -0.3


def first_impact_time(x0: float, a1: float) -> float:
    """From rest at ``x0 < a1 < 0`` (w = 1, free arc about 0): ``x0 cos t = a1``."""
    return float(np.arccos(a1 / x0))


def turn_back_time(x0: float, p: Parameters) -> float:
    """The first impact at a1 (:func:`first_impact_time`), then the arc about ``c = F / K`` from ``a1 - c`` at the
    velocity ``(1 - b) v``, ``v = sqrt(x0**2 - a1**2)`` (energy), turns after the angle ``atan2((1 - b) v, a1 - c)``
    (w = 1)."""
    v_after = (1.0 - p.b) * np.sqrt(x0**2 - p.a1**2)
    return first_impact_time(x0, p.a1) + float(np.arctan2(v_after, p.a1 - p.F / p.K))


def below(t: float) -> float:
    return float(np.nextafter(t, -np.inf))


def above(t: float) -> float:
    return float(np.nextafter(t, np.inf))


def events_of(n_cycles: int) -> int:
    """From the left (the first event the impact at a1), ``n`` cycles end at the ``(n + 1)``-th impact at a1."""
    return 4 * n_cycles + 1


def test_the_closed_forms_are_the_solver_s_doubles():
    """The boundaries below are exact only if the solver's numbers are the closed forms' to the last bit."""
    t1 = first_impact_time(X0, FIG3A.a1)
    assert solve_exact(FIG3A, X0, t_end=2.0).events.t[0] == t1
    weak = solve_exact(WEAK, X0_WEAK, n_cycles=3)
    assert weak.status is Status.TURNED_BACK_IN_ZONE and weak.t_final == turn_back_time(X0_WEAK, WEAK)


# -- t_end -------------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("side, events", [(below, 0), (lambda t: t, 1), (above, 1)])
def test_an_event_exactly_at_the_end_time_belongs_to_the_run(side, events):
    t_end = side(first_impact_time(X0, FIG3A.a1))
    run = solve_exact(FIG3A, X0, t_end=t_end)
    impacts = f"{events} impact{'' if events == 1 else 's'} at a1"
    assert len(run.events) == events and run.status is Status.COMPLETED and run.t_final == t_end
    assert run.message.endswith(impacts) and run.trajectory.t_final == t_end
    if events:
        assert run.events.kind[0] == EventKind.IMPACT_A1 and run.events.t[0] <= t_end
    stream = iter_cycles(FIG3A, X0, t_end=t_end)
    assert list(stream) == [] and stream.summary.n_events == events and stream.summary.t_final == t_end


@pytest.mark.parametrize("side, status", [(below, Status.COMPLETED), (lambda t: t, Status.TURNED_BACK_IN_ZONE),
                                          (above, Status.TURNED_BACK_IN_ZONE)])
def test_a_turn_back_in_a_zone_exactly_at_the_end_time_is_that_exit(side, status):
    turn = turn_back_time(X0_WEAK, WEAK)
    t_end = side(turn)
    run = solve_exact(WEAK, X0_WEAK, t_end=t_end)
    assert run.status is status and len(run.events) == 1
    assert run.t_final == (t_end if status is Status.COMPLETED else turn)
    stream = iter_cycles(WEAK, X0_WEAK, t_end=t_end)
    list(stream)
    assert stream.summary.status is status and stream.summary.t_final == run.t_final


# -- n_cycles ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", [1, 2, 7])
def test_n_cycles_end_at_the_impact_at_a1_that_ends_the_last(n):
    run = solve_exact(FIG3A, X0, n_cycles=n)
    at_a1 = np.flatnonzero(run.events.kind == EventKind.IMPACT_A1)
    assert run.status is Status.COMPLETED and len(run.cycles) == n
    assert len(run.events) == events_of(n) and len(at_a1) == n + 1 and at_a1[-1] == len(run.events) - 1
    assert run.t_final == run.events.t[-1] == run.cycles.impact_time[-1] + run.cycles.period[-1]
    # released on the other side, the impact at a3 and the end of the zone at a4 come first: two events more
    assert len(solve_exact(FIG3A, -X0, n_cycles=n).events) == events_of(n) + 2


# -- max_events --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("spare, status, cycles", [(-1, Status.EVENT_LIMIT, 2), (0, Status.COMPLETED, 3),
                                                   (1, Status.COMPLETED, 3)])
def test_the_event_that_ends_the_last_cycle_completes_the_run_even_as_the_last_allowed(spare, status, cycles):
    max_events = events_of(3) + spare
    run = solve_exact(FIG3A, X0, n_cycles=3, max_events=max_events)
    assert run.status is status and len(run.cycles) == cycles
    assert len(run.events) == min(max_events, events_of(3)) and run.t_final == run.events.t[-1]
    if status is Status.EVENT_LIMIT:
        assert run.message.startswith(f"ended after max_events = {max_events} events at t = ")
    stream = iter_cycles(FIG3A, X0, n_cycles=3, max_events=max_events)
    assert sum(len(chunk) for chunk in stream) == cycles
    assert (stream.summary.status, stream.summary.n_events) == (status, len(run.events))
    ensemble = solve_ensemble(**FIG3A.as_dict(), x0=[X0, X0], n_cycles=3, max_events=max_events)
    assert [ensemble.outcome(i) for i in range(2)] == [status, status]
    assert np.isfinite(ensemble.cycles.period).sum(axis=1).tolist() == [cycles, cycles]


@pytest.mark.parametrize("max_events, status, events", [(1, Status.EVENT_LIMIT, 1), (2, Status.COMPLETED, 1)])
def test_the_last_allowed_event_ends_a_run_to_t_end_before_the_end_time_is_looked_for(max_events, status, events):
    """The end time an ulp after the first impact comes before the second event: with one event allowed the run
    ends at that impact by the bound, with two by the end time."""
    t_end = above(first_impact_time(X0, FIG3A.a1))
    run = solve_exact(FIG3A, X0, t_end=t_end, max_events=max_events)
    assert run.status is status and len(run.events) == events
    assert run.t_final == (run.events.t[0] if status is Status.EVENT_LIMIT else t_end)


@pytest.mark.parametrize("max_events", [PASS_EVENTS - 1, PASS_EVENTS, PASS_EVENTS + 1, 2 * PASS_EVENTS + 1])
def test_the_event_bound_across_the_stream_s_passes(max_events):
    stream = iter_cycles(FIG3A, X0, n_cycles=10 * PASS_EVENTS, max_events=max_events)
    cycles = sum(len(chunk) for chunk in stream)
    assert stream.summary.status is Status.EVENT_LIMIT and stream.summary.n_events == max_events
    assert cycles == (max_events - 1) // 4  # the (k + 1)-th impact at a1, event 4 k + 1, ends cycle k
    run = solve_exact(FIG3A, X0, n_cycles=10 * PASS_EVENTS, max_events=max_events, record_trajectory=False)
    assert (run.status, len(run.events), len(run.cycles)) == (Status.EVENT_LIMIT, max_events, cycles)


# -- the largest counts ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name, largest, limits", [("n_cycles", MAX_CYCLES, {}),
                                                   ("max_events", MAX_EVENTS, dict(t_end=1.0))])
def test_the_largest_count_is_refused_by_the_memory_budget_alone_and_one_more_by_its_name(name, largest, limits):
    with pytest.raises(MemoryBudgetError):
        solve_exact(FIG3A, X0, **limits, **{name: largest})
    with pytest.raises(ParameterError) as refused:
        solve_exact(FIG3A, X0, **limits, **{name: largest + 1})
    assert not isinstance(refused.value, MemoryBudgetError)
    assert (refused.value.name, refused.value.value) == (name, largest + 1)
