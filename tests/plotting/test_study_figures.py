"""What the project's own figures state: rounding noise drawn as such (long run), which sign of the rate
gains (escapement error), why a work-precision line turns back in time, and Fig. 3's formulas as mathtext."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from escapement.plotting.captions import math_text
from escapement.plotting.study_figures import COLD_START, long_run, work_precision

PERIOD = 6.295673629674346  # s, the fixed point's period of Fig. 3 case (a)


def _long_run_dataset(drift_ivp_second: float) -> xr.Dataset:
    cycle = np.array([1, 2, 3, 10])
    return xr.Dataset(
        {"drift_exact": ("cycle", [1e-16, 2e-16, 1e-16, 3e-16]),
         "drift_ivp": ("cycle", [3e-13, drift_ivp_second, 1e-12, 1e-11]),
         "error_velocity_exact": ("cycle", [1e-17, 4e-16, 0.0, 2e-16]),
         "error_velocity_ivp": ("cycle", [1e-13, 2e-12, 3e-12, 3e-12]),
         "fixed_point_period": PERIOD},
        coords={"cycle": cycle}, attrs={"ivp_label": "solve_ivp DOP853 rtol=1e-12"})


def _lines(fig, label):
    return [line.get_ydata() for ax in fig.axes for line in ax.get_lines() if line.get_label() == label]


def test_rounding_noise_is_drawn_on_the_band_edge_and_its_bits_do_not_change_the_figure():
    a, b = long_run(_long_run_dataset(1.7e-14)), long_run(_long_run_dataset(1.1e-14))
    try:
        drift = _lines(a, "solve_ivp DOP853 rtol=1e-12")[0]
        # cycle 2, t = 12.59 s: 16 ulps, the spacing of float64 in [8, 16) being 2**-49
        assert drift[1] == pytest.approx(16 * 2.0**-49, rel=1e-12)
        assert [drift[0], *drift[2:]] == [3e-13, 1e-12, 1e-11]  # above the band: as measured
        for label in ("solve_ivp DOP853 rtol=1e-12", "exact solver"):
            for x, y in zip(_lines(a, label), _lines(b, label)):
                np.testing.assert_array_equal(x, y)
        exact_velocity = _lines(a, "exact solver")[1]
        np.testing.assert_array_equal(exact_velocity, np.full(4, 16 * 2.0**-52))
        assert "16 ulps" in a._suptitle.get_text()
    finally:
        plt.close(a)
        plt.close(b)


def _row(method, setting, wall, repeats=1):
    return {"method": method, "setting": setting, "wall_s": wall, "repeats": repeats, "error_velocity": 1e-6,
            "error_time": 1e-7}


@pytest.mark.parametrize("repeats, ringed", [(1, True), (5, False)])
def test_the_first_cvode_run_timed_once_is_ringed_and_explained(repeats, ringed):
    rows = [_row("CVODE-Adams", 1e-3, 3.5, repeats), _row("CVODE-Adams", 1e-6, 1.1), _row("DOP853", 1e-3, 0.9)]
    fig = work_precision(rows)
    try:
        assert bool(_lines(fig, COLD_START)) is ringed
        assert "loading SUNDIALS" in fig._suptitle.get_text()
    finally:
        plt.close(fig)


def test_math_text_writes_the_formulas_and_the_accent():
    text = ("Poincare map; Step-1 amplitude h0(k) = sqrt(a1^2 + (v_k / omega)^2) of the arc ending at a1; "
            "h4(k) = h0(k+1); a1s")
    assert math_text(text) == ("Poincar\u00e9 map; Step-1 amplitude $h_0(k)$ = $\\sqrt{a_1^2+(v_k/\\omega)^2}$ of the "
                               "arc ending at $a_1$; $h_4(k)$ = $h_0(k+1)$; a1s")
    assert math_text(math_text(text)) == math_text(text)


def test_the_escapement_error_says_which_sign_gains():
    from escapement import Parameters
    from escapement.pipeline.simulate import escapement_error_scene
    from escapement.plotting.study_figures import escapement_error

    ds = escapement_error_scene(Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05), [0.5, 1.0],
                                {"paper": [-0.1, 0.05]})
    fig = escapement_error(ds)
    try:
        assert all("> 0: gains (runs fast), < 0: loses" in ax.get_ylabel() for ax in fig.axes)
        assert "a positive rate means the clock gains (runs fast)" in fig._suptitle.get_text()
    finally:
        plt.close(fig)
