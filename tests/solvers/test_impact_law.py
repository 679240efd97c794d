"""The impact law is written once (:func:`escapement.model.automaton.impact_factor`, ``v+ = r v-``): patch it, and
every solver path must follow the patched law, checked against numbers derived here from the law alone.

The patched law is ``r = 1 - 1.2 b`` (0.88 for ``b = 0.1``; the paper's is 0.9). In the symmetric geometry, with
``f = F/M`` and ``beta = r**2``, energy along a half cycle gives for the velocity ``V`` before an impact and ``V'``
before the next: the impact multiplies ``V**2`` by ``beta``, the zone it opens adds ``2 f (a2 - a1)``, and the
spring's work from one impact position to the other is ``w**2 (a1**2 - a3**2) = 0``. So per cycle
``v_{k+1}**2 = beta**2 v_k**2 + 2 f (a2 - a1) (1 + beta)``, of fixed point ``v***2 = 2 f (a2 - a1) / (1 - beta)``
(the paper's ``2 f (a2 - a1) / (b (2 - b))``). From rest at ``x0 > a3`` the first impact is at a3 with
``V**2 = w**2 (x0**2 - a3**2)``, so the first at a1 comes with ``v_1**2 = beta w**2 (x0**2 - a1**2) + 2 f (a2 - a1)``.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from escapement.model import automaton
from escapement.model.parameters import Parameters
from escapement.model.status import Status
from escapement.solvers import closed_form
from escapement.solvers.cycles import CLOSED_FORM, iter_closed_form_cycles, solve_cycles
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision
from escapement.integrators.naive import solve_naive
from escapement.integrators.reference import solve_reference
from escapement.solvers.stream import iter_cycles

#: the paper's case (a), symmetric, released at rest at x0 = +1 m (the configuration's mirror; w = 1 rad/s)
PAPER = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
X0 = 1.0
FACTOR = 1.2  # the patched law's r = 1 - 1.2 b


def patched_factor(b):
    """r = 1 - 1.2 b: v+ = (1 - 1.2 b) v- at an impact (floats, arrays, mpmath numbers)."""
    return 1.0 - FACTOR * b


def expected_velocities(p: Parameters, r: float, x0: float, n: int) -> np.ndarray:
    """The velocities before the impacts at a1 of cycles 1 .. n for ``v+ = r v-`` (the module's docstring)."""
    beta, zone = r * r, 2.0 * p.f * (p.a2 - p.a1)
    v_sq = [beta * p.omega2 * (x0 * x0 - p.a1 * p.a1) + zone]
    for _ in range(n - 1):
        v_sq.append(beta * beta * v_sq[-1] + zone * (1.0 + beta))
    return np.sqrt(v_sq)


def expected_amplitudes(p: Parameters, r: float, v: np.ndarray) -> np.ndarray:
    """The top of each cycle's free swing from a2, ``sqrt(a2**2 + v2**2 / w**2)``, energy through the zone (a1, a2)
    about ``c = F/K`` giving ``v2**2 = (r v)**2 + w**2 ((a1 - c)**2 - (a2 - c)**2)``."""
    c = p.zone_offset
    v2_sq = (r * v) ** 2 + p.omega2 * ((p.a1 - c) ** 2 - (p.a2 - c) ** 2)
    return np.sqrt(p.a2**2 + v2_sq / p.omega2)


def fixed_point(p: Parameters, r: float) -> float:
    """``v* = sqrt(2 f (a2 - a1) / (1 - r**2))``."""
    return math.sqrt(2.0 * p.f * (p.a2 - p.a1) / (1.0 - r * r))


def test_the_derivation_holds_for_the_papers_law():
    """The expectation checked against the unpatched solver, and the patched law far from the paper's."""
    r = 1.0 - PAPER.b
    v = solve_exact(PAPER, X0, n_cycles=400, record_trajectory=False).cycles.velocity_before_impact
    assert v == pytest.approx(expected_velocities(PAPER, r, X0, 400), rel=1e-14)
    assert v[-1] == pytest.approx(fixed_point(PAPER, r), rel=1e-14)
    assert fixed_point(PAPER, r) ** 2 == pytest.approx(2 * PAPER.f * 0.15 / (PAPER.b * (2 - PAPER.b)), rel=1e-15)
    patched = expected_velocities(PAPER, 1.0 - FACTOR * PAPER.b, X0, 400)
    assert np.min(np.abs(patched - v) / v) > 0.01  # above every path's tolerance (5e-3 at most)


def _floats(values) -> np.ndarray:
    return np.array([float(v) for v in values])


#: every path to the velocities before the impacts at a1, the event log where the path keeps one, and the
#: relative tolerance of the path's arithmetic
N = 60
PATHS = {
    "solve_exact": lambda: solve_exact(PAPER, X0, n_cycles=N),
    "solve_exact without trajectory": lambda: solve_exact(PAPER, X0, n_cycles=N, record_trajectory=False),
    "iter_cycles": lambda: iter_cycles(PAPER, X0, n_cycles=N, chunk=7),
    "solve_ensemble": lambda: solve_ensemble(PAPER.M, PAPER.K, PAPER.F, [PAPER.b, PAPER.b], PAPER.a1, PAPER.a2,
                                             x0=[X0, X0], n_cycles=N),
    "solve_cycles": lambda: solve_cycles(PAPER, X0, n_cycles=N),
    "iter_closed_form_cycles": lambda: iter_closed_form_cycles(PAPER, X0, n_cycles=N, chunk=7),
    "solve_reference": lambda: solve_reference(PAPER, X0, n_cycles=N, rtol=1e-12, record_trajectory=False),
    "solve_high_precision": lambda: solve_high_precision(PAPER, X0, n_cycles=N, dps=30),
    "solve_naive": lambda: solve_naive(PAPER, X0, n_cycles=N, step=1e-3),
}
TOLERANCE = {"solve_reference": 1e-9, "solve_high_precision": 1e-15,
             # RK4 with events applied up to a step late, at a state up to |v| h past the surface: each event
             # moves v by up to w**2 |x| h <= 1e-3 (|x| <= 1 m, w = 1, h = 1e-3); a few events' worth at most
             "solve_naive": 5e-3}


def _velocities_and_events(name: str):
    """The velocities before the impacts at a1 and the amplitudes (an ensemble's first row), the events, the result."""
    result = PATHS[name]()
    tables = list(result) if name.startswith("iter") else [result.cycles]
    if name == "solve_ensemble":
        assert np.array_equal(*result.cycles.velocity_before_impact)
    v, amplitude = (_floats(np.concatenate([np.atleast_2d(getattr(t, column))[0] for t in tables]))
                    for column in ("velocity_before_impact", "largest_displacement"))
    return v, amplitude, getattr(result, "events", None), result


@pytest.mark.parametrize("name", list(PATHS))
def test_every_path_follows_a_patched_impact_law(monkeypatch, name):
    """The velocities before the impacts at a1 follow the patched law's map to its fixed point; in an event log each
    impact's jump is the patched ratio (none at the zones' ends); the closed forms take the multiplier from the law too
    (their cycles, not the event solver's fallback)."""
    rel = TOLERANCE.get(name, 1e-14)
    r = 1.0 - FACTOR * PAPER.b
    monkeypatch.setattr(automaton, "impact_factor", patched_factor)
    v, amplitude, events, result = _velocities_and_events(name)
    assert len(v) == N
    expected = expected_velocities(PAPER, r, X0, N)
    assert v == pytest.approx(expected, rel=rel)
    assert amplitude == pytest.approx(expected_amplitudes(PAPER, r, expected), rel=rel)
    assert v[-1] == pytest.approx(fixed_point(PAPER, r), rel=max(rel, 1e-12))  # (0.88**4)**59 ~ 1e-13
    if events is not None:
        impact = np.isin(events.kind, [1, 3])
        ratio = _floats([a / b for a, b in zip(events.v_after, events.v_before)])
        assert impact.sum() >= 2 * N
        assert ratio[impact] == pytest.approx(r, rel=1e-15 if name != "solve_high_precision" else 1e-28)
        assert np.all(ratio[~impact] == 1.0)
    if name in ("solve_cycles", "iter_closed_form_cycles"):
        assert result.method == CLOSED_FORM  # not the event solver's fallback


@pytest.mark.parametrize("streamed", [False, True])
def test_the_closed_forms_fallback_follows_a_patched_impact_law(monkeypatch, streamed):
    """Where the closed form gives way (a grazing margin that takes every arc) the event solver's run follows it."""
    monkeypatch.setattr(automaton, "impact_factor", patched_factor)
    monkeypatch.setattr(closed_form, "GRAZING_SPEED_SQ", 1.0)
    if streamed:
        chunks = iter_closed_form_cycles(PAPER, X0, n_cycles=N, chunk=7)
        v, fallback = np.concatenate([c.velocity_before_impact for c in chunks]), chunks.fallback
    else:
        run = solve_cycles(PAPER, X0, n_cycles=N)
        v, fallback = run.cycles.velocity_before_impact, run.fallback
    assert "grazes" in fallback
    assert v == pytest.approx(expected_velocities(PAPER, 1.0 - FACTOR * PAPER.b, X0, N), rel=1e-14)


def test_the_zeno_time_follows_a_patched_reversing_law(monkeypatch):
    """v+ = (1 - 1.2 b) v-: for b = 1.5 each rebound keeps 0.8 of the speed (the paper's law keeps 0.5); the
    flights back to a3 = 0.1 m (w = 1) last 2 atan(0.8**n v / (w a3)), summed in 30 digits."""
    monkeypatch.setattr(automaton, "impact_factor", patched_factor)
    p = Parameters(M=1.0, K=1.0, F=1.0, b=1.5, a1=-0.1, a2=0.05)
    s = solve_exact(p, 1.0, n_cycles=3)
    assert s.status == Status.CHATTERING
    assert s.events.v_after[-1] == pytest.approx(-0.8 * s.events.v_before[-1], rel=1e-15)
    speed, distance = abs(s.events.v_after[-1]), 0.1
    with mpmath.workdps(30):
        rest = 2 * mpmath.nsum(lambda n: mpmath.atan(speed / distance * mpmath.mpf(0.8) ** n), [0, mpmath.inf])
    assert s.exit.t_accumulation == pytest.approx(s.events.t[-1] + float(rest), rel=1e-12)
    ens = solve_ensemble(p.M, p.K, p.F, p.b, p.a1, p.a2, x0=1.0, n_cycles=3)
    assert ens.outcome(0) == Status.CHATTERING
    assert ens.exit_t_accumulation[0] == pytest.approx(s.exit.t_accumulation, rel=1e-14)
