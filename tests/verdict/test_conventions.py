"""The printed formulas under each convention of the paper (paper.conventions, verdict.sec3_steps and sec3_period), on
small synthetic Fig. 3 datasets built here (no solver run): each check answers a grid, whether the formula holds under
each convention, and the rule decides (reproduced under all, undetermined when they disagree, not reproduced
under none).

Hand derivations for the paper's case M = K = 1 kg, N/m (w = 1), F = 1 N (f = 1, c = f/w^2 = 1), b = 0.1,
a1 = -0.1, a2 = 0.05, a3 = 0.1, a4 = -0.05 m, and v1 = 1 m/s before the impact at a1:
v1p^2 = 0.81; v2^2 = 0.81 + (0.01 - 0.0025) + 2 (0.15) = 1.1175; v4^2 = v2^2 + (0.0025 - 0.01) = 1.11;
v4p^2 = 0.81 * 1.11 = 0.8991. Eq. (14) as printed: v5^2 = 0.8991 + 0.0075 - 0.3 = 0.6066; with -f for the
force (sigma f) or the mirrored positions: 0.8991 + 0.0075 + 0.3 = 1.2066, with both 0.6066 again; with Sec. 4's
magnitudes (a4 = +0.05) 0.8991 + 0.0075 -/+ 0.1 = 0.8066 or 1.0066; with v4^2 = 1.11 (the velocity before the impact)
0.8175, 1.4175, 1.0175 or 1.2175. None is 1: a simulated v5 = -1 m/s is met by no convention.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from escapement.paper import conventions as cv
from escapement.verdict import sec3_period, sec3_steps
from escapement.paper import printed as pe
from escapement.verdict.evidence import Evidence
from escapement.verdict.rule import NOT, REPRODUCED, UNDETERMINED, status_of
from escapement.model.parameters import Parameters
from verdict.test_check_boundaries import fig3 as scene

GEOMETRY = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05}
V4P = -math.sqrt(0.8991)
V4 = -math.sqrt(1.11)


def fig3(v_last: float = 1.0, zone_left: float = 1.0, period: float = 6.3, v5: float = -1.0,
         steps: tuple = (1.0, 1.0, 1.0)) -> xr.Dataset:
    """Three cycles, the velocity before impact ``v_last`` at each; the last cycle's steps last ``steps`` and
    ``zone_left``; the velocity before the event at a4 is ``v5``."""
    durations = np.ones((3, 4))
    durations[-1] = [steps[0], steps[1], zone_left, steps[2]]
    kinds = np.array([1, 2, 3, 4] * 3 + [1])
    return scene([v_last] * 3, period=period, durations=durations,
                 before=np.select([kinds == 1, kinds == 4], [v_last, v5], 0.0))


def verdict(check, ds: xr.Dataset, tolerance: float = 1e-9, **args):
    ev = Evidence(fig3={"a": ds}, fig4=None, fig5={}, checks=None)
    return check({"args": {"case": "a", **args}, "tolerance": tolerance}, ev)


def holding(result) -> set[str]:
    """The conventions of a check's grid under which the formula holds."""
    assert isinstance(result.holds, dict)
    return {reading for reading, holds in result.holds.items() if holds}


def status(result) -> str:
    return status_of(result.holds.values())


AS_READ = "positions signed, force f, half as written, velocity after"


# --- the readings ------------------------------------------------------------------------------


def test_every_reading_once_the_adopted_one_first():
    every = cv.readings(tuple(cv.AXES))
    assert len(every) == len(set(every)) == 16 and every[0] == cv.AS_READ
    assert cv.readings(()) == [cv.AS_READ]
    assert {r.velocity for r in cv.readings(("velocity",))} == {"after", "before"}
    with pytest.raises(ValueError, match="axes = .* must name axes"):
        cv.readings(("sign",))
    with pytest.raises(ValueError, match="positions = 'absolute' must be one of signed, magnitudes"):
        cv.Reading("absolute", "f", "as written", "after")


def test_the_symbols_of_each_convention():
    p = Parameters(**GEOMETRY)
    mirrored = cv.Reading("signed", "f", "mirrored", "after")
    assert cv.symbols(p, mirrored, second_half=True) == (pe.Symbols(0.1, -0.05, -0.1, 0.05, 1.0, 1.0), -1.0)
    assert cv.symbols(p, mirrored, second_half=False) == (pe.Symbols(-0.1, 0.05, 0.1, -0.05, 1.0, 1.0), 1.0)
    sigma = cv.Reading("magnitudes", "sigma f", "as written", "after")
    assert cv.symbols(p, sigma, second_half=True) == (pe.Symbols(0.1, 0.05, 0.1, 0.05, -1.0, 1.0), 1.0)
    with pytest.raises(ValueError, match="second_half = 1 must be True or False"):
        cv.symbols(p, sigma, second_half=1)


def test_try_readings_refuses_a_bad_tolerance_or_simulated_value():
    with pytest.raises(ValueError, match="tolerance = -1 must be a number >= 0"):
        cv.try_readings(lambda r: 1.0, 1.0, -1, ())
    with pytest.raises(ValueError, match="simulated = 0.0 must be a finite non-zero float"):
        cv.try_readings(lambda r: 1.0, 0.0, 1e-6, ())


def test_eq23_with_the_magnitudes_of_sec4_is_the_swing_through_the_left_turning_point():
    # the swing a4 -> -h5 -> a1 takes acos(-a4/h5) + acos(-a1/h5) with signed a4, a1 < 0 (w = 1)
    s = pe.Symbols(0.1, 0.05, 0.1, 0.05, 1.0, 1.0)  # Sec. 4's magnitudes
    velocities = {"v1p": 0.9, "v2": 1.0, "v4p": -0.9, "v5": -1.2}
    h5 = math.hypot(0.05, 1.2)
    assert pe.period_terms_23(velocities, s)["a4_to_a1"] == pytest.approx(
        math.acos(0.05 / h5) + math.acos(0.1 / h5), rel=1e-15)


# --- Eq. (14) ----------------------------------------------------------------------------------


def test_eq14_holds_under_the_conventions_that_give_the_simulated_value_and_the_rule_decides():
    as_read = verdict(sec3_steps.eq14_conventions, fig3(v5=-math.sqrt(0.6066)))
    assert len(as_read.holds) == 16
    assert holding(as_read) == {AS_READ, "positions signed, force sigma f, half mirrored, velocity after"}
    assert status(as_read) == UNDETERMINED
    assert "under 2 of the 16 conventions of the paper (as read, sigma f + mirrored), not under" in as_read.note
    other = verdict(sec3_steps.eq14_conventions, fig3(v5=-math.sqrt(1.2066)))
    assert holding(other) == {"positions signed, force sigma f, half as written, velocity after",
                              "positions signed, force f, half mirrored, velocity after"}
    assert status(other) == UNDETERMINED
    none = verdict(sec3_steps.eq14_conventions, fig3(v5=-1.0))
    assert holding(none) == set() and status(none) == NOT and "under 0 of the 16" in none.note
    # within 60 % every value is met (the farthest, sqrt(1.4175 / 0.6066) - 1 = 0.529): reproduced
    assert status(verdict(sec3_steps.eq14_conventions, fig3(v5=-math.sqrt(0.6066)), tolerance=0.6)) == REPRODUCED


# --- Eq. (22e) ---------------------------------------------------------------------------------


def eq22e_by_hand(a3: float, a4: float, c: float, v: float) -> float:
    """atan(v / (a3 + c)) - acos((a4 + c) / h3), h3 = |(a3 + c, v)|, at w = 1 (the printed (22e))."""
    return math.atan(v / (a3 + c)) - math.acos((a4 + c) / math.hypot(a3 + c, v))


def test_eq22e_holds_under_the_conventions_that_give_the_simulated_time_and_the_rule_decides():
    as_read = verdict(sec3_period.eq22e, fig3(zone_left=eq22e_by_hand(0.1, -0.05, 1.0, V4P)))
    # Sec. 4's magnitudes put a4 = +0.05: another time by hand
    assert eq22e_by_hand(0.1, 0.05, 1.0, V4P) != pytest.approx(eq22e_by_hand(0.1, -0.05, 1.0, V4P), rel=1e-3)
    assert AS_READ in holding(as_read)
    assert not as_read.holds["positions magnitudes, force f, half as written, velocity after"]
    assert status(as_read) == UNDETERMINED
    # mirrored positions (-a3, -a4), the mirrored velocity before the impact
    mirrored = verdict(sec3_period.eq22e, fig3(zone_left=eq22e_by_hand(-0.1, 0.05, 1.0, -V4)))
    assert "positions signed, force f, half mirrored, velocity before" in holding(mirrored)
    assert AS_READ not in holding(mirrored) and "(mirrored + before)" in mirrored.note
    # the left zone's true time: the mirror of the right one, [acos((c - a2)/R) - acos((c - a1)/R)]/w
    r = math.hypot(-0.1 - 1.0, -V4P)
    true_time = math.acos(0.95 / r) - math.acos(1.1 / r)
    wrong = verdict(sec3_period.eq22e, fig3(zone_left=true_time))
    assert status(wrong) == NOT and "instead of -, the mirror image of (22b)" in wrong.note


# --- Eq. (23) ----------------------------------------------------------------------------------


def test_eq23_holds_whole_under_each_convention_a_grid_the_rule_decides():
    c = 1.0
    v1p, v2, v5 = 0.9, math.sqrt(1.1175), -math.sqrt(1.2066)
    r1, h2, r3 = math.hypot(-0.1 - c, v1p), math.hypot(0.05, v2), math.hypot(0.1 + c, V4P)
    h5 = math.hypot(-0.05, v5)
    zone_right = math.acos((c - 0.05) / r1) - math.acos((c + 0.1) / r1)
    a2_to_a3 = math.acos(0.05 / h2) + math.acos(0.1 / h2)
    zone_left = math.acos((c - 0.05) / r3) - math.acos((c + 0.1) / r3)
    printed_swing = math.acos(-0.05 / h5) + math.acos(-0.1 / h5)  # signed a4, a1 as printed
    true_swing = math.acos(0.05 / h5) + math.acos(0.1 / h5)  # through the left turning point
    steps = (zone_right, a2_to_a3, true_swing)
    as_read = sum((zone_right, a2_to_a3, zone_left, printed_swing))
    # with Sec. 4's magnitudes (a1 = +0.1, a4 = +0.05) the zone terms and the swing change: another period
    r1m = math.hypot(0.1 - c, v1p)
    magnitudes = (math.acos((c - 0.05) / r1m) - math.acos((c - 0.1) / r1m) + a2_to_a3
                  + math.acos((c + 0.05) / r3) - math.acos((c + 0.1) / r3) + true_swing)
    assert abs(magnitudes - as_read) > 1e-3
    held = verdict(sec3_period.eq23, fig3(period=as_read, zone_left=zone_left, steps=steps))
    assert AS_READ in holding(held)
    assert not held.holds["positions magnitudes, force f, half as written, velocity after"]
    assert status(held) == UNDETERMINED
    # each step right under some convention, the whole under none: not reproduced
    true_period = sum((zone_right, a2_to_a3, zone_left, true_swing))
    mixed = verdict(sec3_period.eq23, fig3(period=true_period, zone_left=zone_left, steps=steps))
    assert status(mixed) == NOT
    assert "a4_to_a1: mirrored or magnitudes" in mixed.note and "zone_left: as read" in mixed.note
    wrong = verdict(sec3_period.eq23, fig3(period=true_period, zone_left=1.0, steps=steps))
    assert status(wrong) == NOT and "zone_left: no reading" in wrong.note


# --- Eqs. (24), (25) ---------------------------------------------------------------------------


@pytest.mark.parametrize("form", ["first", "second"])
def test_eq24_is_read_in_one_convention_for_both_forms(monkeypatch, form):
    # at v1 = 1: the sine phase atan2(a1, v) jumps from atan2(-0.1, 1) to atan2(-0.1, 0.9), a delay of
    # atan(0.1/0.9) - atan(0.1) s, which the first form gives with x1+ = 0.9, the velocity after the impact as
    # Eq. (10) defines it; the second form with the same x1+ = 0.9 gives atan(0.1 * 0.1 * 0.9 / (0.01 + 0.9 * 0.81))
    # instead (it needs x1 = 1, the velocity before: a misprint). With x1+ read as the velocity before the impact
    # (x1 after) the first form gives minus the delay and the second the delay: no one reading gives both. With Sec.
    # 4's magnitudes (a1 = +0.1) the first form gives atan(9) - atan(10), minus the delay: a grid of two conventions.
    delay = math.atan(0.1 / 0.9) - math.atan(0.1)
    second_as_printed = math.atan(0.1 * 0.1 * 0.9 / (0.01 + 0.9 * 0.81))
    result = verdict(sec3_period.eq24, fig3(), tolerance=1e-12, form=form)
    assert result.holds == {AS_READ: form == "first", "positions magnitudes, force f, half as written, velocity after":
                            False}
    assert result.replicated_value == (f"phase delay of the impact {delay:.10g} s; with x1+ after the impact: first "
                                       f"form {delay:.10g} s, second form {second_as_printed:.10g} s")
    assert f"the first form gives {-delay:.10g} s and the second {delay:.10g} s" in result.note
    assert ("a misprint, x1+ printed where" in result.note) is (form == "second")
    # a phase delay that neither form gives under any convention
    monkeypatch.setattr(sec3_period.derived, "impact_phase_jump", lambda position, v, p: 1.01 * delay)
    assert status(verdict(sec3_period.eq24, fig3(), tolerance=1e-6, form=form)) == NOT
    with pytest.raises(ValueError, match="form = 'third'"):
        verdict(sec3_period.eq24, fig3(), tolerance=1e-6, form="third")


def eq25_by_hand(v_in: float, a1: float, a2: float) -> float:
    """2 pi + 2 (dT1 + dT2) at w = f = c = 1, b = 0.1, v1 = 1, positions a1, a2, entering the zone at v_in."""
    d1 = math.atan(0.9 / a1) - math.atan(1.0 / a1)
    r1 = math.hypot(a1 - 1.0, v_in)
    exit_ = math.sqrt(v_in**2 + a1**2 - a2**2 - 2 * (a1 - a2))
    d2 = (math.acos((1.0 - a2) / r1) - math.acos((1.0 - a1) / r1)) - (math.atan(exit_ / a2) - math.atan(v_in / a1))
    return 2 * math.pi + 2 * (d1 + d2)


def test_eq25_holds_under_each_convention_a_grid_the_rule_decides():
    as_read, magnitudes_before = eq25_by_hand(0.9, -0.1, 0.05), eq25_by_hand(1.0, 0.1, 0.05)
    assert abs(as_read - magnitudes_before) > 1e-3
    held = verdict(sec3_period.eq25, fig3(period=as_read))
    assert len(held.holds) == 4 and AS_READ in holding(held) and status(held) == UNDETERMINED
    magnitudes = verdict(sec3_period.eq25, fig3(period=magnitudes_before))
    assert "positions magnitudes, force f, half as written, velocity before" in holding(magnitudes)
    assert AS_READ not in holding(magnitudes) and "(magnitudes + before)" in magnitudes.note
    assert status(verdict(sec3_period.eq25, fig3(period=6.3))) == NOT
