import math

import pytest

from escapement import ParameterError, Parameters
from escapement.parameters import check_initial_state

VALID = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


def test_symmetric_defaults_follow_a1_and_a2():
    p = Parameters(**VALID)
    assert (p.a3, p.a4) == (0.1, -0.05)
    assert p.symmetric


def test_asymmetric_positions_are_kept():
    p = Parameters(**VALID, a3=0.2, a4=-0.01)
    assert (p.a3, p.a4) == (0.2, -0.01)
    assert not p.symmetric


def test_derived_quantities():
    p = Parameters(M=2.0, K=8.0, F=3.0, b=0.1, a1=-0.1, a2=0.05)
    assert p.omega == 2.0
    assert p.omega2 == 4.0
    assert p.f == 1.5
    assert p.zone_offset == 3.0 / 8.0
    assert p.natural_period == math.pi


@pytest.mark.parametrize(
    "name, value, requirement",
    [
        ("M", 0.0, "> 0"),
        ("M", -1.0, "> 0"),
        ("K", 0.0, "> 0"),
        ("K", -2.0, "> 0"),
        ("F", -0.1, ">= 0"),
        ("b", 0.0, "(0, 2)"),
        ("b", 2.0, "(0, 2)"),
        ("b", -0.5, "(0, 2)"),
        ("a2", -0.1, "> a1"),
        ("a2", -0.2, "> a1"),
        ("M", math.nan, "finite"),
        ("K", math.inf, "finite"),
        ("F", -math.inf, "finite"),
        ("a1", math.nan, "finite"),
        ("b", "0.1", "a real number"),
        ("F", True, "a real number"),
        ("a2", None, "a real number"),
    ],
)
def test_each_violation_names_the_parameter_and_the_rule(name, value, requirement):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, name: value})
    assert err.value.name == name
    assert str(err.value).startswith(f"{name} = {value!r} is invalid")
    assert requirement in str(err.value)


def test_a4_must_lie_below_a3():
    with pytest.raises(ParameterError, match=r"a4 = 0\.1 is invalid: a4 must be < a3 = 0\.1"):
        Parameters(**VALID, a3=0.1, a4=0.1)


def test_a3_must_be_a_number():
    with pytest.raises(ParameterError, match="a3 = 'x' is invalid: a3 must be a real number"):
        Parameters(**VALID, a3="x")


def test_positions_too_large_for_the_energy_are_rejected():
    with pytest.raises(ParameterError, match="a1"):
        Parameters(**{**VALID, "a1": -1e200, "K": 1e10})


@pytest.mark.parametrize("x0, v0, name", [(math.nan, 0.0, "x0"), (1.0, math.inf, "v0"), ("1", 0.0, "x0")])
def test_initial_state_is_checked(x0, v0, name):
    with pytest.raises(ParameterError, match=f"^{name} = "):
        check_initial_state(x0, v0)
