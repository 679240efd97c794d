"""The three checks on runs from rest of their own positions (``existence_sign_change``, ``release_boundary``,
``grazing_uniqueness``, the runs made by the checks scene) hand their verdict functions the register's tolerance
and the closed-form reference, unchanged.

The verdict functions are tested at their boundaries in ``test_check_boundaries*.py``; a tolerance scaled
inside a wrapper, or a wrong closed form passed to it, would change no status when the runs converge to
rounding. Here the verdict function is watched as the wrapper calls it, on the register's own rows, and
the reference is written from the closed forms of the register's positions, by hand.
"""

from __future__ import annotations

import math

import pytest
from verdict.test_check_boundaries import register_row, release_runs

from escapement.verdict import engine as cl

from escapement.verdict import sec3_equations, sec4_fig3, sec5_conclusions
from escapement.verdict.evidence import Evidence

# asymmetric_convergence_depends (its reading "whether the motion converges"): a1..a4 = -0.3, -0.25, 0.1, 0.05,
# b = 0.1, K = 1 N/m:
# F* = (2b - b^2) K (a1^2 - a3^2) / (2 [(1 - b)^2 (a2 - a1) + (a3 - a4)]) = 0.19 * 0.08 / (2 * 0.0905)
THRESHOLD = 0.19 * 0.08 / (2 * (0.81 * 0.05 + 0.05))
# initial_amplitude_no_effect and symmetric_convergence_only_b (their readings "whether the motion converges" from
# every release): the free swing from rest meets an impact position beyond min(-a1, a3) = 0.1 m
BOUNDARY = 0.1
# solution_exists_unique: a1 = -0.1, a3 = 0.3, a4 = -0.05 m, f = F / M = 0.1 m/s^2, w^2 = 1 s^-2:
# v1^2 = w^2 (a3^2 - a1^2) + 2 f (a3 - a4) = 0.08 + 0.07
LIMIT = math.sqrt(0.15)

CASES = [
    ("asymmetric_convergence_depends", 1, "existence_verdict", THRESHOLD),
    ("initial_amplitude_no_effect", 0, "release_verdict", BOUNDARY),
    ("solution_exists_unique", 0, "grazing_verdict", LIMIT),
    ("symmetric_convergence_only_b", 2, "release_verdict", BOUNDARY),
]


@pytest.mark.parametrize("claim_id, reading, verdict_function, reference", CASES)
def test_the_wrapper_hands_its_verdict_the_registers_tolerance_and_the_closed_form(
        monkeypatch, claim_id, reading, verdict_function, reference):
    row = register_row(claim_id, 1e-8, reading)
    module = {"existence_verdict": sec5_conclusions, "grazing_verdict": sec3_equations,
              "release_verdict": sec4_fig3}[verdict_function]
    real = getattr(module, verdict_function)
    calls = []

    def watched(rows, closed_form, tolerance, *rest):
        calls.append((closed_form, tolerance))
        return real(rows, closed_form, tolerance, *rest)

    monkeypatch.setattr(module, verdict_function, watched)
    cl.verdict(row, row, Evidence(fig3={}, fig4=None, fig5={}, checks=release_runs(row["args"])))
    assert len(calls) == 1
    closed_form, tolerance = calls[0]
    assert tolerance == row["tolerance"]
    assert closed_form == pytest.approx(reference, rel=1e-14)
