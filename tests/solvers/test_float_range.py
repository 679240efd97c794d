"""Every input answered: refused before any work (the bounds of :mod:`escapement.model.parameters`: every non-zero
dimensional input of magnitude in [1e-50, 1e50], SI units), or run to a typed outcome; a completed run holds only
finite numbers, or the run raises."""

from __future__ import annotations

import itertools
import math
from unittest import mock

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st

import escapement.solvers.ensemble as ensemble_module
import escapement.solvers.exact as exact_module
from escapement.model.events import EventKind
from escapement.model.limits import RunLimits, RunSpec
from escapement.model.parameters import ParameterError, Parameters
from escapement.model.quantities import INITIAL_STATE, MODEL_KEYS
from escapement.model.status import Status
from escapement.integrators.driver import NO_EVENT, Step, drive
from escapement.solvers.ensemble import solve_ensemble
from escapement.solvers.exact import solve_exact
from escapement.integrators.high_precision import solve_high_precision

PAPER = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
SPEC = RunSpec(PAPER, 1.0, 0.0, RunLimits(n_cycles=1))
CYCLE_COLUMNS = ("impact_time", "velocity_before_impact", "period", "largest_displacement")
EVENT_COLUMNS = ("t", "x", "v_before", "v_after")


def _all_finite(run) -> bool:
    columns = [getattr(run.events, n) for n in EVENT_COLUMNS] + [getattr(run.cycles, n) for n in CYCLE_COLUMNS]
    return all(np.isfinite(np.asarray(c, dtype=float)).all() for c in columns) and math.isfinite(run.t_final)


SPECIAL = [0.0, 5e-324, 1e-310, 2.2250738585072014e-308, 1e-51, 1e51, 1e308, 1.7976931348623157e308]


def _magnitudes(wide: bool):
    """Magnitudes from 1e-300 to 1e300 and the float64 extremes, or near the accepted range (mostly inside)."""
    exponent = st.integers(-300, 300) if wide else st.integers(-51, 50)
    spread = st.builds(lambda m, e: m * 10.0**e, st.floats(1.0, 9.99), exponent)
    return st.one_of(spread, st.sampled_from(SPECIAL)) if wide else spread


@st.composite
def _cases(draw):
    """Parameters and a state drawn wide or near the range, the geometry of independent magnitudes or of one scale."""
    wide = draw(st.booleans())
    magnitude = _magnitudes(wide)
    sign = st.sampled_from([1.0, -1.0])
    values = {"M": draw(magnitude), "K": draw(magnitude), "F": draw(st.one_of(st.just(0.0), magnitude)),
              "b": draw(st.one_of(st.floats(0.01, 1.99), magnitude) if wide else st.floats(0.01, 1.99))}
    if draw(st.booleans()):
        lengths = [draw(magnitude) for _ in range(4)]
    else:
        scale = draw(magnitude)
        lengths = [scale * draw(st.floats(0.1, 10.0)) for _ in range(4)]
    values.update(a1=-lengths[0], a2=-lengths[0] + lengths[1], a3=lengths[2], a4=lengths[2] - lengths[3])
    state = st.one_of(magnitude, _magnitudes(True))  # now and then out of range when the parameters are not
    x0 = draw(sign) * draw(state)
    v0 = draw(sign) * draw(st.one_of(st.just(0.0), state))
    return values, x0, v0


@settings(max_examples=100, deadline=None)
@given(_cases())
def test_every_input_is_refused_before_any_work_or_run_to_finite_numbers(case):
    values, x0, v0 = case
    # the ensemble: refused before its first closed form, or run
    with mock.patch.object(ensemble_module, "crossing", wraps=ensemble_module.crossing) as closed_form:
        try:  # one-element lists, so that the refusals name the row
            ens = solve_ensemble(**{k: [v] for k, v in {**values, "x0": x0, "v0": v0}.items()}, n_cycles=3)
            ens_error = None
        except ParameterError as err:
            assert not closed_form.called
            assert err.name in (*MODEL_KEYS, *INITIAL_STATE) and err.row == 0
            ens_error = (err.name, err.requirement)
    # the scalar solver: refused by Parameters or before its loop, or run
    try:
        params = Parameters(**values)
    except ParameterError as err:
        assert err.name in MODEL_KEYS and err.row is None
        assert ens_error == (err.name, err.requirement)  # one validation for both
        event(f"refused: {err.name}")
        return
    with mock.patch.object(exact_module, "EventRun", wraps=exact_module.EventRun) as loop:
        try:
            run = solve_exact(params, x0, v0, n_cycles=3)
        except ParameterError as err:
            assert not loop.called and err.name in INITIAL_STATE
            assert ens_error == (err.name, err.requirement)
            event(f"refused: {err.name}")
            return
    assert ens_error is None
    assert isinstance(run.status, Status)
    event(f"run: {run.status.value}")
    if run.status is Status.COMPLETED:
        assert _all_finite(run), run.message
    assert ens.outcome(0) == run.status
    if ens.success[0]:
        for name in CYCLE_COLUMNS:
            assert np.isfinite(getattr(ens.cycles, name)[0]).all(), name
    hp = solve_high_precision(params, x0, v0, n_cycles=2, dps=20)
    assert isinstance(hp.status, Status)
    if hp.status is Status.COMPLETED:
        assert _all_finite(hp), hp.message


def test_at_the_corners_of_the_range_the_runs_complete_with_finite_numbers_and_the_ensemble_agrees():
    """M, K in {1e-50, 1e50}, F in {0, 1e-50, 1e50}, positions near 1e-50 or 1e50, released beyond the impacts or
    inside them at the largest speed: omega, F/K and v0/omega span 1e-100 .. 1e100."""
    rows = []
    for M, K, F, s in itertools.product((1e-50, 1e50), (1e-50, 1e50), (0.0, 1e-50, 1e50), (1e-50, 2.5e49)):
        rows.append(dict(M=M, K=K, F=F, b=0.1, a1=-2 * s, a2=s, x0=4 * s, v0=0.0))
        rows.append(dict(M=M, K=K, F=F, b=0.1, a1=-2 * s, a2=s, x0=-s, v0=1e50))
        rows.append(dict(M=M, K=K, F=F, b=0.1, a1=-2 * s, a2=s, x0=4 * s, v0=-1e-50))
    ens = solve_ensemble(**{k: [r[k] for r in rows] for k in rows[0]}, n_cycles=4)
    for i, row in enumerate(rows):
        run = solve_exact(Parameters(**{k: v for k, v in row.items() if k not in INITIAL_STATE}), row["x0"], row["v0"],
                          n_cycles=4)
        # the first free swing, of radius hypot(x0, v0/omega), misses a1 and a3 = 2 s only when released
        # inside them with too little speed (omega = 1e50 and v0 = 1e50: v0/omega = 1 m against s = 2.5e49 m)
        swing = math.hypot(row["x0"], row["v0"] / math.sqrt(row["K"] / row["M"]))
        assert run.status is (Status.STOPPED if swing < -row["a1"] else Status.COMPLETED), row
        assert ens.outcome(i) is run.status
        if run.status is Status.COMPLETED:
            assert _all_finite(run), row
            for name in CYCLE_COLUMNS:
                assert getattr(ens.cycles, name)[i] == pytest.approx(getattr(run.cycles, name), rel=1e-12), (name, row)
    assert ens.success.sum() == len(rows) - 3


class _Scripted:
    """A stepper that answers from a script (standing for an integrator whose arithmetic overflowed)."""

    name = "scripted"

    def __init__(self, script):
        self.script = list(script)

    def next_event(self, mode, centre, t, x, v, watched, t_stop):
        return self.script.pop(0)

    def trajectory(self, t_final):
        return None


A1, A2, A3, A4 = EventKind.IMPACT_A1, EventKind.ZONE_END_A2, EventKind.IMPACT_A3, EventKind.ZONE_END_A4
CYCLE = [Step(A2, 0.5, 1.0, 0.05), Step(A3, 1.0, -1.0, 0.1), Step(A4, 0.5, -1.0, 0.1), Step(A1, 1.0, 1.0, -0.1)]


@pytest.mark.parametrize("bad, where", [(CYCLE[1], None), (Step(A3, 1.0, -math.inf, 0.1), "events.v_before"),
                                        (Step(A3, math.inf, -1.0, 0.1), "events.t"),
                                        (Step(A3, 1.0, -1.0, math.inf), "cycles.largest_displacement")])
def test_a_completed_run_with_a_non_finite_number_raises_and_a_stopped_run_may_end_at_infinity(bad, where):
    script = [Step(A1, 1.0, 1.0, -0.1), CYCLE[0], bad, *CYCLE[2:]]
    if where is None:  # the finite script completes
        sol = drive(SPEC, _Scripted(script))
        assert sol.status is Status.COMPLETED and _all_finite(sol)
        stopped = drive(SPEC, _Scripted([Step(NO_EVENT, math.inf, 0.0, 0.08)]))
        assert stopped.status is Status.STOPPED and stopped.t_final == math.inf
        return
    with pytest.raises(FloatingPointError, match=f"^scripted: a completed run holds a non-finite {where}"):
        drive(SPEC, _Scripted(script))
