"""The work-precision benchmark: every method against the 50-digit reference, the rows and ratios it times (on a
clock of set durations), and its refusals of bad arguments before any run."""

import math
from types import SimpleNamespace

import pytest

from escapement.model.parameters import Parameters
from escapement.integrators.high_precision import solve_high_precision
from escapement.studies import benchmark
from escapement.studies.benchmark import (closed_form_map, headline_ratios, median_wall, per_cycle_times, run_method,
                                          work_precision)

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)
N = 5


class DurationClock:
    """A clock read twice per timed run: each end comes the next of ``durations`` (binary fractions: sums and
    quotients exact) after the start, or 1 s."""

    def __init__(self, durations=()) -> None:
        self.durations, self.now, self.readings = list(durations), 0.0, 0

    def __call__(self) -> float:
        self.readings += 1
        if self.readings % 2 == 0:
            self.now += self.durations.pop(0) if self.durations else 1.0
        return self.now


def use_clock(monkeypatch, durations=()) -> DurationClock:
    clock = DurationClock(durations)
    monkeypatch.setattr(benchmark, "time", SimpleNamespace(perf_counter=clock))
    return clock


@pytest.fixture(scope="module")
def reference():
    """Velocity before impact and impact time at cycle N, in 50 digits (t is about 30 s, v about 1.2 m/s)."""
    hp = solve_high_precision(P, 1.0, n_cycles=N).cycles
    return float(hp.velocity_before_impact[-1]), float(hp.impact_time[-1])


@pytest.mark.parametrize("x0", [1.0, -1.0, -3.0])
def test_closed_form_map_agrees_with_the_50_digit_reference(x0):
    """From either side: released right of a3 the first swing meets a3 first, left of a1 it meets a1 (from rest at
    -1 m, w = 1: x = -cos t meets a1 = -0.1 at t = arccos(0.1), at v = sqrt(1 - 0.01))."""
    v, t = closed_form_map(P, x0, 50)
    hp = solve_high_precision(P, x0, n_cycles=50).cycles
    assert (v, t) == pytest.approx((float(hp.velocity_before_impact[-1]), float(hp.impact_time[-1])), rel=1e-14)
    if x0 == -1.0:
        assert closed_form_map(P, x0, 1) == pytest.approx((math.sqrt(0.99), math.acos(0.1)), rel=1e-15)


# Tolerances, from the error each method can make over the N = 5 cycles (about 20 events, 40 segments):
# * exact, the per-cycle closed form and map16: rounding, some ulps per event: 1e-14;
# * an integrator at rtol: each segment's local error is up to a few rtol and an event location moves the
#   time by that over |v| >= 0.1 m/s: within 1e3 rtol;
# * naive RK4 at step h: each event is applied up to one step late, so the time is off by at most 20 h
#   over t = 30 s, and each event's velocity by up to w^2 |x| h <= h (|x| <= 1 m), a few events' worth: 5 h.
@pytest.mark.parametrize("method, setting, tol_v, tol_t", [
    ("exact", None, 1e-14, 1e-14), ("closed-form cycles", None, 1e-14, 1e-14), ("map16", None, 1e-14, 1e-14),
    ("RK45", 1e-8, 1e-5, 1e-5), ("DOP853", 1e-10, 1e-7, 1e-7), ("LSODA", 1e-8, 1e-5, 1e-5), ("Radau", 1e-8, 1e-5, 1e-5),
    ("CVODE-Adams", 1e-9, 1e-6, 1e-6), ("CVODE-BDF", 1e-9, 1e-6, 1e-6), ("naive-RK4", 1e-3, 5e-3, 20 * 1e-3 / 30),
])
def test_every_method_lands_near_the_50_digit_reference(reference, method, setting, tol_v, tol_t):
    v_ref, t_ref = reference
    v, t = run_method(method, setting, P, 1.0, N)
    assert abs(v - v_ref) / v_ref < tol_v and abs(t - t_ref) / t_ref < tol_t
    if method == "naive-RK4":  # ten times the step, about ten times the time error (events late by up to a step)
        assert 3 < abs(run_method(method, 10 * setting, P, 1.0, N)[1] - t_ref) / abs(t - t_ref) < 30


@pytest.mark.parametrize("method", ["naive-RK4", "DOP853"])
def test_a_run_that_leaves_the_regime_is_an_error(method):
    # released inside |a1|: the escapement stops, no cycle is completed
    with pytest.raises(RuntimeError, match="ended early"):
        run_method(method, 0.01 if method == "naive-RK4" else 1e-8, P, 0.05, N)


def test_rows_hold_the_errors_of_each_run_against_50_digits(reference, monkeypatch):
    v_ref, t_ref = reference
    # one run of each at 0.5 s, then 0.25 s each up to 1 s: 1, 1, 3 and 4 runs (the last at its cap of 4)
    use_clock(monkeypatch, [1.0, 2.0, 0.5, 0.25, 0.25, 0.25, 0.25, 0.25, 0.25])
    rows = work_precision(P, 1.0, N, {"exact": [], "naive-RK4": [0.1, 0.01]}, min_seconds=1.0, max_repeats=4)
    assert [(r["wall_s"], r["repeats"]) for r in rows] == [(1.0, 1), (2.0, 1), (0.25, 3), (0.25, 4)]
    assert [(r["method"], r["setting"]) for r in rows] == [
        ("exact", ""), ("closed-form cycles", ""), ("naive-RK4", "0.1"), ("naive-RK4", "0.01")]
    for row, setting in zip(rows[2:], (0.1, 0.01)):
        v, t = run_method("naive-RK4", setting, P, 1.0, N)  # deterministic: the same run again
        assert row["error_velocity"] == pytest.approx(abs(v - v_ref) / v_ref, rel=1e-12)
        assert row["error_time"] == pytest.approx(abs(t - t_ref) / t_ref, rel=1e-12)
    for row in rows[:2]:  # the exact solver and the per-cycle closed form
        assert row["error_velocity"] < 1e-14 and row["error_time"] < 1e-14
    assert rows[3]["error_time"] < rows[2]["error_time"]  # a smaller step is more accurate


def test_the_closed_form_row_follows_exact_only_when_asked(monkeypatch):
    use_clock(monkeypatch)
    for settings, closed_form, methods in (({"map16": [], "exact": []}, True, ["map16", "exact", "closed-form cycles"]),
                                           ({"map16": []}, True, ["map16"]), ({"exact": []}, False, ["exact"])):
        rows = work_precision(P, 1.0, N, settings, min_seconds=0.01, max_repeats=2, closed_form=closed_form)
        assert [r["method"] for r in rows] == methods


def test_headline_ratios_pick_the_fastest_setting_that_reaches_the_target(reference, monkeypatch):
    # timed in this order, one run each (every run takes at least min_seconds): the exact solver 2 s, the
    # per-cycle closed form 0.5 s, DOP853 4 s, CVODE-Adams 1 s, RK45 0.25 s; naive-RK4 is no candidate
    use_clock(monkeypatch, [2.0, 0.5, 4.0, 1.0, 0.25])
    settings = {"DOP853": [1e-10], "CVODE-Adams": [1e-9], "RK45": [1e-2], "naive-RK4": [0.1]}
    h = headline_ratios(P, 1.0, N, settings, target=1e-5, min_seconds=0.25, max_repeats=3)
    assert h["n_cycles"] == N and h["target"] == 1e-5 and h["errors"] == ("error_velocity", "error_time")
    assert [(r["method"], r["setting"], r["wall_s"]) for r in h["candidates"]] == [
        ("DOP853", "1e-10", 4.0), ("CVODE-Adams", "1e-09", 1.0), ("RK45", "0.01", 0.25)]
    # DOP853 and CVODE-Adams reach 1e-5 (within 1e-7 and 1e-6, the tolerances above); RK45 at rtol 1e-2,
    # the fastest, does not: so CVODE-Adams, 1 s, is the one compared
    assert max(h["candidates"][2]["error_velocity"], h["candidates"][2]["error_time"]) > 1e-5
    assert (h["exact"]["wall_s"], h["closed_form"]["wall_s"]) == (2.0, 0.5)
    assert (h["ode"]["method"], h["ode"]["wall_s"]) == ("CVODE-Adams", 1.0)
    assert h["exact_over_closed_form"] == 4.0  # 2 / 0.5
    assert h["ode_over_closed_form"] == 2.0  # 1 / 0.5
    assert h["ode_over_exact"] == 0.5  # 1 / 2
    # a target no setting reaches: no ode row, no ratio against it
    none = headline_ratios(P, 1.0, N, {"DOP853": [1e-6]}, target=1e-30, errors=("error_time",), min_seconds=0.25,
                           max_repeats=2)
    assert none["ode"] is None and math.isnan(none["ode_over_closed_form"]) and math.isnan(none["ode_over_exact"])
    assert none["exact_over_closed_form"] == 1.0  # both 1 s on the clock's default


def test_per_cycle_times_compare_the_closed_form_with_the_exact_solver(monkeypatch):
    use_clock(monkeypatch, [2.0, 0.5, 8.0, 1.0])  # for 5 cycles, the exact solver then the closed form; for 50
    rows = per_cycle_times(P, 1.0, (5, 50), min_seconds=0.5, max_repeats=3)
    assert rows == [
        {"n_cycles": 5, "exact_s_per_cycle": pytest.approx(0.4), "closed_form_s_per_cycle": pytest.approx(0.1),
         "ratio": 4.0},
        {"n_cycles": 50, "exact_s_per_cycle": pytest.approx(0.16), "closed_form_s_per_cycle": pytest.approx(0.02),
         "ratio": 8.0},
    ]


def _never(*args, **kwargs):
    pytest.fail("a refused call ran")


@pytest.mark.parametrize("call, words", [
    *[(lambda n=n: closed_form_map(P, -1.0, n), f"n_cycles = {n!r} is invalid: n_cycles must be a positive")
      for n in (0, 1.5, True)],
    *[(lambda x0=x0: closed_form_map(P, x0, 5), f"x0 = {x0!r} is invalid: x0 must be a release left of a1 = -0.1 < 0 "
       "or right of a3 = 0.1 > 0 (m)") for x0 in (0.05, -0.05, 0.1, -0.1)],
    *[(lambda m=m: run_method(m, None, P, 1.0, N), f"method = {m!r} is invalid: method must be one of exact, ")
      for m in ("magic", "rk45", "", "exact ")],
    (lambda: work_precision(P, 1.0, 5, {"magic": []}, 0.1, 5), "method = 'magic' is invalid"),
    (lambda: work_precision(P, 1.0, 5, {"exact": []}, 0.0, 5), "min_seconds = 0.0 is invalid: min_seconds must be in"),
    (lambda: work_precision(P, 1.0, 5, {"exact": []}, 0.1, True), "max_repeats = True is invalid"),
    (lambda: headline_ratios(P, 1.0, N, {}, errors=("error_amplitude",)), "errors = ('error_amplitude',) is invalid"),
    (lambda: headline_ratios(P, 1.0, N, {}, target=0), "target = 0 is invalid: target must be > 0"),
    (lambda: median_wall(None, 0.01, 3), "fn = None is invalid: fn must be callable"),
    *[(lambda m=m: median_wall(_never, m, 3), f"min_seconds = {m!r} is invalid: min_seconds must be in (0, 60] (s)")
      for m in (0, 61.0, "0.1")],
    *[(lambda m=m: median_wall(_never, 0.01, m), f"max_repeats = {m!r} is invalid: max_repeats must be an integer in "
       "[1, 10000]") for m in (0, 2.0)],
])
def test_a_bad_argument_is_refused_in_one_line_before_any_run(call, words, monkeypatch):
    for name in ("solve_exact", "solve_cycles", "solve_high_precision", "solve_reference", "solve_naive"):
        monkeypatch.setattr(benchmark, name, _never)
    with pytest.raises((TypeError, ValueError)) as refused:  # ParameterError is a ValueError
        call()
    assert str(refused.value).startswith(words) and "\n" not in str(refused.value)


def test_timing_repeats_a_call_until_the_time_is_measured_and_stops_at_the_cap(monkeypatch):
    """On a clock on which every run takes a set time: a call that takes 0.125 s is repeated until the runs
    add up to the time asked for, one that takes more than that runs once, and the cap holds."""
    calls = []

    def call():
        calls.append(1)
        return "done"

    use_clock(monkeypatch, [0.125] * 10)
    wall, runs, result = median_wall(call, min_seconds=1.0, max_repeats=10_000)
    assert result == "done" and runs == len(calls) == 8 and wall == 0.125  # 8 * 0.125 = 1
    use_clock(monkeypatch, [2.0])
    assert median_wall(call, min_seconds=1.0, max_repeats=50)[1] == 1
    use_clock(monkeypatch, [0.125] * 7)
    assert median_wall(call, min_seconds=10.0, max_repeats=7)[1] == 7  # the cap
    use_clock(monkeypatch, [0.5, 0.125, 1.0])  # the median of three, not their mean
    assert median_wall(call, min_seconds=1.5, max_repeats=10)[:2] == (0.5, 3)
