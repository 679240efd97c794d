"""The score table of the readings against the printed axes, and the best reading per panel."""

from __future__ import annotations

import csv
import math
from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal

import pytest

from escapement.paper.printed_axes import PANELS
from escapement.pipeline.readings import COLUMNS, best_readings, limits_match, score_readings, score_table
from escapement.plotting.autoscale import VARIANTS
from escapement.studies.readings import fig3_readings, fig4_readings, fig5_readings

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
CASES = {"a": {"F": 1.0, "x0": 1.0}, "b": {"F": 0.5, "x0": 3.0}}
VELOCITY_LEFT = "release -x0; velocity before the impact at a1"
VELOCITY_RIGHT = "release +x0; velocity before the impact at a1"


@pytest.fixture(scope="module")
def fig3_rows():
    return score_table(fig3_readings(MODEL, CASES, 50))


def _outward(value: float, step: str) -> tuple[float, float]:
    """``value`` rounded down and up to multiples of ``step`` (decimal arithmetic)."""
    q = Decimal(repr(value)) / Decimal(step)
    return (float(q.to_integral_value(ROUND_FLOOR) * Decimal(step)),
            float(q.to_integral_value(ROUND_CEILING) * Decimal(step)))


def test_fig3a_velocity_axis_scores_derived_on_paper(fig3_rows):
    """Case (a), K = M = 1, b = 0.1, F = 1. The map v**2 -> (1-b)**4 v**2 + C, C = 2 f (a2 - a1)
    (b**2 - 2b + 2), is increasing with fixed point v* = sqrt(C / (1 - (1-b)**4)) = 1.2566; from
    below, the velocities rise towards it, so the axis spans [v1, v*) rounded out by 0.05. From
    -1 m, v1 = sqrt(0.99) = 0.995: [0.95, 1.3], both printed limits. From +1 m, v1 = 1.0497 (the
    impact at a3 first): [1.0, 1.3], the upper one only. Cycles 1..50 on a step of 10: [0, 50].
    """
    b, f, a1, a2 = 0.1, 1.0, -0.1, 0.05
    c = 2 * f * (a2 - a1) * (b**2 - 2 * b + 2)
    v_star = math.sqrt(c / (1 - (1 - b) ** 4))
    v_left = math.sqrt(0.99)
    v4p = (1 - b) * math.sqrt(1 - 0.1**2)
    v_right = math.sqrt(v4p**2 + (0.1**2 - 0.05**2) + 2 * f * 0.15 + 0.05**2 - 0.1**2)
    assert 1.25 < v_star < 1.3
    expected = {}
    for name, v1 in ((VELOCITY_LEFT, v_left), (VELOCITY_RIGHT, v_right)):
        low, high = _outward(v1, "0.05")[0], _outward(v_star, "0.05")[1]
        expected[name] = int(low == 0.95) + int(high == 1.3)
    assert expected == {VELOCITY_LEFT: 2, VELOCITY_RIGHT: 1}

    rows = {(r["reading"], r["axis"]): r for r in fig3_rows
            if r["panel"] == "a/velocity" and r["autoscale"] == "round, margin 0"}
    for name, matches in expected.items():
        assert rows[(name, "y")]["matches"] == matches
        assert rows[(name, "x")]["matches"] == 2
    assert rows[(VELOCITY_LEFT, "y")]["low"] == pytest.approx(0.95)
    assert rows[(VELOCITY_RIGHT, "y")]["low"] == pytest.approx(1.0)

    best = {b["panel"]: b for b in best_readings(fig3_rows) if b["figure"] == "3"}
    assert best["a/velocity"]["best"] == [(VELOCITY_LEFT, "round, margin 0")]
    assert (best["a/velocity"]["score"], best["a/velocity"]["out_of"]) == (4, 4)


def test_a_margin_of_5_percent_moves_the_cycle_axis_off_0_to_50(fig3_rows):
    """[1, 50] widened by 0.05 * 49 on each side is [-1.45, 52.45]: ticks -10 and 60."""
    rows = [r for r in fig3_rows if r["axis"] == "x" and r["autoscale"] == "round, margin 0.05"
            and r["panel"].endswith("velocity")]
    assert rows and all((r["low"], r["high"]) == (-10, 60) and r["matches"] == 0 for r in rows)


def test_the_step1_amplitude_has_51_points_and_reaches_the_printed_60(fig3_rows):
    """h0(k) for k = 1..51 puts the last point at 51: the cycle axis rounds out to 60."""
    rows = [r for r in fig3_rows if r["axis"] == "x" and r["autoscale"] == "round, margin 0"
            and r["panel"].endswith("amplitude")]
    for r in rows:
        assert r["matches"] == (2 if "h0(k), k = 1..N+1" in r["reading"] else 1), r["reading"]


def test_one_row_per_reading_scored_axis_and_variant():
    readings = [
        *fig3_readings(MODEL, CASES, 4),
        *fig4_readings(MODEL, {"b": CASES["b"]}, {"velocity": (0.0, 3.0), "acceleration": (1.0, 2.0)}, 50,
                       K_values=(1.0,)),
        *fig5_readings(MODEL, {"a": 0.1, "b": 1.0, "c": 10.0}, 2, 40, forces=(0.5,), releases=(-1.0,)),
    ]
    rows = score_table(readings)
    scored = {(p.figure, p.name): [n for n, a in p.axes.items() if a.scored] for p in PANELS}
    expected = {(r.figure, r.panel, axis, r.name, v) for r in readings for axis in scored[(r.figure, r.panel)]
                for v in VARIANTS}
    keys = [(r["figure"], r["panel"], r["axis"], r["reading"], r["autoscale"]) for r in rows]
    assert len(keys) == len(set(keys)) == len(expected)
    assert set(keys) == expected
    assert {(r["figure"], r["panel"]) for r in rows} == set(scored)
    assert all(r["matches"] in (0, 1, 2) for r in rows)
    assert all(r["low"] <= r["data_min"] and r["data_max"] <= r["high"] for r in rows)


def test_limits_match_counts_each_limit_to_a_billionth_of_the_step():
    assert limits_match(0.9500000000000001, 1.3, 0.95, 1.3, 0.05) == 2
    assert limits_match(1.0, 1.3, 0.95, 1.3, 0.05) == 1
    assert limits_match(1.0, 1.35, 0.95, 1.3, 0.05) == 0
    assert limits_match(6.2830001, 6.2846, 6.283, 6.2846, 0.0002) == 1


def test_best_readings_keeps_ties_and_can_be_restricted_to_one_variant():
    rows = [
        {"figure": "5", "panel": "b", "axis": axis, "reading": name, "autoscale": variant, "matches": m}
        for name, variant, axis, m in [
            ("one", "round, margin 0", "x", 2), ("one", "round, margin 0", "y", 2),
            ("two", "round, margin 0", "x", 2), ("two", "round, margin 0", "y", 2),
            ("one", "round, margin 0.05", "x", 2), ("one", "round, margin 0.05", "y", 1),
        ]
    ]
    (best,) = best_readings(rows)
    assert best["best"] == [("one", "round, margin 0"), ("two", "round, margin 0")]
    assert (best["score"], best["out_of"]) == (4, 4)
    (best,) = best_readings(rows, autoscale="round, margin 0.05")
    assert best["best"] == [("one", "round, margin 0.05")] and best["score"] == 3


def test_the_job_writes_the_table_and_logs_the_best(tmp_path):
    settings = {
        "model": MODEL,
        "fig3": {"n_cycles": 3, "cases": CASES},
        "fig4": {"velocity_window": [0.0, 4.0], "acceleration_window": [1.0, 3.0], "samples_per_second": 20},
        "fig5": {"K": [0.1, 1.0, 10.0], "n_cycles": 2, "samples_per_period": 20},
    }
    out, log = tmp_path / "readings" / "axis_scores.csv", tmp_path / "score_readings.log"
    score_readings(str(out), str(log), settings)
    with open(out, newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert rows and list(rows[0]) == COLUMNS
    assert {(r["figure"], r["panel"]) for r in rows} == {(p.figure, p.name) for p in PANELS}
    text = log.read_text()
    assert "Fig. 3 a/velocity" in text and "score_readings done" in text
