import numpy as np

from escapement import Parameters
from escapement.longrun import converged_after, long_run, sample_cycles

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
