import pytest

from escapement import Parameters, solve_exact
from escapement.benchmark import METHODS, closed_form_map, run_method, work_precision
from escapement.highprecision import solve_high_precision

P = Parameters(M=1, K=1, F=1, b=0.1, a1=-0.1, a2=0.05)


def test_closed_form_map_agrees_with_the_50_digit_reference():
    hp = solve_high_precision(P, 1.0, n_cycles=50)
    v, t = closed_form_map(P, 1.0, 50)
    assert v == pytest.approx(float(hp.velocity_before_impact[-1]), rel=1e-14)
    assert t == pytest.approx(float(hp.impact_time[-1]), rel=1e-14)


def test_closed_form_map_needs_release_beyond_a3():
    with pytest.raises(ValueError, match="x0 > a3"):
        closed_form_map(P, 0.05, 5)


@pytest.mark.parametrize("method, setting", [("exact", None), ("DOP853", 1e-9), ("CVODE-Adams", 1e-9),
                                             ("naive-RK4", 0.01), ("map16", None)])
def test_every_method_lands_near_the_exact_solution(method, setting):
    c = solve_exact(P, 1.0, n_cycles=5).cycles
    v, t = run_method(method, setting, P, 1.0, 5)
    tolerance = 5e-2 if method == "naive-RK4" else 1e-5
    assert v == pytest.approx(c.velocity_before_impact[-1], rel=tolerance)
    assert t == pytest.approx(c.impact_time[-1], rel=tolerance)


def test_rows_have_the_benchmark_columns_and_a_reasonable_order():
    rows = work_precision(P, 1.0, 5, {"exact": [], "naive-RK4": [0.1, 0.01]}, repeats=5)
    assert [list(r) for r in rows] == [["method", "setting", "wall_s", "error_velocity", "error_time"]] * 3
    assert rows[0]["error_velocity"] < 1e-14 and rows[0]["error_time"] < 1e-14
    assert rows[2]["error_velocity"] < rows[1]["error_velocity"]  # a smaller step is more accurate


@pytest.mark.parametrize("settings, repeats, message", [({"exact": []}, 4, "repeats"), ({"magic": []}, 5, "method")])
def test_invalid_benchmark_settings(settings, repeats, message):
    with pytest.raises(ValueError, match=message):
        work_precision(P, 1.0, 5, settings, repeats)


def test_method_names():
    assert set(METHODS) >= {"exact", "map16", "RK45", "DOP853", "LSODA", "Radau", "CVODE-Adams", "CVODE-BDF", "naive-RK4"}
