"""The long run against 50 digits: the exact solver and the closed forms at rounding level, streamed in chunks (of
700 cycles here, so that the runs cross chunk boundaries), and the numbers of the whole table."""

import math

import mpmath
import numpy as np
import pytest

from escapement.model.parameters import ParameterError, Parameters
from escapement.solvers.cycles import compare_tables, solve_cycles
from escapement.solvers.exact import solve_exact
from escapement.studies import long_run as module
from escapement.studies.long_run import converged_after, long_run, sample_cycles

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)


@pytest.fixture(autouse=True)
def small_chunks(monkeypatch):
    monkeypatch.setattr(module, "CHUNK", 700)


def test_converged_after_leaves_a_transient_below_1e45_and_samples_are_log_spaced():
    # 45 digits of a transient decaying by 0.6561 per cycle: 45 ln 10 / -ln 0.6561 = 245.9, so 246 + 2 cycles
    assert converged_after(P) == 248 and 0.6561 ** (248 - 2) < 1e-45 < 0.6561 ** (248 - 4)
    assert converged_after(Parameters(M=1, K=1, F=1, b=1.0, a1=-0.1, a2=0.05)) == 2
    c = sample_cycles(10_000)
    assert c[0] == 1 and c[-1] == 10_000 and np.all(np.diff(c) > 0)


def test_a_short_long_run_stays_at_rounding_level():
    r = long_run(P, 1.0, 3_000, "DOP853", 1e-10, 20)
    et, ev, _ = r["exact"]
    assert np.nanmax(et) < 1e-15 and np.nanmax(ev) < 1e-15
    assert r["max_velocity_deviation"] < 1e-15 and r["max_period_deviation"] < 1e-15
    assert np.nanmax(r["ivp"][0]) > np.nanmax(et)
    assert np.isnan(r["ivp"][0][r["cycles"] > 20]).all() and np.isfinite(r["ivp"][0][r["cycles"] <= 20]).all()
    # the series in closed form, checked by the streamed event solver over the whole run
    assert r["series_method"] == "closed-form cycles" and r["fallback"] is None and r["distinct_cycles"] < 300
    assert r["check_cycles"] == 3_000 and r["check_max_relative_difference"] <= 1e-14
    assert set(r["check_differences"]) == {"impact_time", "velocity_before_impact", "period", "largest_displacement"}
    cf_t, cf_v, _ = r["closed_form"]
    assert np.nanmax(cf_t) < 1e-15 and np.nanmax(cf_v) < 1e-14 and np.isfinite(cf_t).all()
    assert r["closed_form_wall_s"] > 0 and r["exact_wall_s"] > 0 and not r["any_nan"] and r["converged_after"] == 248
    assert r["fixed_point_velocity"] == pytest.approx(math.sqrt(2 * 0.15 / (0.2 - 0.01)), rel=1e-15)  # Eq. (19)


def test_a_long_run_checks_the_closed_form_on_a_prefix():
    r = long_run(P, 1.0, 3_000, "DOP853", 1e-8, 5, check_cycles=1_000)
    assert r["check_cycles"] == 1_000 and r["check_max_relative_difference"] <= 1e-14
    es_t = r["exact"][0]
    assert np.isfinite(es_t[r["cycles"] <= 1_000]).all() and np.isnan(es_t[r["cycles"] > 1_000]).all()
    assert np.isfinite(r["closed_form"][0]).all()  # the closed forms cover every cycle


@pytest.mark.parametrize("n_cycles, check_cycles, name, value", [
    (10, None, "n_cycles", 10), (248, None, "n_cycles", 248), (3_000, 10, "check_cycles", 10)])
def test_a_run_or_check_no_longer_than_the_transient_is_refused(n_cycles, check_cycles, name, value):
    with pytest.raises(ParameterError) as err:
        long_run(P, 1.0, n_cycles, "DOP853", 1e-8, 5, check_cycles=check_cycles)
    assert (err.value.name, err.value.value) == (name, value) and "> 248" in err.value.requirement


def test_the_long_run_gives_the_numbers_of_the_whole_cycle_table():
    """The long run keeps only sampled cycles and running maxima; from the whole table of solve_exact the
    same numbers follow, and the closed forms' whole table is within 1e-14 of it."""
    n = 2_500
    r = long_run(P, 1.0, n, "DOP853", 1e-8, 5)
    c = solve_exact(P, 1.0, n_cycles=n, record_trajectory=False).cycles
    n0 = r["converged_after"]
    v_star, t_star = r["fixed_point_velocity"], r["fixed_point_period"]
    assert r["max_velocity_deviation"] == float(np.max(np.abs(c.velocity_before_impact[n0:] - v_star))) / v_star
    assert r["max_period_deviation"] == float(np.max(np.abs(c.period[n0:] - t_star))) / t_star
    et, ev, drift = r["exact"]
    # the drift is t - t_ref; t_ref from the error: |drift| / t_ref = et
    with mpmath.workdps(60):
        t_ref = [mpmath.mpf(c.impact_time[k - 1]) - mpmath.mpf(d) for k, d in zip(r["cycles"], drift)]
    assert np.all(np.isfinite(et)) and np.all(np.isfinite(ev))
    assert et == pytest.approx([abs(d) / float(t) for d, t in zip(drift, t_ref)], rel=1e-12)
    assert r["check_differences"] == compare_tables(solve_cycles(P, 1.0, n_cycles=n).cycles, c)
