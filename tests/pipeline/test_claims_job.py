"""The check_claims job on tiny netCDF files (the claims table, and the axis limits beside it), and the claims
table's CSV round trip."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import xarray as xr
import yaml

from escapement.io.netcdf import DatasetError, read_csv, write_csv, write_netcdf
from escapement.pipeline.claims import check_claims
from escapement.pipeline.readings import _formatted, score_table
from escapement.pipeline.tables import LIMIT_COLUMNS, read_claims
from escapement.studies.readings import Reading
from escapement.verdict import sec3_map
from escapement.verdict.engine import ClaimError
from escapement.verdict.rule import COLUMNS
from escapement.verdict.scores import COLUMNS as SCORE_COLUMNS

#: the model's parameters and x0 as 0-d variables, as the scenes write them; the outcome as attributes
MODEL = {k: ((), v) for k, v in {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1,
                                 "a4": -0.05, "x0": 1.0}.items()}
OUTCOME = {"outcome": "completed", "outcome_message": "completed 2 cycles"}
# x1^2 = 0.3 f / 0.19 for f = 1: the fixed point of the map x1(k+1)^2 = 0.6561 x1(k)^2 + 0.543 f
FIXED_POINT = (0.3 / 0.19) ** 0.5


def files(tmp_path) -> dict:
    cycles = {"velocity_before_impact": FIXED_POINT, "period": 6.3, "largest_displacement": 1.2}
    fig3 = xr.Dataset(
        {**{k: ("cycle", np.full(2, v)) for k, v in cycles.items()},
         "event_time": ("event", np.arange(9.0)), "event_kind": ("event", np.array([1, 2, 3, 4] * 2 + [1], np.int8)),
         "event_velocity_before": ("event", np.zeros(9)), "event_velocity_after": ("event", np.zeros(9)), **MODEL},
        coords={"cycle": [1, 2]}, attrs=OUTCOME,
    )
    fig4 = xr.Dataset(
        {"velocity": ("t", np.zeros(3)), "acceleration": ("t", np.zeros(3)), "velocity_before": ("impact", [1.0]),
         "impulse": ("impact", [-0.1]), "energy_dissipated": ("impact", [0.095]),
         "velocity_window": ("window_edge", [80.0, 82.0]), "acceleration_window": ("window_edge", [80.0, 82.0]),
         **MODEL},
        coords={"t": [80.0, 81.0, 82.0]}, attrs=OUTCOME,
    )
    # a phase ellipse of 0.9 m by 0.95 m/s: with Fig. 5 (b)'s tick steps (0.5 m, 0.2 m/s) its axes round out to
    # the printed -1 .. 1 and -1 .. 1
    phase = np.linspace(0.0, 2.0 * np.pi, 9)
    fig5 = xr.Dataset(
        {"displacement": ("t", 0.9 * np.cos(phase)), "velocity": ("t", -0.95 * np.sin(phase)),
         "impact_time": ("impact", [1.0]), **{k: ("cycle", np.full(2, v)) for k, v in cycles.items()}, **MODEL},
        coords={"t": phase}, attrs=OUTCOME,
    )
    runs = xr.Dataset(
        {"label": ("case", ["p"]), "group": ("case", ["paper"]), "outcome": ("case", ["completed"]),
         "outcome_message": ("case", ["completed"]),
         **{k: ("case", [v]) for k, v in {"F": 1.0, "b": 0.1, "x0": 1.0, "velocity": FIXED_POINT, "period": 6.3,
                                            "multiplier": 0.6561, "multiplier_eq21": 0.6561}.items()}},
    )
    paths = {"fig3": tmp_path / "case_first.nc", "fig4": tmp_path / "shock.nc", "fig5": tmp_path / "K_1.nc",
             "checks": tmp_path / "checks.nc"}
    for ds, path in zip((fig3, fig4, fig5, runs), paths.values()):
        write_netcdf(ds, path)
    register = tmp_path / "claims.yaml"
    weight = {"origin": "paper", "quote": "a sentence"}
    claims = [
        {"id": "fixed_point_first", "source": "Eq. (19)", **weight, "part": "the first", "statement": "s",
         "paper_value": None, "tolerance": 1e-8, "tolerance_reason": "r", "check": "sec3_map.fixed_point",
         "args": {"case": "first"}},
        {"id": "multiplier", "source": "Eq. (21)", **weight, "part": "the multiplier", "statement": "s",
         "paper_value": 0.6561, "tolerance": 1e-8, "tolerance_reason": "r", "check": "sec3_map.multiplier_paper_cases",
         "args": {"runs": "paper"}},
        {"id": "fig5b_axes", "source": "Fig. 5 (b)", "origin": "paper", "quote": "Fig. 5.", "statement": "s",
         "paper_value": None, "tolerance": None, "check": "figure_axes.printed_axes",
         "args": {"figure": "5", "panel": "b"}},
    ]
    register.write_text(yaml.safe_dump({"version": 3, "claims": claims}))
    # the grid of candidate readings of Fig. 5 (b): the same ellipse, and one twice as large (-2 .. 2 on both axes)
    readings = [Reading("5", "b", "as simulated", 0.9 * np.cos(phase), -0.95 * np.sin(phase)),
                Reading("5", "b", "twice as large", 1.8 * np.cos(phase), -1.9 * np.sin(phase))]
    scores = tmp_path / "axis_scores.csv"
    write_csv([_formatted(r) for r in score_table(readings)], SCORE_COLUMNS, scores)
    return {"register": str(register), "fig3": {"first": str(paths["fig3"])}, "fig4": str(paths["fig4"]),
            "fig5": {"1": str(paths["fig5"])}, "checks": str(paths["checks"]), "readings": str(scores),
            "limits": str(tmp_path / "panel_limits.csv")}


def test_the_job_writes_one_row_per_claim_with_the_configured_label_and_the_limits_its_axis_claim_judged(tmp_path):
    output, inputs = tmp_path / "claims.csv", files(tmp_path)
    check_claims(**inputs, output=str(output), log=str(tmp_path / "log"),
                 settings={"checks": {"n_cycles": 2, "paper": {"from": "fig3"}}})
    rows = read_claims(output)
    assert [r["claim_id"] for r in rows] == ["fixed_point_first", "multiplier", "fig5b_axes"]
    # the axes were fitted: a match is consistent, not reproduced; the first two rows are parts of one sentence
    assert [r["status"] for r in rows] == ["reproduced", "reproduced", "consistent"]
    assert [r["finding"] for r in rows] == ["fixed_point_first", "fixed_point_first", "fig5b_axes"]
    assert rows[0]["replicated_value"] == "1.256561725 m/s at cycle 2"
    # the job autoscaled the Fig. 5 output itself (matplotlib, the printed tick steps), and read the grid's scores
    assert rows[2]["replicated_value"].startswith(
        "Displacement (m): [-1, 1]; Velocity (m/s): [-1, 1] (4 of 4 printed limits); best of the 2 candidate "
        "readings: 4 of 4, by one reading [as simulated]")
    # the same limits as numbers, one row per scored axis of the panel the claim's args name
    assert [(r["claim_id"], r["figure"], r["panel"], r["axis"], float(r["low"]), float(r["high"]))
            for r in read_csv(inputs["limits"], LIMIT_COLUMNS)] == [("fig5b_axes", "5", "b", "x", -1.0, 1.0),
                                                                   ("fig5b_axes", "5", "b", "y", -1.0, 1.0)]


def test_the_job_fails_naming_the_claim_when_a_check_raises(tmp_path, monkeypatch):
    def broken(claim, ev):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(sec3_map, "multiplier_paper_cases",
                        dataclasses.replace(sec3_map.multiplier_paper_cases, function=broken))
    output, log = tmp_path / "claims.csv", tmp_path / "log"
    with pytest.raises(ClaimError, match="claim 'multiplier'.*ZeroDivisionError") as info:
        check_claims(**files(tmp_path), output=str(output), log=str(log))
    assert isinstance(info.value.__cause__, ZeroDivisionError)
    assert not output.exists()
    assert "claim 'multiplier'" in log.read_text()


ROWS = [
    {"claim_id": "x", "source": "Eq. (1)", "origin": "paper", "quote": "It is, \"said\".", "part": "", "finding": "x",
     "evidence": "independent", "statement": 's, with "quotes"', "readings": "as stated: holds",
     "paper_value": "[0.5, 3]", "replicated_value": "a: 1, b: 2", "tolerance": "", "status": "reproduced",
     "note": "line\nbreak"},
    {"claim_id": "y", "source": "Fig. 2", "origin": "beyond", "quote": "", "part": "", "finding": "",
     "evidence": "fitted", "statement": "s", "readings": "in s: fails; per cycle: holds", "paper_value": "6.2832",
     "replicated_value": "6.2957 s", "tolerance": "5e-05", "status": "undetermined", "note": ""},
]


def test_csv_round_trip(tmp_path):
    path = tmp_path / "claims.csv"
    write_csv(ROWS, COLUMNS, path)
    assert path.read_text().splitlines()[1] == ",".join(COLUMNS)  # under the line of its row count and digest
    assert read_claims(path) == ROWS


def test_csv_with_other_columns_is_rejected(tmp_path):
    path = tmp_path / "bad.csv"
    write_csv([{"a": 1, "b": 2}], ["a", "b"], path)
    with pytest.raises(DatasetError, match="bad.csv: not a table with the columns"):
        read_claims(path)
