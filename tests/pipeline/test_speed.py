"""The speed job on a small workload: one row per ratio, the columns of the table, and the headline's and the
per-cycle rows timed on an injected clock, so that their times and ratios are known by hand (the floors' rows
are measured for real, and their ratios tested on an injected clock in tests/benchmarks/test_floor.py)."""

import math
from types import SimpleNamespace

from benchmarks.floor import floor_rows

from escapement.io.netcdf import read_csv
from escapement.pipeline.studies import run_speed
from escapement.studies import benchmark
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
    return read_csv(out, SPEED_COLUMNS), read_csv(head, WORK_PRECISION_COLUMNS)


def _durations(monkeypatch, durations):
    """Each run the benchmark times takes the next of ``durations`` (s), read off a clock the test sets."""
    remaining, now, readings = list(durations), [0.0], [0]

    def clock():
        readings[0] += 1
        if readings[0] % 2 == 0:  # the end of a run
            now[0] += remaining.pop(0)
        return now[0]

    monkeypatch.setattr(benchmark, "time", SimpleNamespace(perf_counter=clock))
    return remaining


def test_the_speed_table_has_a_row_per_ratio(tmp_path, monkeypatch):
    # timed in this order, one run each: the headline's exact solver 2 s, closed form 0.5 s, DOP853 at rtol 1e-3
    # 0.25 s and at 1e-12 4 s; then per cycle, the exact solver and the closed form on 50 and 20 cycles (the
    # floors' sizes, 50, among them once)
    left = _durations(monkeypatch, [2.0, 0.5, 0.25, 4.0, 1.0, 0.25, 3.0, 1.0])
    rows, headline = _run(tmp_path, 1e-9)
    assert left == []
    assert list(rows[0]) == SPEED_COLUMNS and list(headline[0]) == WORK_PRECISION_COLUMNS
    names = [r["name"] for r in rows]
    assert names[:2] == ["DOP853 rtol 1e-12 / solve_exact", "DOP853 rtol 1e-12 / closed-form cycles"]
    assert names.count("solve_exact / closed-form cycles") == 2
    assert sum(name.startswith("solve_exact") and name.endswith("/ minimal cycle loop") for name in names) == 3
    assert sum(name.startswith("solve_exact") and name.endswith("/ minimal event loop") for name in names) == 2
    assert sum(name.startswith("solve_ensemble / numpy loop") for name in names) == 2
    assert "solve_exact streamed / closed-form cycles streamed" in names
    assert "closed-form cycles streamed, peak memory against 100 cycles" in names
    # rtol 1e-3 misses the target (below), so DOP853 at 1e-12, 4 s, is compared: 4 / 2 and 4 / 0.5; per cycle,
    # the exact solver over the closed form: 1 / 0.25, 3 / 1
    timed = [(r["name"], int(r["n"]), float(r["ratio"]), float(r["time_s"]), float(r["reference_s"]))
             for r in rows[:4]]
    assert timed == [("DOP853 rtol 1e-12 / solve_exact", 20, 2.0, 4.0, 2.0),
                     ("DOP853 rtol 1e-12 / closed-form cycles", 20, 8.0, 4.0, 0.5),
                     ("solve_exact / closed-form cycles", 50, 4.0, 1.0, 0.25),
                     ("solve_exact / closed-form cycles", 20, 3.0, 3.0, 1.0)]
    assert all(float(r["ratio"]) > 0 for r in rows[4:])  # the floors, measured
    # the candidates: rtol 1e-3 misses 1e-9 in the impact time, 1e-12 reaches it
    by_setting = {(r["method"], r["setting"]): r for r in headline}
    loose, tight = by_setting[("DOP853", "0.001")], by_setting[("DOP853", "1e-12")]
    assert float(loose["error_time"]) > 1e-9 >= float(tight["error_time"])
    assert float(by_setting[("exact", "")]["error_time"]) < 1e-15


def test_no_candidate_reaching_the_target_is_said_so(tmp_path, monkeypatch):
    _durations(monkeypatch, [1.0] * 8)
    rows, _ = _run(tmp_path, 1e-30)
    assert math.isnan(float(rows[0]["ratio"])) and "no candidate setting reaches 1e-30" in rows[0]["note"]
