"""The score table of the readings against the printed axes, and the best reading per panel."""

from __future__ import annotations

import math
from pathlib import Path
from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal

import pytest
import yaml

from escapement.io.netcdf import read_csv
from escapement.paper.printed_axes import PANELS
from escapement.verdict.scores import Candidates
from escapement.pipeline.readings import COLUMNS, limits_match, score_readings, score_table
from escapement.verdict.scores import (DEFAULT_LOCATOR, PRINTED_STEP, best_readings_table, joint_candidates,
                                      panel_candidates, read_scores)
from escapement.plotting.autoscale import VARIANTS
from escapement.studies.readings import all_readings, fig3_readings, fig4_readings, fig5_readings

MODEL = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
CASES = {"a": {"F": 1.0, "x0": 1.0}, "b": {"F": 0.5, "x0": 3.0}}
VELOCITY_LEFT = "from -x0, section a1; speed before the impact; k = 1..N"
VELOCITY_RIGHT = "from +x0, section a1; speed before the impact; k = 1..N"
MIRROR_LEFT = "from +x0, section a3; speed before the impact; k = 1..N"


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
    printed_low, printed_high = 0.95, 1.3  # Fig. 3(a)'s velocity axis as printed
    rows = {(r["reading"], r["axis"]): r for r in fig3_rows
            if r["panel"] == "a/velocity" and r["autoscale"] == "round, margin 0" and r["ticks"] == PRINTED_STEP}
    for name, v1 in ((VELOCITY_LEFT, v_left), (VELOCITY_RIGHT, v_right)):
        low, high = _outward(v1, "0.05")[0], _outward(v_star, "0.05")[1]
        y = rows[(name, "y")]
        assert (y["low"], y["high"]) == (pytest.approx(low), pytest.approx(high))
        assert y["matches"] == int(low == printed_low) + int(high == printed_high)
        x = rows[(name, "x")]
        assert (x["low"], x["high"], x["matches"]) == (0, 50, 2)

    # the mirror image read at a3 plots the same values: one group, not a tie
    c = panel_candidates(fig3_rows)[("3", "a/velocity")]
    assert c.tied() == (4, [(MIRROR_LEFT, VELOCITY_LEFT)]) and c.out_of == 4


def test_a_margin_of_5_percent_moves_the_cycle_axis_off_0_to_50(fig3_rows):
    """[1, 50] widened by 0.05 * 49 on each side is [-1.45, 52.45]: ticks -10 and 60."""
    rows = [r for r in fig3_rows if r["axis"] == "x" and r["autoscale"] == "round, margin 0.05"
            and r["panel"].endswith("velocity") and r["ticks"] == PRINTED_STEP and r["reading"].endswith("1..N")]
    assert rows and all((r["low"], r["high"]) == (-10, 60) and r["matches"] == 0 for r in rows)


def test_the_step1_amplitude_has_51_points_and_reaches_the_printed_60(fig3_rows):
    """h0(k) for k = 1..51 puts the last point at 51: the cycle axis rounds out to 60."""
    rows = [r for r in fig3_rows if r["axis"] == "x" and r["autoscale"] == "round, margin 0"
            and r["panel"].endswith("amplitude") and r["ticks"] == PRINTED_STEP]
    assert rows
    for r in rows:
        assert r["matches"] == (2 if r["reading"].endswith("k = 1..N+1") else 1), r["reading"]


def test_one_row_per_reading_scored_axis_and_variant():
    readings = [
        *fig3_readings(MODEL, CASES, 4),
        *fig4_readings(MODEL, {"b": CASES["b"]}, {"velocity": (0.0, 3.0), "acceleration": (1.0, 2.0)}, 50,
                       K_values=(1.0,)),
        *fig5_readings(MODEL, {"a": 0.1, "b": 1.0, "c": 10.0}, 2, 40, forces=(0.5,), releases=(-1.0,)),
    ]
    rows = score_table(readings)
    scored = {(p.figure, p.name): [n for n, a in p.axes.items() if a.scored] for p in PANELS}
    expected = {(r.figure, r.panel, axis, r.name, v, t) for r in readings for axis in scored[(r.figure, r.panel)]
                for v in VARIANTS for t in (PRINTED_STEP, DEFAULT_LOCATOR)}
    keys = [(r["figure"], r["panel"], r["axis"], r["reading"], r["autoscale"], r["ticks"]) for r in rows]
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


def _rows(entries):
    """Synthetic score rows: (panel, reading, same_values_as, ticks, axis, matches), margin 0."""
    return [{"figure": "5", "panel": panel, "axis": axis, "reading": name, "autoscale": "round, margin 0",
             "ticks": ticks, "matches": m, "same_values_as": same}
            for panel, name, same, ticks, axis, m in entries]


def test_ties_reach_the_summary_as_ties_and_equivalents_group():
    p, d = PRINTED_STEP, DEFAULT_LOCATOR
    rows = _rows([
        ("b", "one", "one", p, "x", 2), ("b", "one", "one", p, "y", 2),
        ("b", "mirror of one", "one", p, "x", 2), ("b", "mirror of one", "one", p, "y", 2),
        ("b", "two", "two", p, "x", 2), ("b", "two", "two", p, "y", 2),
        ("b", "three", "three", p, "x", 2), ("b", "three", "three", p, "y", 1),
        ("b", "one", "one", d, "x", 1), ("b", "one", "one", d, "y", 2),
        ("b", "mirror of one", "one", d, "x", 1), ("b", "mirror of one", "one", d, "y", 2),
        ("b", "two", "two", d, "x", 0), ("b", "two", "two", d, "y", 2),
        ("b", "three", "three", d, "x", 2), ("b", "three", "three", d, "y", 2),
    ])
    c = panel_candidates(rows)[("5", "b")]
    assert c == Candidates(out_of=4, scores={"one": 4, "mirror of one": 4, "two": 4, "three": 3},
                           default_scores={"one": 3, "mirror of one": 3, "two": 2, "three": 4},
                           equivalent=(("one", "mirror of one"),))
    assert c.tied() == (4, [("one", "mirror of one"), ("two",)])
    (row,) = best_readings_table(rows)
    assert row["limits reproduced"] == "4 of 4 (4 with the default locator)"
    readings = row["best-supported readings"]
    assert "undetermined" in readings and "one = mirror of one<br>two" in readings


def test_one_group_of_equivalent_readings_is_not_a_tie():
    p = PRINTED_STEP
    rows = _rows([("c", "one", "one", p, "x", 2), ("c", "mirror", "one", p, "x", 2), ("c", "two", "two", p, "x", 1)])
    best, groups = panel_candidates(rows)[("5", "c")].tied()
    assert (best, groups) == (4 // 2, [("one", "mirror")])
    (row,) = best_readings_table(rows)
    assert "undetermined" not in row["best-supported readings"]


def test_a_joint_reading_is_scored_over_both_panels():
    p = PRINTED_STEP
    rows = [{**r, "figure": "4"} for r in _rows([
        ("velocity", "A", "A", p, "y", 1), ("acceleration", "A", "A", p, "y", 1),
        ("velocity", "B", "B", p, "y", 2), ("acceleration", "B", "B", p, "y", 0),
        ("velocity", "C", "C", p, "y", 0), ("acceleration", "C", "C", p, "y", 2),
    ])]
    c = joint_candidates(rows, "4")
    assert c.out_of == 4 and c.scores == {"A": 2, "B": 2, "C": 2}
    assert c.tied() == (2, [("A",), ("B",), ("C",)])


@pytest.fixture(scope="module")
def paper_rows():
    """The whole grid at the paper's settings (about a second)."""
    paper = yaml.safe_load((Path(__file__).resolve().parents[2] / "config/paper.yaml").read_text())
    return score_table(all_readings({key: paper[key] for key in ("model", "fig3", "fig4", "fig5")}))


def test_on_the_paper_grid_fig4_is_undetermined(paper_rows):
    """Several readings of Fig. 4 tie at the best joint score, and they differ in their choices."""
    best, groups = joint_candidates(paper_rows, "4").tied()
    assert best < 4  # no reading reaches the printed -0.1 .. 0.9 on both axes
    assert len(groups) > 1
    heads = {g[0].split(";")[0] for g in groups}
    assert len(heads) > 1  # not only the windows differ: the force, release or K do


def test_on_the_paper_grid_fig5_scores_depend_on_the_imposed_step(paper_rows):
    """Panel (a)'s printed limits (-5, 5; -1.5, 1.5) need the printed step. By hand, K = 0.1, F = 1:
    the limit cycle has v*^2 = C / (1 - (1-b)^4), C = 2 f (a2 - a1)(b^2 - 2b + 2) = 0.543, so
    v* = 1.2566; through the zone v2^2 = (0.9 v*)^2 + w^2 (a1^2 - a2^2) + 2 f (a2 - a1) = 1.5797, and
    the right turning point is hypot(a2, v2 / w) = 3.9749 m (w^2 = 0.1), approached from inside: a
    step of 5 rounds it to +-5, matplotlib's own step of 1 to +-4."""
    c = panel_candidates(paper_rows)
    assert c[("5", "a")].tied()[0] == 4
    assert max(c[("5", "a")].default_scores.values()) < 4
    rows = {(r["axis"], r["ticks"]): r for r in paper_rows if r["panel"] == "a" and r["figure"] == "5"
            and r["reading"] == "F = 1 N, x0 = -1 m; whole trajectory, 60 cycles"
            and r["autoscale"] == "round, margin 0"}
    assert rows[("x", PRINTED_STEP)]["data_max"] == pytest.approx(3.9749, abs=2e-4)
    assert (rows[("x", PRINTED_STEP)]["low"], rows[("x", PRINTED_STEP)]["high"]) == (-5.0, 5.0)
    assert (rows[("x", DEFAULT_LOCATOR)]["low"], rows[("x", DEFAULT_LOCATOR)]["high"]) == (-4.0, 4.0)


def test_the_job_writes_the_table_and_logs_the_best(tmp_path):
    settings = {
        "model": MODEL,
        "fig3": {"n_cycles": 3, "cases": CASES},
        "fig4": {"velocity_window": [0.0, 4.0], "acceleration_window": [1.0, 3.0], "samples_per_second": 20},
        "fig5": {"K": [0.1, 1.0, 10.0], "n_cycles": 2, "samples_per_period": 20},
    }
    out, log = tmp_path / "readings" / "axis_scores.csv", tmp_path / "score_readings.log"
    score_readings(str(out), str(log), settings)
    rows = read_csv(out, COLUMNS)
    assert rows and list(rows[0]) == COLUMNS
    assert {(r["figure"], r["panel"]) for r in rows} == {(p.figure, p.name) for p in PANELS}
    text = log.read_text()
    assert "Fig. 3 a/velocity" in text and "Fig. 4, both panels" in text and "score_readings done" in text
    table = read_scores(str(out))
    assert {r["ticks"] for r in table} == {PRINTED_STEP, DEFAULT_LOCATOR}
    assert set(panel_candidates(table)) == {(p.figure, p.name) for p in PANELS}
