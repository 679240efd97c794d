"""The axis claims: a printed panel is reproduced only when the output autoscales to its limits.

The autoscaled limits are given as evidence (the workflow computes them with matplotlib); the
printed limits are those of escapement.paper.printed_axes, written out here by hand.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from escapement.paper import claims as cl
from escapement.paper.checks import Evidence


def _ds(K: float = 1.0, outcome: str = "completed", **extra) -> xr.Dataset:
    variables = {name: ((), value) for name, value in
                 {"M": 1.0, "K": K, "F": 0.5, "b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05, "x0": -1.0}.items()}
    return xr.Dataset({**variables, **extra}, attrs={"outcome": outcome, "outcome_message": outcome})


def _evidence(axes: dict, fig5_K=(0.1, 1.0, 10.0), outcome="completed") -> Evidence:
    amplitude = xr.DataArray(np.ones(3), dims="amplitude_cycle", attrs={"definition": "step1"})
    fig3 = {c: _ds(outcome=outcome, amplitude=amplitude) for c in ("a", "b")}
    return Evidence(fig3=fig3, fig4=_ds(K=0.1), fig5={f"{k:g}": _ds(K=k) for k in fig5_K}, checks=_ds(), axes=axes)


def _claim(figure: str, panel: str) -> dict:
    return {"id": f"fig{figure}_{panel}", "source": "S", "statement": "s", "paper_value": None, "tolerance": None,
            "check": "printed_axes", "args": {"figure": figure, "panel": panel}}


@pytest.mark.parametrize(
    "figure, panel, limits, status",
    [
        # Fig. 3 (a) velocity: printed cycles 0-50, velocity 0.95-1.3 by 0.05
        ("3", "a/velocity", {"x": (0.0, 50.0), "y": (0.95, 1.3)}, "reproduced"),
        ("3", "a/velocity", {"x": (0.0, 50.0), "y": (1.0, 1.3)}, "partially_reproduced"),
        # the cycle axis alone follows from the number of cycles plotted: not even partly
        ("3", "a/period", {"x": (0.0, 50.0), "y": (6.2956, 6.3044)}, "not_reproduced"),
        ("3", "b/amplitude", {"x": (0.0, 60.0), "y": (0.5, 3.0)}, "reproduced"),
        ("3", "b/amplitude", {"x": (0.0, 50.0), "y": (0.5, 3.0)}, "partially_reproduced"),
        # Fig. 4: only the value axes are scored (the time axes are the printed windows)
        ("4", "velocity", {"y": (-0.1, 0.9)}, "reproduced"),
        ("4", "velocity", {"y": (0.1, 0.9)}, "partially_reproduced"),
        ("4", "acceleration", {"y": (-1.0, 1.0)}, "not_reproduced"),
        # Fig. 5 (c), K = 10 N/m: displacement -1-1 by 0.5, velocity -3-4 by 1
        ("5", "c", {"x": (-1.0, 1.0), "y": (-3.0, 4.0)}, "reproduced"),
        ("5", "c", {"x": (-1.0, 1.0), "y": (-4.0, 3.0)}, "partially_reproduced"),
    ],
)
def test_a_panel_is_reproduced_only_when_every_limit_matches(figure, panel, limits, status):
    row = cl.evaluate([_claim(figure, panel)], _evidence({(figure, panel): limits}))[0]
    assert row["status"] == status


def test_limits_off_by_rounding_still_match_and_by_a_tick_do_not():
    near = {("3", "a/velocity"): {"x": (0.0, 50.0), "y": (0.9500000000000001, 1.3)}}
    assert cl.evaluate([_claim("3", "a/velocity")], _evidence(near))[0]["status"] == "reproduced"


def test_the_row_gives_the_printed_and_the_autoscaled_limits_and_the_reading():
    row = cl.evaluate([_claim("5", "a")], _evidence({("5", "a"): {"x": (-5.0, 5.0), "y": (-1.5, 1.5)}}))[0]
    assert row["paper_value"] == "Displacement (m): [-5, 5]; Velocity (m/s): [-1.5, 1.5]"
    assert row["replicated_value"] == "Displacement (m): [-5, 5]; Velocity (m/s): [-1.5, 1.5] (4 of 4 printed limits)"
    assert "K = 0.1 N/m" in row["note"] and "x0 = -1 m" in row["note"]


def test_a_fig5_panel_without_its_spring_constant_and_missing_limits_fail_loudly():
    with pytest.raises(cl.ClaimError, match="no Fig. 5 output has the spring constant of panel"):
        cl.evaluate([_claim("5", "c")], _evidence({}, fig5_K=(0.1, 1.0)))
    with pytest.raises(cl.ClaimError, match="no autoscaled limits for Fig. 3 panel 'a/velocity'"):
        cl.evaluate([_claim("3", "a/velocity")], _evidence({}))


def test_a_scene_that_left_the_regime_is_not_evaluated():
    row = cl.evaluate([_claim("3", "a/velocity")], _evidence({}, outcome="stopped"))[0]
    assert row["status"] == "not_reproduced" and row["replicated_value"].startswith("not evaluated")
