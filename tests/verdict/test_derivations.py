"""The paper's derivations on its printed formulas. By hand, at the paper's geometry a1 = -0.1, a2 = 0.05,
a3 = 0.1, a4 = -0.05 (m), M = K = 1, f = 1, b = 0.1 and x1 = 1 m/s: (10)-(13) give x2^2 = 0.81 + 0.0075 + 0.3 =
1.1175, x4^2 = 1.11, x4+^2 = 0.8991; (14) as printed, -2 (a3 - a4) f = -0.3, gives x5^2 = 0.6066 and (15)
x1(k+1)^2 = 0.5991, where (16) prints 0.6561 + 0.243 + 0.3 = 1.1991; the fixed point of (17) is x*^2 = 0.3 / 0.19.
"""

import functools
import math

import pytest
import xarray as xr

from escapement.model.parameters import Parameters
from escapement.model.quantities import MODEL_KEYS
from escapement.paper import printed as pe
from escapement.paper.conventions import AS_READ, Reading
from escapement.verdict import derivations as dv
from escapement.verdict import engine as cl
from escapement.verdict.evidence import Evidence
from escapement.verdict.rule import status_of

PAPER = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
SIGMA_F = Reading("signed", "sigma f", "as written", "after")


@functools.cache
def claims() -> dict[str, dict]:
    return {c["id"]: c for c in cl.load_claims(cl.REGISTER)}


def judged(claim_id: str) -> dict | bool:
    """The register's row ``claim_id`` judged on the paper's Fig. 3 case (a) and the module's other models."""
    scene = xr.Dataset({k: ((), float(getattr(PAPER, k))) for k in MODEL_KEYS},
                       attrs={"outcome": "completed", "outcome_message": "completed"})
    claim = claims()[claim_id]
    return cl.verdict(claim, claim["readings"][0], Evidence({"a": scene}, None, {}, None)).holds


def test_eq14_as_printed_substituted_gives_not_eq16_as_read_but_under_sigma_f():
    assert pe.step_velocities(1.0, PAPER)["v1_next"] ** 2 == pytest.approx(0.5991, rel=1e-14)
    assert pe.poincare_map_16(1.0, PAPER) ** 2 == pytest.approx(1.1991, rel=1e-14)
    off = abs(math.sqrt(0.5991) - math.sqrt(1.1991)) / math.sqrt(1.1991)
    assert dv.substitution_difference(PAPER, 1.0, AS_READ) == pytest.approx(off, rel=1e-12)
    assert dv.substitution_difference(PAPER, 1.0, SIGMA_F) < 1e-15
    holds = judged("eq16_derivation")
    assert holds["as read"] is False and holds["sigma f"] is True and status_of(holds.values()) == "undetermined"


def test_a_step_keeps_the_energy_of_the_equation_it_cites_or_changes_it_by_the_work_of_f():
    """(A-5), x'' + x = -f, keeps v^2 + x^2 + 2 x: over (14) as printed it changes by 0.6 (of x5^2 = 0.6066), over
    (15) by 2 f (a4 - a1) = 0.1 (of 0.5991), the work of a force (15) leaves out."""
    assert dv.step_energy_change("14", PAPER, 1.0, AS_READ) == pytest.approx(0.6 / 0.6066, rel=1e-12)
    assert dv.step_energy_change("15", PAPER, 1.0, AS_READ) == pytest.approx(0.1 / 0.5991, rel=1e-12)
    assert dv.step_energy_change("11", PAPER, 1.0, AS_READ) < 1e-15
    assert set(judged("eq11_derivation").values()) == {True} and set(judged("eq15_derivation").values()) == {False}


def test_the_fixed_point_of_eq17_is_eq19():
    assert dv.fixed_point_17(PAPER, 1.0) == pytest.approx(math.sqrt(0.3 / 0.19), rel=1e-14)
    assert judged("eq19_derivation") is True


@pytest.mark.parametrize(("claim_id", "name", "wrong"), [
    ("eq17_derivation", "poincare_map_17", lambda v, p: math.sqrt(0.6561 * v * v + 0.3 * 1.82 * 1.01)),
    ("eq20_derivation", "map_derivative_20", lambda v, p: 0.6561 * v / pe.poincare_map_17(v, p) * 1.001),
    ("eq21_derivation", "multiplier_21", lambda p: 0.6561 * 1.001)])
def test_a_printed_form_that_does_not_follow_fails(monkeypatch, claim_id, name, wrong):
    assert judged(claim_id) is True
    monkeypatch.setattr(pe, name, wrong)
    assert judged(claim_id) is False


def test_an_unknown_equation_is_refused_in_one_line():
    claim = claims()["eq11_derivation"]
    reading = {**claim["readings"][0], "args": {"equation": "13"}}
    with pytest.raises(cl.ClaimError, match="^claim 'eq11_derivation': check 'derivations.appendix_step' failed: "
                       "ValueError: equation = '13' must be one of 11, 12, 14, 15$"):
        cl.verdict(claim, reading, Evidence({}, None, {}, None))


def test_the_intervals_of_eq22_end_where_their_steps_end_and_a_wrong_one_does_not(monkeypatch):
    """(22a) from rest at -h0, h0 = |(a1, x1/w)| = sqrt(1.01), under x'' = -x reaches a1 = -0.1 at
    acos(0.1 / sqrt(1.01)); an interval (22b) 1e-3 s long from a1 at x1+ = 0.9 m/s misses a2 by about 9e-4 m."""
    assert pe.step_times_22(1.0, PAPER, math.sqrt(1.01))["22a"] == pytest.approx(math.acos(0.1 / math.sqrt(1.01)))
    assert max(dv.interval_errors(PAPER, 1.0).values()) < 1e-13 and judged("eq22_derivation") is True
    printed = pe.step_times_22
    monkeypatch.setattr(pe, "step_times_22", lambda *a: {**printed(*a), "22b": printed(*a)["22b"] + 1e-3})
    assert judged("eq22_derivation") is False
