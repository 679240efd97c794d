"""What a notebook sees of a run: a short repr, its cycles and events as tables (``to_dataframe``), its samples
(the run as a CF dataset: tests/io); and every number a message or a summary prints true as printed: an input
reads back as itself, a computed value compares with its bounds and its neighbours as it does, no zero has a sign."""

from __future__ import annotations

import dataclasses
import math
import re
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from escapement import EventKind, Parameters, solve_ensemble, solve_exact, solve_high_precision, solve_reference
from escapement.model.printing import compared, exact, texts
from escapement.solvers.describe import ArcTable
from escapement.solvers.outcomes import stopped_message, turned_back_message


def test_the_repr_of_a_50_cycle_run_is_a_short_summary(run50):
    text = repr(run50)
    assert len(text) < 1000 and len(text.splitlines()) <= 12 and "array(" not in text
    assert text.splitlines()[0] == "<escapement.Solution> completed (exact)" and "completed 50 cycles" in text
    assert f"events:     {len(run50.events)} " in text and "cycles:     50;" in text
    params = next(line for line in text.splitlines() if line.startswith("parameters:"))
    assert params == ("parameters: M = 1 kg, K = 1 N/m, F = 1 N, b = 0.1, a1 = -0.1 m, a2 = 0.05 m, a3 = 0.1 m, "
                      "a4 = -0.05 m")
    assert "initial:    x0 = 1 m, v0 = 0 m/s" in text and str(run50) == text
    short, long = (repr(solve_exact(run50.params, 1.0, n_cycles=n, record_trajectory=False)) for n in (5, 5000))
    # the repr does not grow with the run: only the counts' digits differ
    assert len(long.splitlines()) == len(short.splitlines()) and abs(len(long) - len(short)) < 20
    cycles, (lo, hi) = repr(run50.cycles), (run50.cycles.period.min(), run50.cycles.period.max())
    assert cycles.splitlines()[0] == "<CycleTable> 50 cycles" and len(cycles) < 400
    assert f"period                  {lo:.6g} .. {hi:.6g} s" in cycles
    arcs = repr(run50.trajectory)
    assert arcs.startswith(f"<ArcTable> {len(run50.trajectory.t_start)} harmonic arcs") and len(arcs) < 200


def test_the_repr_of_a_regime_exit_names_it_and_its_numbers(stopped):
    text = repr(stopped)
    assert text.splitlines()[0] == "<escapement.Solution> stopped (exact)" and "t = 0 .. inf s" in text
    assert "exit:       turning_point = 0.01 m, margin = 0.09 m" in text
    assert "a1 = -0.1 m (moving right)" in text  # the message, wrapped but whole
    assert max(len(line) for line in text.splitlines()) <= 120
    assert stopped.to_dataframe("cycles").empty and stopped.to_dataframe("events").empty


def test_a_high_precision_run_prints_its_numbers_and_gives_its_tables_as_doubles():
    hp = solve_high_precision(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), 1.0, n_cycles=2, dps=20)
    text = repr(hp)
    assert text.splitlines()[0] == "<escapement.Solution> completed (mpmath 20 digits)"
    assert f"period {float(hp.cycles.period[-1]):.6g} s" in text and "trajectory: not kept" in text
    df = hp.to_dataframe("cycles")
    assert df["largest_displacement"].dtype == np.float64
    assert df["largest_displacement"].tolist() == [float(x) for x in hp.cycles.largest_displacement]
    assert hp.to_dataframe("events")["event_time"].tolist() == [float(x) for x in hp.events.t]


def test_the_repr_of_an_ensemble_counts_the_outcomes_in_a_few_lines():
    x0 = np.where(np.arange(1000) % 4 == 0, 0.01, 1.0)  # a quarter released inside the free swing: they stop
    runs = solve_ensemble(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05, x0=x0, n_cycles=20)
    text = repr(runs)
    assert len(text) < 1000
    expected = "<escapement.EnsembleSolution> 1000 trajectories, 20 cycles (exact, vectorised ensemble)"
    assert text.splitlines()[0] == expected
    assert "outcomes:                completed 750, stopped 250" in text
    assert "exit_turning_point:      0.01 m" in text
    assert "array(" not in text


def test_importing_the_solvers_imports_neither_io_nor_xarray_nor_pandas():
    """to_dataframe imports pandas on use, and the solvers never import io: they stay below it."""
    code = ("import sys, escapement.solvers\n"
            "print(sorted({'escapement.io', 'escapement.io.dataset', 'xarray', 'pandas'} & set(sys.modules)))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def test_the_cycles_dataframe_copies_the_cycle_table_its_columns_the_tables_fields(run50):
    df = run50.to_dataframe("cycles")
    assert isinstance(df, pd.DataFrame) and run50.to_dataframe().equals(df)  # cycles by default
    assert list(df.columns) == [f.name for f in dataclasses.fields(run50.cycles)]
    assert df.index.name == "cycle" and df.index.tolist() == list(range(1, 51))
    for name in df.columns:
        np.testing.assert_array_equal(df[name].to_numpy(), getattr(run50.cycles, name))
    # times in seconds, the velocity in metres per second, the largest displacement in metres
    assert df.attrs["units"] == {"impact_time": "s", "velocity_before_impact": "m s-1", "period": "s",
                                 "largest_displacement": "m"}
    assert df.attrs["long_names"]["period"] == "time from impact k to impact k+1 at a1"


def test_the_events_dataframe_copies_the_event_log(run50):
    df = run50.to_dataframe("events")
    ev = run50.events
    assert len(df) == len(ev) and df.index.name == "event" and df.index[0] == 0
    for column, field in (("event_time", "t"), ("event_velocity_after", "v_after"), ("event_position", "x")):
        np.testing.assert_array_equal(df[column].to_numpy(), getattr(ev, field))
    impacts = df[df["event_kind"] == EventKind.IMPACT_A1]
    assert impacts.index.tolist() == ev.of_kind(EventKind.IMPACT_A1).tolist()
    assert (impacts["event_position"] == -0.1).all()  # every impact at a1 is at a1
    assert df.attrs["units"] == {"event_time": "s", "event_position": "m", "event_velocity_before": "m s-1",
                                 "event_velocity_after": "m s-1"}  # the kind is a code, without units
    assert df.attrs["long_names"]["event_velocity_after"] == "velocity just after the event"


@pytest.mark.parametrize(("t", "shape"), [(1.0, ()), (1, ()), (np.float32(1.0), ()), ([1.0], (1,)), ([0, 1], (2,)),
                                          (np.arange(3) / 2, (3,)), ([], (0,)), (np.ma.array([1.0], mask=False), (1,))])
def test_sample_takes_real_times_of_every_plain_kind(run50, t, shape):
    """Before the first impact (at 1.47 s) the release from 1 m at rest swings as x = cos t, v = -sin t (K = M = 1)."""
    x, v, a = run50.sample(t)
    assert x.shape == v.shape == a.shape == shape
    times = np.asarray(t, dtype=float)
    np.testing.assert_allclose(x, np.cos(times), rtol=1e-14)
    np.testing.assert_allclose(v, -np.sin(times), rtol=1e-14, atol=1e-15)


#: a number printed with a minus sign and nothing but zeros: -0, -0.0, -0.000
NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0(?:\.0*)?(?![\w.])")
finite = st.floats(allow_nan=False, allow_infinity=False)


def order(x: float, y: float) -> int:
    return (x > y) - (x < y)


@given(finite)
def test_an_input_prints_as_text_that_reads_back_as_itself(x):
    text = exact(x)
    assert float(text) == x and not NEGATIVE_ZERO.search(text)


@pytest.mark.parametrize("value, text", [
    (1.999999, "1.999999"), (2 - 4.4e-16, "1.9999999999999996"), (1 + 2**-52, "1.0000000000000002"),
    (-0.0, "0"), (1.0, "1"), (-0.1, "-0.1"), (1 / 3, "0.3333333333333333"), (1e22, "1e+22"),
])
def test_an_input_prints_as_it_is_typed(value, text):
    assert exact(value) == text


@given(st.lists(finite, min_size=1, max_size=5), st.integers(1, 12))
def test_computed_values_print_in_their_order(values, digits):
    printed = texts(values, digits)
    read = [float(t) for t in printed]
    for i in range(len(values)):
        assert not NEGATIVE_ZERO.search(printed[i])
        for j in range(len(values)):
            assert order(read[i], read[j]) == order(values[i], values[j]), (values, printed)


@given(finite, st.lists(finite, min_size=1, max_size=3), st.integers(1, 12))
def test_a_value_prints_on_its_side_of_every_bound(value, bounds, digits):
    read = float(compared(value, bounds, digits))
    assert all(order(read, b) == order(value, b) for b in bounds), (value, bounds)


def test_a_value_equal_to_its_bound_prints_as_the_bound_and_sizes_that_differ_print_unlike():
    assert compared(0.1, [0.1]) == "0.1" and compared(2 / 3, [2 / 3], digits=6) == exact(2 / 3)
    estimate, budget = texts([2_000_000_002 / 1e9, 2_000_000_001 / 1e9], 3)  # both "2" GB to three digits
    assert float(estimate) > float(budget)


def params(**changes) -> Parameters:
    return Parameters(**{"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, **changes})


@pytest.mark.parametrize("b", [1 + 2**-52, 1.0000001, 1.5 + 2**-52, 2 - 4.4e-16])
def test_the_chattering_message_tells_b_the_ratio_and_the_zeno_time_apart_from_their_bounds(b):
    run = solve_exact(params(b=b), 1.0, n_cycles=3)
    assert run.status.value == "chattering"
    assert f"(b = {b!r} > 1," in run.message  # as typed, so never "b = 1 > 1" nor "b = 2"
    ratio = float(re.search(r"v\+ = (\S+) v-", run.message).group(1))
    assert -1 < ratio < 0 and ratio == pytest.approx(1 - b, rel=1e-9)  # the impact law: v+ = (1 - b) v-
    t_hit = float(re.search(r"at t = (\S+) s reversed", run.message).group(1))
    t_acc = float(re.search(r"accumulate at t = (\S+) s", run.message).group(1))
    assert t_acc > t_hit  # the rebounds take time: never printed as the impact's own time
    assert NEGATIVE_ZERO.search(run.message) is None


@pytest.mark.parametrize("changes, x0", [
    ({"b": 1.999999}, 1.0), ({"b": 0.1 + 2**-50, "F": 1 / 3}, 1 + 2**-52), ({"a1": -0.1000000000000001}, 0.7),
    ({"a2": 0.05, "a3": 0.12345678901234, "a4": -0.0123456789}, 1.0),
])
def test_a_summary_prints_every_input_so_that_it_reads_back(changes, x0):
    p = params(**changes)
    run = solve_exact(p, x0, n_cycles=2)
    lines = {line.split(":", 1)[0]: line.split(":", 1)[1] for line in repr(run).splitlines()[2:] if ":" in line}
    printed = dict(re.findall(r"(\w+) = (\S+?)(?:,| |$)", lines["parameters"] + "," + lines["initial"]))
    expected = {**p.as_dict(), "x0": x0, "v0": 0.0}
    assert set(printed) == set(expected)
    assert all(float(printed[name]) == value for name, value in expected.items()), printed


def negative_zeros(run) -> list[str]:
    texts_ = [run.message, repr(run)] + ([repr(run.trajectory)] if isinstance(run.trajectory, ArcTable) else [])
    return [text for text in texts_ if NEGATIVE_ZERO.search(text)]


@pytest.mark.parametrize("x0, v0, solver", [(-0.01, 0.0, solve_reference), (-0.04, 1e-3, solve_reference),
                                             (-0.02, -1e-3, solve_reference), (-0.0, -0.0, solve_exact),
                                             (-0.0, 0.0, solve_exact), (0.0, -0.0, solve_exact),
                                             (-0.03, -0.0, solve_exact)])
def test_a_run_that_stops_at_once_or_a_signed_zero_input_prints_no_negative_zero(x0, v0, solver):
    run = solver(params(), x0, v0, n_cycles=2)
    assert negative_zeros(run) == []
    if solver is solve_reference:  # from the left, stopped at once
        assert run.status.value == "stopped" and "stopped at t = 0 s" in run.message
    else:
        runs = solve_ensemble(M=1.0, K=1.0, F=[1.0, 0.5], b=0.1, a1=-0.1, a2=0.05, x0=x0, v0=v0, n_cycles=2)
        assert not NEGATIVE_ZERO.search(repr(runs))


def test_the_stopped_message_prints_a_turning_point_short_of_its_bound_as_short():
    text = stopped_message(-0.0, 0.09999999999999999, {"a1": -0.1, "a3": 0.1})
    assert "stopped at t = 0 s" in text
    turns = [float(x) for x in re.findall(r"turns at x = (\S+) m and x = (\S+) m", text)[0]]
    assert turns[0] > -0.1 and turns[1] < 0.1 and turns[0] == -turns[1]
    assert "x = 0 m and x = 0 m" in stopped_message(1.0, -0.0, {"a1": -0.1})


@pytest.mark.parametrize("turning, end", [(0.05 - 2**-57, 0.05), (-0.1 + 1e-15, -0.1), (0.3, 0.3)])
def test_the_turned_back_message_prints_the_turning_point_on_its_side_of_the_zone_end(turning, end):
    text = turned_back_message(2.5, "(a1, a2)", turning, 0.01, end)
    read = float(re.search(r"the motion turns at x = (\S+) m", text).group(1))
    assert order(read, end) == order(turning, end)
    assert f"end at {exact(end)} m" in text


@pytest.mark.parametrize("t_end, text", [(1 / 3, "0.3333333333333333"), (0.1 + 0.2, "0.30000000000000004"),
                                         (7.0, "7")])
def test_the_end_time_prints_as_typed(t_end, text):
    run = solve_exact(params(), 1.0, t_end=t_end)
    assert run.message.startswith(f"reached t_end = {text} s after ")


def test_a_summary_of_times_that_differ_prints_them_apart():
    run = solve_exact(params(b=1 + 2**-52), 1.0, n_cycles=3)  # the rebounds accumulate just after the impact
    text = repr(run)
    t_final = float(re.search(r"t = 0 \.\. (\S+) s \(t_final\)", text).group(1))
    t_acc = float(re.search(r"t_accumulation = (\S+) s", text).group(1))
    assert math.isfinite(t_acc) and t_acc > t_final
    assert not np.isnan(run.exit.t_accumulation)
