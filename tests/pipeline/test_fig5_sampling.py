"""The configured sampling of Fig. 5 (config/paper.yaml, ``fig5.samples_per_period``) resolves the impulse zones.

Fig. 5 draws the velocity against time; its rise across an impulse zone is only drawn if the uniform time grid
puts at least two samples inside each zone crossing. The bound on the crossing time is derived here by hand,
on the limit cycle of each panel (its spring constant and force), from the map (16) and energy alone.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

CONFIG = Path(__file__).resolve().parents[2] / "config" / "paper.yaml"


def _panels() -> list[dict]:
    config = yaml.safe_load(CONFIG.read_text())
    model, fig5 = config["model"], config["fig5"]
    forces = fig5["F"] if isinstance(fig5["F"], list) else [fig5["F"]] * len(fig5["K"])
    return [{**model, "K": k, "F": f, "samples_per_period": fig5["samples_per_period"]}
            for k, f in zip(fig5["K"], forces, strict=True)]


def shortest_zone_crossing(M: float, K: float, F: float, b: float, a1: float, a2: float) -> float:
    """A lower bound on the time the limit cycle takes through the zone (a1, a2), by hand.

    The fixed point of the map (16), v*^2 = C / (1 - (1-b)^4) with C = 2 f (a2 - a1)(b^2 - 2b + 2), f = F/M, is
    the speed before the impact at a1; after it, (1 - b) v*. Through the zone, by energy,
    v(x)^2 = (1-b)^2 v*^2 + w^2 (a1^2 - x^2) + 2 f (x - a1) <= (1-b)^2 v*^2 + w^2 a1^2 + 2 f (a2 - a1) = v_max^2,
    so the crossing of the length a2 - a1 takes at least (a2 - a1) / v_max.
    """
    f, w2 = F / M, K / M
    c = 2 * f * (a2 - a1) * (b * b - 2 * b + 2)
    v_star2 = c / (1 - (1 - b) ** 4)
    v_max = math.sqrt((1 - b) ** 2 * v_star2 + w2 * a1 * a1 + 2 * f * (a2 - a1))
    return (a2 - a1) / v_max


def test_the_zone_bound_on_the_paper_s_case_a():
    # M = K = F = 1, b = 0.1, a1 = -0.1, a2 = 0.05: C = 0.3 * 1.81 = 0.543, v*^2 = 0.543 / 0.3439 = 1.57895,
    # v_max^2 = 0.81 * 1.57895 + 0.01 + 0.3 = 1.58895, so at least 0.15 / 1.26053 = 0.118997 s
    assert shortest_zone_crossing(1.0, 1.0, 1.0, 0.1, -0.1, 0.05) == pytest.approx(0.118997, rel=1e-5)


@pytest.mark.parametrize("panel", _panels(), ids=lambda p: f"K={p['K']}")
def test_each_fig5_panel_samples_every_zone_crossing_at_least_twice(panel):
    """The zone (a4, a3) is the mirror image of (a1, a2) (a3 = -a1, a4 = -a2 by default): one bound for both."""
    assert panel.get("a3", -panel["a1"]) == -panel["a1"] and panel.get("a4", -panel["a2"]) == -panel["a2"]
    step = 2 * math.pi * math.sqrt(panel["M"] / panel["K"]) / panel["samples_per_period"]
    crossing = shortest_zone_crossing(panel["M"], panel["K"], panel["F"], panel["b"], panel["a1"], panel["a2"])
    assert crossing / step >= 2, f"{crossing / step:.2f} samples in a zone crossing of {crossing:.4f} s"
