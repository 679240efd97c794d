"""What a notebook sees of a run: a short repr, its cycles and events as tables (``to_dataframe``), its samples
(the run as a CF dataset: tests/io)."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from escapement import EventKind, Parameters, Status, solve_ensemble, solve_exact, solve_high_precision


def test_the_repr_of_a_50_cycle_run_is_a_short_summary(run50):
    text = repr(run50)
    assert len(text) < 1000 and len(text.splitlines()) <= 12 and "array(" not in text
    assert text.splitlines()[0] == "<escapement.Solution> completed (exact)" and "completed 50 cycles" in text
    assert f"events:     {len(run50.events)} " in text and "cycles:     50;" in text
    params = next(line for line in text.splitlines() if line.startswith("parameters:"))
    assert params == ("parameters: M = 1 kg, K = 1 N/m, F = 1 N, b = 0.1, a1 = -0.1 m, a2 = 0.05 m, a3 = 0.1 m, "
                      "a4 = -0.05 m")
    assert "initial:    x0 = 1 m, v0 = 0 m/s" in text
    assert str(run50) == text
    short, long = (repr(solve_exact(run50.params, 1.0, n_cycles=n, record_trajectory=False)) for n in (5, 5000))
    assert len(long.splitlines()) == len(short.splitlines())
    assert abs(len(long) - len(short)) < 20  # the repr does not grow with the run: only the counts' digits differ


def test_the_repr_of_a_regime_exit_names_it_and_its_numbers(stopped):
    text = repr(stopped)
    assert text.splitlines()[0] == "<escapement.Solution> stopped (exact)"
    assert "t = 0 .. inf s" in text
    assert "exit:       turning_point = 0.01 m, margin = 0.09 m" in text
    assert "a1 = -0.1 m (moving right)" in text  # the message, wrapped but whole
    assert max(len(line) for line in text.splitlines()) <= 120


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


def test_the_cycle_table_and_arcs_print_short(run50):
    cycles = repr(run50.cycles)
    assert cycles.splitlines()[0] == "<CycleTable> 50 cycles"
    lo, hi = run50.cycles.period.min(), run50.cycles.period.max()
    assert f"period                  {lo:.6g} .. {hi:.6g} s" in cycles
    assert len(cycles) < 400
    arcs = repr(run50.trajectory)
    assert arcs.startswith(f"<ArcTable> {len(run50.trajectory.t_start)} harmonic arcs") and len(arcs) < 200


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
    np.testing.assert_array_equal(df["event_time"].to_numpy(), ev.t)
    np.testing.assert_array_equal(df["event_velocity_after"].to_numpy(), ev.v_after)
    np.testing.assert_array_equal(df["event_position"].to_numpy(), ev.x)
    impacts = df[df["event_kind"] == EventKind.IMPACT_A1]
    assert impacts.index.tolist() == ev.of_kind(EventKind.IMPACT_A1).tolist()
    assert (impacts["event_position"] == -0.1).all()  # every impact at a1 is at a1
    assert df.attrs["units"] == {"event_time": "s", "event_position": "m", "event_velocity_before": "m s-1",
                                 "event_velocity_after": "m s-1"}  # the kind is a code, without units
    assert df.attrs["long_names"]["event_velocity_after"] == "velocity just after the event"


def test_a_stopped_run_gives_empty_tables(stopped):
    assert stopped.status is Status.STOPPED
    assert stopped.to_dataframe("cycles").empty and stopped.to_dataframe("events").empty


@pytest.mark.parametrize(("t", "shape"), [(1.0, ()), (1, ()), (np.float32(1.0), ()), ([1.0], (1,)), ([0, 1], (2,)),
                                          (np.arange(3) / 2, (3,)), ([], (0,)), (np.ma.array([1.0], mask=False), (1,))])
def test_sample_takes_real_times_of_every_plain_kind(run50, t, shape):
    """Before the first impact (at 1.47 s) the release from 1 m at rest swings as x = cos t, v = -sin t (K = M = 1)."""
    x, v, a = run50.sample(t)
    assert x.shape == v.shape == a.shape == shape
    times = np.asarray(t, dtype=float)
    np.testing.assert_allclose(x, np.cos(times), rtol=1e-14)
    np.testing.assert_allclose(v, -np.sin(times), rtol=1e-14, atol=1e-15)
