"""The axis claims: a printed panel's claim holds when the best reading of the whole grid gives every printed
limit (a match under a fitted reading is only consistent), and a tie between readings that plot different values is
reported as a tie; the autoscaled limits and the scores are given, the printed limits written out here by hand.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from escapement.verdict import engine as cl
from escapement.verdict.evidence import Evidence
from escapement.verdict.scores import Candidates
from verdict.test_check_boundaries import DONE, scalars


def _ds(K: float = 1.0, **extra) -> xr.Dataset:
    return xr.Dataset({**scalars(K=K, F=0.5), **extra}, attrs=DONE)


def _evidence(axes: dict, readings: dict | None = None, fig5_K=(0.1, 1.0, 10.0)) -> Evidence:
    amplitude = xr.DataArray(np.ones(3), dims="amplitude_cycle")
    fig3 = {c: _ds(amplitude_h0=amplitude).assign_attrs(amplitude_variable="amplitude_h0") for c in ("a", "b")}
    return Evidence(fig3=fig3, fig4=_ds(K=0.1), fig5={f"{k:g}": _ds(K=k) for k in fig5_K}, checks=_ds(), axes=axes,
                    readings=readings or {})


def _claim(figure: str, panel: str) -> dict:
    return {"id": f"fig{figure}_{panel}", "source": "S", "origin": "paper", "quote": "q", "statement": "s",
            "paper_value": None, "readings": [{"reading": "as stated", "check": "figure_axes.printed_axes",
                                               "tolerance": None, "args": {"figure": figure, "panel": panel}}]}


def _row(figure: str, panel: str, limits: dict, scores: dict, **candidates) -> dict:
    ev = _evidence({(figure, panel): limits}, {(figure, panel): Candidates(2 * len(limits), scores, **candidates)})
    return cl.evaluate([_claim(figure, panel)], ev)[0]


@pytest.mark.parametrize(
    "figure, panel, limits, best, status",
    [
        # Fig. 3 (a) velocity: printed cycles 0-50, velocity 0.95-1.3 by 0.05; 4 of 4 by a fitted reading
        ("3", "a/velocity", {"x": (0.0, 50.0), "y": (0.95, 1.3)}, 4, "consistent"),
        # a limit missed by every reading of the grid: a failure under readings the project chose, no verdict
        ("3", "a/velocity", {"x": (0.0, 50.0), "y": (1.0, 1.3)}, 3, "undetermined"),
        ("3", "a/period", {"x": (0.0, 50.0), "y": (6.2956, 6.3044)}, 2, "undetermined"),
        ("3", "b/amplitude", {"x": (0.0, 50.0), "y": (0.5, 3.0)}, 3, "undetermined"),
        # Fig. 4: only the value axes are scored (the time axes are the printed windows), no cycle axis
        ("4", "velocity", {"y": (0.1, 0.9)}, 1, "undetermined"),
        ("4", "acceleration", {"y": (-1.0, 1.0)}, 0, "undetermined"),
        ("5", "c", {"x": (-1.0, 1.0), "y": (-3.0, 4.0)}, 4, "consistent"),
    ],
)
def test_the_status_is_the_best_readings_of_the_grid_weighed_as_fitted(figure, panel, limits, best, status):
    row = _row(figure, panel, limits, {"adopted": best, "other": 0})
    assert (row["status"], row["evidence"]) == (status, "fitted")


def test_a_better_reading_elsewhere_in_the_grid_decides_the_status_not_the_adopted_one():
    row = _row("3", "a/velocity", {"x": (0.0, 50.0), "y": (1.0, 1.3)}, {"adopted": 3, "better": 4})
    assert row["status"] == "consistent"
    value = row["replicated_value"]
    assert "(3 of 4 printed limits)" in value and "4 of 4, by one reading [better]" in value


def test_a_tie_between_different_readings_is_named_and_equivalent_readings_count_once():
    row = _row("4", "velocity", {"y": (0.1, 0.9)}, {"A": 1, "B": 1, "C": 0, "D": 1},
               equivalent=(("A", "D"),))
    assert "a tie of 2 readings that plot different values, so the reading is undetermined: [A = D], [B]" in (
        row["replicated_value"])
    assert row["status"] == "undetermined"  # fails under the readings the project chose only
    one = _row("4", "velocity", {"y": (0.1, 0.9)}, {"A": 1, "D": 1, "C": 0}, equivalent=(("A", "D"),))
    assert "by one reading [A = D]" in one["replicated_value"] and "undetermined" not in one["replicated_value"]


def test_the_tie_groups_only_the_tied_members_of_an_equivalence_group():
    best, groups = Candidates(4, {"A": 4, "B": 2, "C": 4}, equivalent=(("A", "B"),)).tied()
    assert best == 4 and groups == [("A",), ("C",)]


def test_the_default_locators_score_is_reported_beside_the_imposed_steps():
    row = _row("5", "a", {"x": (-5.0, 5.0), "y": (-1.5, 1.5)}, {"r": 4}, default_scores={"r": 2, "s": 3})
    assert "with the plotting program's own tick step the best is 3 of 4" in row["note"]


def test_the_row_gives_the_printed_and_the_autoscaled_limits_and_the_reading():
    row = _row("5", "a", {"x": (-5.0, 5.0), "y": (-1.5, 1.5)}, {"r": 4})
    assert row["paper_value"] == "Displacement (m): [-5, 5]; Velocity (m/s): [-1.5, 1.5]"
    assert row["replicated_value"].startswith(
        "Displacement (m): [-5, 5]; Velocity (m/s): [-1.5, 1.5] (4 of 4 printed limits)")
    assert "K = 0.1 N/m" in row["note"] and "x0 = -1 m" in row["note"]


@pytest.mark.parametrize("panel, given, message", [
    (("5", "c"), _evidence({}, fig5_K=(0.1, 1.0)), "no Fig. 5 output has the spring constant of panel"),
    (("3", "a/velocity"), _evidence({}), "no autoscaled limits for Fig. 3 panel 'a/velocity'"),
    (("3", "a/velocity"), _evidence({("3", "a/velocity"): {"x": (0, 50), "y": (1, 2)}}),
     "no scored candidate readings for Fig. 3 panel 'a/velocity'"),
    (("3", "a/velocity"), _evidence({("3", "a/velocity"): {"x": (0, 50), "y": (1, 2)}},
                                    {("3", "a/velocity"): Candidates(2, {"r": 2})}),
     "scored out of 2 limits; the panel has 4"),
])
def test_missing_evidence_fails_loudly(panel, given, message):
    with pytest.raises(cl.ClaimError, match=message):
        cl.evaluate([_claim(*panel)], given)
