"""The candidate readings' series against closed forms derived on paper. Notation: omega = sqrt(K/M), f = F/M,
symmetric geometry a3 = -a1, a4 = -a2. In free flight ``v**2 + omega**2 x**2`` is constant; across an impulse zone
passed in the direction of the force ``v**2`` gains ``2 f`` times the zone's length on top of the spring's
``omega**2 (x_in**2 - x_out**2)``; an impact multiplies ``v`` by ``1 - b``."""

from __future__ import annotations

import math

import numpy as np
import pytest

from escapement import solve_exact
from escapement.studies.readings import (Runs, all_readings, critical_times, fig3_readings, fig4_readings,
                                         fig5_readings, largest_abs_per_cycle, step1_amplitudes)

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
CASES = {"a": {"F": 1.0, "x0": 1.0}, "b": {"F": 0.5, "x0": 3.0}}  # Fig. 3's, as the configuration gives them
B, A1, A2, A3, A4 = 0.1, -0.1, 0.05, 0.1, -0.05
N = 50


def cycle_by_energy(v1: float, w2: float, f: float) -> dict[str, float]:
    """One cycle from the velocity v1 before the impact at a1, step by step."""
    v1p = (1 - B) * v1
    v2 = math.sqrt(v1p**2 + w2 * (A1**2 - A2**2) + 2 * f * (A2 - A1))  # through (a1, a2) with +f
    v4 = math.sqrt(v2**2 + w2 * (A2**2 - A3**2))  # free to a3 (speed)
    v4p = (1 - B) * v4
    v5 = math.sqrt(v4p**2 + w2 * (A3**2 - A4**2) + 2 * f * (A3 - A4))  # through (a4, a3) with -f, moving left
    v1_next = math.sqrt(v5**2 + w2 * (A4**2 - A1**2))  # free to a1
    return {"v2": v2, "v4": v4, "v5": v5, "v1_next": v1_next}


def velocities(v1: float, n: int, w2: float = 1.0, f: float = 1.0) -> np.ndarray:
    out = [v1]
    for _ in range(n):
        out.append(cycle_by_energy(out[-1], w2, f)["v1_next"])
    return np.array(out)


def by_name(readings, panel: str, *words: str, count: str | None = None):
    """The one reading of ``panel`` whose name holds every word (and ends with ``; count``)."""
    found = [r for r in readings if r.panel == panel and all(w in r.name for w in words)
             and (count is None or r.name.endswith(f"; {count}"))]
    assert len(found) == 1, [r.name for r in found]
    return found[0]


@pytest.fixture(scope="module")
def fig3():
    return fig3_readings(MODEL, CASES, N)


def test_first_velocity_from_the_right_passes_the_impact_at_a3(fig3):
    """Released at +1 m: speed sqrt(1 - a3**2) at a3, times (1 - b), through (a4, a3) with the
    force, free from a4 to a1."""
    v4p = (1 - B) * math.sqrt(1.0 - A3**2)
    v5 = math.sqrt(v4p**2 + (A3**2 - A4**2) + 2 * 1.0 * (A3 - A4))
    expected = math.sqrt(v5**2 + A4**2 - A1**2)
    v = by_name(fig3, "a/velocity", "from +x0, section a1", count="k = 1..N").y
    assert v[0] == pytest.approx(expected, rel=1e-13)
    assert expected == pytest.approx(1.0497142, abs=1e-7)


@pytest.mark.parametrize("case, F, x0", [("a", 1.0, 1.0), ("b", 0.5, 3.0)])
def test_velocity_series_follows_the_energy_balance_from_the_left(fig3, case, F, x0):
    """Released at -x0: v**2 = omega**2 (x0**2 - a1**2) at a1 (0.99 for case a), then cycle by cycle."""
    r = by_name(fig3, f"{case}/velocity", "from -x0, section a1", count="k = 1..N")
    np.testing.assert_allclose(r.y, velocities(math.sqrt(x0**2 - A1**2), N - 1, f=F), rtol=1e-12)
    np.testing.assert_array_equal(r.x, np.arange(1, N + 1))


def test_step1_amplitude_from_minus_3_starts_at_3_and_has_one_more_point(fig3):
    r = by_name(fig3, "b/amplitude", "from -x0, section a1", "Step-1", count="k = 1..N+1")
    assert r.y[0] == pytest.approx(3.0, rel=1e-14)
    assert len(r.y) == N + 1 and r.x[-1] == N + 1
    v = velocities(math.sqrt(9.0 - A1**2), N, f=0.5)
    np.testing.assert_allclose(r.y, np.hypot(A1, v), rtol=1e-12)
    step8 = by_name(fig3, "b/amplitude", "from -x0, section a1", "Step-8", count="k = 1..N")
    np.testing.assert_allclose(step8.y, r.y[1:], rtol=0)
    assert len(step8.y) == N


def test_largest_displacement_and_largest_abs_per_cycle(fig3):
    """Right turning point sqrt(a2**2 + v2**2) (free after a2); left one h0(k + 1)."""
    v = velocities(math.sqrt(0.99), N, f=1.0)
    right = np.array([math.hypot(A2, cycle_by_energy(vk, 1.0, 1.0)["v2"]) for vk in v[:-1]])
    left = np.hypot(A1, v[1:])
    largest = by_name(fig3, "a/amplitude", "from -x0, section a1", "right turning point", count="k = 1..N")
    np.testing.assert_allclose(largest.y, right, rtol=1e-12)
    largest_abs = by_name(fig3, "a/amplitude", "from -x0, section a1", "largest |x|", count="k = 1..N")
    np.testing.assert_allclose(largest_abs.y, np.maximum(right, left), rtol=1e-12)


def test_fig3_reads_every_case_release_section_quantity_and_count(fig3, case_b):
    # 2 cases x 2 sides x 2 sections x 2 counts x (1 velocity + 2 periods + 5 amplitudes)
    assert len(fig3) == 2 * 2 * 2 * 2 * 8
    assert len({(r.panel, r.name) for r in fig3}) == len(fig3)
    assert {r.panel for r in fig3} == {f"{c}/{q}" for c in "ab" for q in ("velocity", "period", "amplitude")}
    assert all(r.outcome == "completed" for r in fig3)
    run = solve_exact(case_b, -3.0, n_cycles=4)  # the amplitudes a scene may plot, on a run of its own
    assert len(h0 := step1_amplitudes(run)) == 5 and h0[0] == pytest.approx(3.0, rel=1e-14)
    assert len(largest_abs_per_cycle(run)) == 4


def test_shock_window_draws_the_velocity_before_and_after_the_impact():
    """From -1 m (K = 1, F = 1): x = -cos t meets a1 at t = acos(0.1) with v = sqrt(0.99); the
    acceleration is -x = 0.1 before it and 0.1 + F/M = 1.1 after."""
    windows = {"velocity": (0.0, 1.5), "acceleration": (1.0, 1.5)}
    readings = fig4_readings(MODEL, {"a": {"F": 1.0, "x0": 1.0}}, windows, 100, K_values=(1.0,))
    assert len(readings) == 2 * 2 * 2  # two release sides, two pairings of the windows, two panels
    v = by_name(readings, "velocity", "x0 = -1 m", "velocity 0-1.5 s")
    t1 = math.acos(0.1)
    at_impact = v.y[np.isclose(v.x, t1, rtol=0, atol=1e-12)]
    np.testing.assert_allclose(at_impact, [math.sqrt(0.99), 0.9 * math.sqrt(0.99)], rtol=1e-12)
    assert v.y.max() == pytest.approx(math.sqrt(0.99), rel=1e-12)
    assert v.y.min() == pytest.approx(0.0, abs=1e-15)
    # swapped: the acceleration over the velocity's window, under the same name in both panels
    a = by_name(readings, "acceleration", "x0 = -1 m", "acceleration 0-1.5 s")
    assert any(r.panel == "velocity" and r.name == a.name for r in readings)
    np.testing.assert_allclose(a.y[np.isclose(a.x, t1, rtol=0, atol=1e-12)], [0.1, 1.1], rtol=1e-12)
    assert (a.y.min(), a.y.max()) == (pytest.approx(0.1, rel=1e-12), pytest.approx(1.1, rel=1e-12))


def test_fig4_crosses_every_force_with_every_release_magnitude():
    readings = fig4_readings(MODEL, CASES, {"velocity": (0.0, 2.0), "acceleration": (0.5, 1.5)}, 20, K_values=(1, 10))
    assert {r.name.split(";")[0] for r in readings} == {f"F = {F} N, x0 = {x0} m, K = {K} N/m" for F in ("1", "0.5")
                                                       for x0 in ("+1", "-1", "+3", "-3") for K in ("1", "10")}
    assert len(readings) == 2 * 2 * 2 * 2 * 2 * 2  # F x |x0| x side x K x pairing x panel


def test_the_mirror_image_read_at_the_mirrored_section_plots_the_same_values(fig3):
    """Symmetric geometry: the run from +x0 is the run from -x0 with x -> -x, a1 <-> a3, so every
    quantity read at a3 from +x0 is the one read at a1 from -x0."""
    for r in fig3:
        if r.name.startswith("from +x0, section a3"):
            twin = next(m for m in fig3 if m.panel == r.panel
                        and m.name == r.name.replace("from +x0, section a3", "from -x0, section a1")
                        .replace("left turning point", "RIGHT").replace("right turning point", "left turning point |x|")
                        .replace("RIGHT |x|", "right turning point"))
            np.testing.assert_allclose(r.y, twin.y, rtol=1e-12)


def test_the_right_turning_point_of_cycle_n_plus_1_is_h0_of_the_mirror_run(fig3):
    """Free flight from a2 to the right turning point is centred at 0: its amplitude is the turning point, and h0
    of the mirror run (from +x0, read at a1) is the same free arc's mirror."""
    right = by_name(fig3, "b/amplitude", "from -x0, section a1", "right turning point", count="k = 1..N+1")
    v = velocities(math.sqrt(9.0 - A1**2), N + 1, f=0.5)
    expected = [math.hypot(A2, cycle_by_energy(vk, 1.0, 0.5)["v2"]) for vk in v[:-1]]
    np.testing.assert_allclose(right.y, expected, rtol=1e-12)
    assert len(right.y) == N + 1
    mirror = by_name(fig3, "b/amplitude", "from +x0, section a1", "Step-1", count="k = 1..N+1")
    np.testing.assert_allclose(mirror.y, right.y, rtol=1e-12)


def test_every_run_is_made_once_for_all_figures_and_one_that_left_the_regime_takes_its_needs_stated_again():
    settings = {"model": MODEL, "fig3": {"n_cycles": 3, "cases": CASES},
                "fig4": {"velocity_window": [0.0, 4.0], "acceleration_window": [1.0, 3.0], "samples_per_second": 20},
                "fig5": {"K": [0.1, 1.0, 10.0], "n_cycles": 2, "samples_per_period": 20}}
    runs = Runs(MODEL)
    readings = all_readings(settings, runs)
    # (F, K, x0): Fig. 5's 3 K x 2 F x 4 x0 hold Fig. 4's (the same F, |x0| and K) and Fig. 3's (K = 1)
    assert runs.solved == 3 * 2 * 4
    assert all(r.outcome == "completed" for r in readings)
    with pytest.raises(ValueError, match="already made"):
        runs.need(1.0, 1.0, -1.0, n_cycles=500)
    # released inside the impact positions (|x0| < 0.1 m) the escapement never starts: the run stops at once,
    # holds no cycle, and stating the same need again is no new need
    runs.need(1.0, 1.0, 0.05, n_cycles=3)
    assert runs.outcome(1.0, 1.0, 0.05, n_cycles=3).startswith("stopped")
    runs.need(1.0, 1.0, 0.05, n_cycles=3)
    runs.need(1.0, 1.0, 0.05, n_cycles=2)
    with pytest.raises(ValueError, match="already made"):
        runs.need(1.0, 1.0, 0.05, n_cycles=4)
    assert runs.solved == 3 * 2 * 4 + 1


@pytest.fixture(scope="module")
def fig5():
    return fig5_readings(MODEL, {"b": 1.0, "c": 10.0}, 60, 50, forces=(0.5,), releases=(-1.0, 1.0))


def test_the_whole_phase_trajectory_k10_spans_the_first_cycle_and_the_last_cycle_is_the_limit_cycle(fig5):
    """K = 10, F = 0.5, from -1 m: speeds only fall after the first cycle (the map contracts to v* < sqrt(9.9));
    the fastest point is a1 before the first impact, the most negative a3 before the second; x runs from -1 to the
    first right turning point. K = 1: the fixed point of v**2 -> (1-b)**4 v**2 + 2 f (a2 - a1)(b**2 - 2b + 2); the
    fastest point of the limit cycle is a2 (the zone's force ends there)."""
    r = by_name(fig5, "c", "x0 = -1 m", "whole trajectory")
    w2, f = 10.0, 0.5
    first = cycle_by_energy(math.sqrt(w2 * (1.0 - A1**2)), w2, f)
    assert r.y.max() == pytest.approx(math.sqrt(9.9), rel=1e-12)
    assert r.y.min() == pytest.approx(-first["v4"], rel=1e-12)
    assert r.x.min() == pytest.approx(-1.0, rel=1e-14)
    assert r.x.max() == pytest.approx(math.hypot(A2, first["v2"] / math.sqrt(w2)), rel=1e-12)
    mirror = by_name(fig5, "c", "x0 = +1 m", "whole trajectory")
    assert (mirror.y.min(), mirror.y.max()) == (pytest.approx(-r.y.max(), rel=1e-12),
                                                pytest.approx(-r.y.min(), rel=1e-12))
    v_star = math.sqrt(2 * f * (A2 - A1) * (B**2 - 2 * B + 2) / (1 - (1 - B) ** 4))
    v2 = cycle_by_energy(v_star, 1.0, f)["v2"]
    r = by_name(fig5, "b", "x0 = -1 m", "last cycle")
    assert r.y.max() == pytest.approx(v2, rel=1e-9)
    assert r.y.min() == pytest.approx(-v2, rel=1e-9)
    assert r.x.max() == pytest.approx(math.hypot(A2, v2), rel=1e-9)


def test_critical_times_are_turning_points_or_passages_through_the_centre(case_b):
    run = solve_exact(case_b, -1.0, n_cycles=5)
    t = critical_times(run, 0.0, run.t_final)
    assert t[0] == 0.0  # the release is a turning point
    assert np.all(np.diff(t) > 0)
    _, v, a = run.sample(t)
    # at each: v = 0 (turning point) or a = 0 (the centre of the arc, where |v| peaks)
    assert np.all(np.minimum(np.abs(v), np.abs(a)) < 1e-12)
    # per cycle the two turning points only: the free arcs' centre 0 lies inside the impulse zones,
    # and the zones' centres +-F/K = +-0.5 m lie beyond them; the release adds one
    assert len(t) == 2 * 5 + 1


@pytest.mark.parametrize(("call", "message"), [
    (lambda: fig3_readings({}, {}, 0), "n_cycles = 0 is invalid: n_cycles must be a positive integer"),
    (lambda: all_readings({"model": {}}), r"it must have \['fig3', 'fig4', 'fig5'\]"),
    (lambda: fig4_readings({}, {}, {"v": (0, 1)}, 1.0), "it must have 'velocity' and 'acceleration'"),
    (lambda: Runs({}).need(1, 1, 1, t_end=float("nan")), "t_end = nan is invalid: t_end must be finite"),
    (lambda: Runs({}).need(1, 1, 1, n_cycles=1.5), "n_cycles = 1.5 is invalid"),
])
def test_the_readings_refuse_bad_arguments_before_any_run(call, message):
    with pytest.raises(ValueError, match=message):
        call()
