import math

import numpy as np
import pytest

from escapement.model.parameters import ParameterError, Parameters, check_initial_state, validate_arrays

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
        ("a2", None, "given"),
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


def test_the_error_keeps_its_fields_and_names_the_row():
    err = ParameterError("b", 2.5, "in the open interval (0, 2)", row=3)
    assert (err.name, err.value, err.requirement, err.row) == ("b", 2.5, "in the open interval (0, 2)", 3)
    assert str(err) == "row 3: b = 2.5 is invalid: b must be in the open interval (0, 2)"
    assert isinstance(err, ValueError)


def test_from_mapping_ignores_other_keys_and_names_a_missing_one():
    p = Parameters.from_mapping({**VALID, "x0": 3.0, "label": "case", "a3": None})
    assert p == Parameters(**VALID)
    assert Parameters.from_mapping({**VALID, "a3": 0.2, "a4": 0.0}).a4 == 0.0
    with pytest.raises(ParameterError, match="^a2 = None is invalid: a2 must be given") as err:
        Parameters.from_mapping({k: v for k, v in VALID.items() if k != "a2"})
    assert err.value.name == "a2"


def test_parameters_refuse_arrays():
    with pytest.raises(ParameterError, match="single real number"):
        Parameters(**{**VALID, "F": [1.0, 2.0]})


def test_an_array_parameter_is_named():
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, "F": [1.0, 2.0]})
    assert err.value.name == "F"


def test_values_are_stored_as_floats():
    p = Parameters(M=1, K=4, F=0, b=1, a1=-1, a2=0)
    assert all(type(v) is float for v in p.as_dict().values())
    assert p.as_dict() == {"M": 1.0, "K": 4.0, "F": 0.0, "b": 1.0, "a1": -1.0, "a2": 0.0, "a3": 1.0, "a4": -0.0}


def test_validate_arrays_broadcasts_and_names_the_first_bad_row():
    out = validate_arrays(dict(M=1.0, K=[1.0, 4.0, 9.0], F=0.5, b=0.1, a1=-0.1, a2=0.05))
    assert set(out) == {"M", "K", "F", "b", "a1", "a2", "a3", "a4"}
    assert all(a.shape == (3,) and a.dtype == np.float64 for a in out.values())
    assert out["a3"].tolist() == [0.1] * 3 and out["a4"].tolist() == [-0.05] * 3
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=1.0, K=1.0, F=0.5, b=[0.1, 0.2, 2.0, 3.0], a1=-0.1, a2=0.05))
    assert (err.value.name, err.value.row, err.value.value) == ("b", 2, 2.0)
    assert str(err.value).startswith("row 2: b = 2.0 is invalid")
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=[0.05, -0.2]))
    assert (err.value.name, err.value.row) == ("a2", 1)
    assert "> a1 = -0.1" in str(err.value)
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=[1.0, np.nan], K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05))
    assert (err.value.name, err.value.row, err.value.requirement) == ("M", 1, "finite")


def test_a_scalar_violation_names_no_row():
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=1.0, K=1.0, F=-1.0, b=0.1, a1=-0.1, a2=0.05))
    assert err.value.row is None and not str(err.value).startswith("row")


def test_initial_state_as_floats_and_not_arrays():
    assert check_initial_state(1, -2) == (1.0, -2.0)
    with pytest.raises(ParameterError, match="^v0 = "):
        check_initial_state(1.0, [0.0, 1.0])
