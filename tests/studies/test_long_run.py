import math

import numpy as np
import pytest

from escapement.model.parameters import ParameterError, Parameters
from escapement.studies.long_run import converged_after, long_run, sample_cycles

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)


def test_converged_after_leaves_a_transient_below_1e45():
    n = converged_after(P)
    assert 0.6561 ** (n - 2) < 1e-45 < 0.6561 ** (n - 4)
    assert converged_after(Parameters(M=1, K=1, F=1, b=1.0, a1=-0.1, a2=0.05)) == 2


def test_sample_cycles_are_log_spaced_and_end_at_n():
    c = sample_cycles(10_000)
    assert c[0] == 1 and c[-1] == 10_000 and np.all(np.diff(c) > 0)


def test_a_short_long_run_stays_at_rounding_level():
    r = long_run(P, 1.0, 20_000, "DOP853", 1e-10, 50)
    et, ev, _ = r["exact"]
    assert np.nanmax(et) < 1e-15 and np.nanmax(ev) < 1e-15
    assert r["max_velocity_deviation"] < 1e-15 and r["max_period_deviation"] < 1e-15
    assert np.nanmax(r["ivp"][0]) > np.nanmax(et)
    # the series in closed form, checked by the streamed event solver over the whole run
    assert r["series_method"] == "closed-form cycles" and r["fallback"] is None and r["distinct_cycles"] < 200
    assert r["check_cycles"] == 20_000 and r["check_max_relative_difference"] <= 1e-14
    assert set(r["check_differences"]) == {"impact_time", "velocity_before_impact", "period", "largest_displacement"}
    cf_t, cf_v, _ = r["closed_form"]
    assert np.nanmax(cf_t) < 1e-15 and np.nanmax(cf_v) < 1e-14 and np.isfinite(cf_t).all()
    assert r["closed_form_wall_s"] > 0 and r["exact_wall_s"] > 0


def test_a_long_run_checks_the_closed_form_on_a_prefix():
    r = long_run(P, 1.0, 20_000, "DOP853", 1e-8, 5, check_cycles=1_000)
    assert r["check_cycles"] == 1_000 and r["check_max_relative_difference"] <= 1e-14
    sampled = r["cycles"]
    es_t = r["exact"][0]
    assert np.isfinite(es_t[sampled <= 1_000]).all() and np.isnan(es_t[sampled > 1_000]).all()
    assert np.isfinite(r["closed_form"][0]).all()  # the closed forms cover every cycle


def test_the_event_solver_must_run_past_the_transient():
    with pytest.raises(ParameterError, match="check_cycles"):
        long_run(P, 1.0, 20_000, "DOP853", 1e-8, 5, check_cycles=10)


def test_the_reference_fixed_point_is_eq19():
    # 45 digits of a transient decaying by 0.6561 per cycle: 45 ln 10 / -ln 0.6561 = 245.9, so 246 + 2 cycles
    assert converged_after(P) == 248
    r = long_run(P, 1.0, 300, "DOP853", 1e-8, 5)
    assert r["converged_after"] == 248
    assert r["fixed_point_velocity"] == pytest.approx(math.sqrt(2 * 0.15 / (0.2 - 0.01)), rel=1e-15)
    assert r["cycles"][-1] == 300 and not r["any_nan"]
    assert np.isnan(r["ivp"][0][r["cycles"] > 5]).all() and np.isfinite(r["ivp"][0][r["cycles"] <= 5]).all()


def test_the_long_run_gives_the_numbers_of_the_whole_cycle_table():
    """The long run keeps only sampled cycles and running maxima; from the whole table of solve_exact the
    same numbers follow, and the closed forms' whole table is within 1e-14 of it."""
    import mpmath

    from escapement.solvers.cycles import compare_tables, solve_cycles
    from escapement.solvers.exact import solve_exact

    n = 30_000
    r = long_run(P, 1.0, n, "DOP853", 1e-8, 20)
    c = solve_exact(P, 1.0, n_cycles=n, record_trajectory=False).cycles
    n0 = r["converged_after"]
    v_star, t_star = r["fixed_point_velocity"], r["fixed_point_period"]
    assert r["max_velocity_deviation"] == float(np.max(np.abs(c.velocity_before_impact[n0:] - v_star))) / v_star
    assert r["max_period_deviation"] == float(np.max(np.abs(c.period[n0:] - t_star))) / t_star
    et, ev, drift = r["exact"]
    sampled = r["cycles"]
    # the drift is t - t_ref; t_ref from the error: |drift| / t_ref = et
    with mpmath.workdps(60):
        t_ref = [mpmath.mpf(c.impact_time[k - 1]) - mpmath.mpf(d) for k, d in zip(sampled, drift)]
    assert np.all(np.isfinite(et)) and np.all(np.isfinite(ev))
    assert et == pytest.approx([abs(d) / float(t) for d, t in zip(drift, t_ref)], rel=1e-12)
    assert not r["any_nan"]
    closed = solve_cycles(P, 1.0, n_cycles=n).cycles
    assert r["check_differences"] == compare_tables(closed, c)
    assert r["check_max_relative_difference"] <= 1e-14


@pytest.mark.parametrize("n_cycles", [10, 248])
def test_a_long_run_shorter_than_the_transient_is_refused(n_cycles):
    from escapement.model.parameters import ParameterError

    with pytest.raises(ParameterError) as err:
        long_run(P, 1.0, n_cycles, "DOP853", 1e-8, 5)
    assert (err.value.name, err.value.value) == ("n_cycles", n_cycles) and "> 248" in err.value.requirement
