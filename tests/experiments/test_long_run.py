"""The long run: the study's errors, with the wall times kept apart."""

import pytest

from escapement.experiments.long_run import run_long
from escapement.model.parameters import ParameterError, Parameters

FAST = Parameters(M=1.0, K=1.0, F=1.0, b=0.9, a1=-0.1, a2=0.05)  # converges in a few cycles


def test_the_long_run_keeps_its_settings_and_times_each_method():
    run = run_long(FAST, 1.0, 50, "DOP853", 1e-8, 5)
    assert (run.n_cycles, run.ivp_method, run.ivp_rtol, run.ivp_cycles) == (50, "DOP853", 1e-8, 5)
    assert set(run.timings) == {"exact_seconds", "closed_form_seconds", "ivp_seconds"}
    assert run.timings["exact_seconds"] == run.errors["exact_wall_s"]
    assert run.errors["cycles"][-1] == 50


@pytest.mark.parametrize("name", ["n_cycles", "ivp_cycles"])
def test_the_counts_must_be_positive_integers(name):
    counts = {"n_cycles": 50, "ivp_cycles": 5, name: 0}
    with pytest.raises(ParameterError, match=f"^{name} = "):
        run_long(FAST, 1.0, counts["n_cycles"], "DOP853", 1e-8, counts["ivp_cycles"])
