import math

import numpy as np
import pytest

from escapement.model.parameters import Parameters
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


def test_the_reference_fixed_point_is_eq19():
    # 45 digits of a transient decaying by 0.6561 per cycle: 45 ln 10 / -ln 0.6561 = 245.9, so 246 + 2 cycles
    assert converged_after(P) == 248
    r = long_run(P, 1.0, 300, "DOP853", 1e-8, 5)
    assert r["converged_after"] == 248
    assert r["fixed_point_velocity"] == pytest.approx(math.sqrt(2 * 0.15 / (0.2 - 0.01)), rel=1e-15)
    assert r["cycles"][-1] == 300 and not r["any_nan"]
    assert np.isnan(r["ivp"][0][r["cycles"] > 5]).all() and np.isfinite(r["ivp"][0][r["cycles"] <= 5]).all()
