"""The speed job on a small workload: one row per ratio, the columns of the table, and ratios that are the
quotients of the times written beside them (the timings themselves are not asserted: they vary)."""

import csv
import math

from benchmarks.floor import floor_rows

from escapement.pipeline.studies import run_speed
from escapement.pipeline.tables import SPEED_COLUMNS, WORK_PRECISION_COLUMNS

SCENE = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05, "x0": 1.0,
         "min_seconds": 0.01, "max_repeats": 3}


def _speed(target: float) -> dict:
    return {"headline": {"n_cycles": 20, "target": target, "settings": {"DOP853": [1e-3, 1e-12]}},
            "floor": {"exact_cycles": [50], "ensemble_trajectories": 20, "ensemble_cycles": 5,
                      "stream_cycles": [100, 1000]}}


def _run(tmp_path, target):
    out, head = tmp_path / "speed.csv", tmp_path / "headline.csv"
    run_speed(SCENE, _speed(target), str(out), str(head), str(tmp_path / "speed.log"), floors=floor_rows)
    with open(out) as f, open(head) as g:
        return list(csv.DictReader(f)), list(csv.DictReader(g))


def test_the_speed_table_has_a_row_per_ratio(tmp_path):
    rows, headline = _run(tmp_path, 1e-9)
    assert list(rows[0]) == SPEED_COLUMNS and list(headline[0]) == WORK_PRECISION_COLUMNS
    names = [r["name"] for r in rows]
    assert names[:2] == ["DOP853 rtol 1e-12 / solve_exact", "DOP853 rtol 1e-12 / closed-form cycles"]
    assert names.count("solve_exact / closed-form cycles") == 3
    assert sum(name.startswith("solve_exact") and name.endswith("/ minimal cycle loop") for name in names) == 3
    assert sum(name.startswith("solve_exact") and name.endswith("/ minimal event loop") for name in names) == 2
    assert sum(name.startswith("solve_ensemble / numpy loop") for name in names) == 2
    assert "solve_exact streamed / closed-form cycles streamed" in names
    assert "closed-form cycles streamed, peak memory against 100 cycles" in names
    for r in rows:
        if "peak memory" in r["name"]:  # the memory rows
            assert math.isclose(float(r["ratio"]), float(r["bytes"]) / float(r["reference_bytes"]), rel_tol=1e-6)
        else:
            assert math.isclose(float(r["ratio"]), float(r["time_s"]) / float(r["reference_s"]), rel_tol=1e-6)
    # the candidates: rtol 1e-3 misses 1e-9 in the impact time, 1e-12 reaches it
    by_setting = {(r["method"], r["setting"]): r for r in headline}
    assert float(by_setting[("DOP853", "0.001")]["error_time"]) > 1e-9 >= float(by_setting[("DOP853", "1e-12")]["error_time"])
    assert float(by_setting[("exact", "")]["error_time"]) < 1e-15


def test_no_candidate_reaching_the_target_is_said_so(tmp_path):
    rows, _ = _run(tmp_path, 1e-30)
    assert math.isnan(float(rows[0]["ratio"])) and "no candidate setting reaches 1e-30" in rows[0]["note"]
