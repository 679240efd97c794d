import math
from fractions import Fraction

import numpy as np
import pytest

from escapement.model.parameters import B_SMALLEST, ParameterError, Parameters, check_initial_state, validate_arrays
from escapement.model.quantities import INITIAL_STATE, PARAMETERS

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


# --- the floating-point range --------------------------------------------------------------------

RANGE = "[1e-50, 1e+50]"


@pytest.mark.parametrize(
    "name, value",
    [
        ("M", 1e-320),  # subnormal: blamed on M, not on K/M
        ("M", 5e-324),
        ("M", 1e-51),
        ("M", 1e51),
        ("K", 1e-51),
        ("K", 1e300),
        ("F", 1e-320),
        ("F", 1e-51),
        ("F", 1e51),
        ("a1", -1e51),
        ("a1", -1e-300),
        ("a2", 1e-51),
        ("a2", 1e60),
        ("a3", 1e-320),
        ("a4", -1e200),
    ],
)
def test_a_magnitude_outside_the_range_is_refused_naming_the_parameter_and_the_range(name, value):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, name: value})
    assert err.value.name == name and err.value.value == value and err.value.row is None
    assert str(err.value).startswith(f"{name} = {value!r} is invalid: {name} must be ")
    assert RANGE in err.value.requirement and "normal float64" in err.value.requirement
    assert PARAMETERS[name].unit_label in err.value.requirement


@pytest.mark.parametrize("value", [1e-50, 1e50])
def test_the_ends_of_the_range_are_accepted(value):
    # every dimensional parameter at one end of the range, with a valid geometry
    for name in ("M", "K", "F"):
        assert getattr(Parameters(**{**VALID, name: value}), name) == value
    p = Parameters(**{**VALID, "a1": -value, "a2": value, "a3": value, "a4": -value})
    assert (p.a1, p.a2, p.a3, p.a4) == (-value, value, value, -value)


def test_zero_is_accepted_where_it_means_something():
    p = Parameters(M=1.0, K=1.0, F=0.0, b=0.1, a1=-0.1, a2=0.0, a3=0.1, a4=0.0)
    assert (p.F, p.a2, p.a4) == (0.0, 0.0, 0.0)
    assert check_initial_state(0.0, 0.0) == (0.0, 0.0)
    for name in ("M", "K"):
        with pytest.raises(ParameterError, match="> 0"):
            Parameters(**{**VALID, name: 0.0})


def test_at_the_corners_of_the_range_every_derived_quantity_is_a_normal_float():
    """The bounds are chosen so that omega, F/K, F/M and the squares formed from them stay in
    float64's normal range (2.2e-308 .. 1.8e308), whichever corner the inputs sit at."""
    tiny, huge = np.finfo(float).tiny, np.finfo(float).max
    for M in (1e-50, 1e50):
        for K in (1e-50, 1e50):
            for F in (1e-50, 1e50):
                for a in (1e-50, 1e50):
                    p = Parameters(M=M, K=K, F=F, b=0.1, a1=-a, a2=0.0)
                    for x in (1e-50, 1e50):
                        for v in (1e-50, 1e50):
                            w = v / p.omega
                            derived = [p.omega, p.omega2, p.f, p.zone_offset, p.natural_period, w, w * w,
                                       p.omega2 * x * x, p.omega2 * p.zone_offset**2, p.f * a, 0.5 * p.M * v * v,
                                       0.5 * p.K * x * x, x * p.zone_offset, w * p.zone_offset]
                            assert all(tiny <= abs(q) <= huge for q in derived), (M, K, F, a, x, v)


@pytest.mark.parametrize("b", [1e-13, 5e-17, 1e-320])
def test_an_impact_coefficient_lost_in_one_minus_b_is_refused(b):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, "b": b})
    assert err.value.name == "b" and "1 - b" in err.value.requirement and "1e-12" in err.value.requirement


@pytest.mark.parametrize("factor", [1.0, 1.37, 3.0, 1e3, 1e11])
def test_every_accepted_impact_coefficient_survives_the_impact_law_to_4_digits(factor):
    """The impact law v+ = (1 - b) v- loses b's low digits in 1 - b: from the smallest b Parameters
    accepts up, the b the law applies (recovered from the velocity after a unit impact) agrees to 4 digits."""
    p = Parameters(**{**VALID, "b": B_SMALLEST * factor})
    v_after = (1.0 - p.b) * 1.0
    assert abs((1.0 - v_after) / p.b - 1.0) < 1e-4


@pytest.mark.parametrize("b", [1e-12 * (1 - 1e-9), 1e-14, 1e-16, 1e-17])
def test_an_impact_coefficient_below_the_smallest_is_refused_naming_it(b):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, "b": b})
    assert err.value.name == "b" and err.value.value == b


def test_the_papers_values_lie_far_inside_the_range():
    for K in (0.1, 1.0, 10.0):
        for F in (0.0, 0.01, 0.5, 1.0, 5.0):
            for a1, a2, a3, a4 in ((-0.1, 0.05, 0.1, -0.05), (-0.15, 0.0, 0.08, -0.1), (-0.05, 0.01, 0.3, 0.0)):
                Parameters(M=1.0, K=K, F=F, b=0.1, a1=a1, a2=a2, a3=a3, a4=a4)
    for x0 in (0.021, 1.0, 3.0):
        check_initial_state(x0, 0.0)


@pytest.mark.parametrize("name, x0, v0", [("x0", 1e200, 0.0), ("x0", 1e-320, 0.0), ("x0", -1e51, 0.0),
                                          ("v0", 1.0, 1e51), ("v0", 1.0, -5e-324), ("v0", 1.0, 1e-60)])
def test_an_initial_state_outside_the_range_is_refused(name, x0, v0):
    with pytest.raises(ParameterError) as err:
        check_initial_state(x0, v0)
    assert err.value.name == name and err.value.value == {"x0": x0, "v0": v0}[name]
    assert RANGE in err.value.requirement and INITIAL_STATE[name].unit_label in err.value.requirement


def test_the_ends_of_the_state_range_are_accepted():
    assert check_initial_state(1e50, -1e50) == (1e50, -1e50)
    assert check_initial_state(-1e-50, 1e-50) == (-1e-50, 1e-50)


# --- one validation for scalars and arrays -------------------------------------------------------


@pytest.mark.parametrize(
    "value, row, requirement",
    [
        ([0.1, True], 1, "a real number"),  # NumPy would turn True into 1.0
        (np.array([True, False]), 0, "a real number"),
        (["1.0"], 0, "a real number"),
        ([0.1, "0.2", 0.3], 1, "a real number"),
        ([0.1, [0.2, 0.3]], 1, "a real number"),
        ([0.1, 1j], 1, "a real number"),
        ([0.1, 10**400], 1, "within the float64 range"),
    ],
)
def test_an_array_element_that_is_not_a_real_number_is_named_by_its_row(value, row, requirement):
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=1.0, K=1.0, F=0.5, b=value, a1=-0.1, a2=0.05))
    assert (err.value.name, err.value.row) == ("b", row)
    assert requirement in err.value.requirement


@pytest.mark.parametrize("value", [True, np.True_, "0.1", b"0.1", 10**400, None, 1j, [0.1]])
def test_a_single_parameter_that_is_not_a_real_number_is_refused(value):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, "b": value})
    assert err.value.name == "b"


def test_other_real_numbers_are_taken_as_floats():
    p = Parameters(M=Fraction(1, 2), K=np.float32(2.0), F=np.int64(1), b=0.1, a1=-0.1, a2=0.05)
    assert (p.M, p.K, p.F) == (0.5, 2.0, 1.0) and all(type(v) is float for v in p.as_dict().values())
    out = validate_arrays(dict(M=[1, Fraction(1, 4)], K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05))
    assert out["M"].tolist() == [1.0, 0.25]


def test_the_array_rules_are_the_scalar_rules_row_by_row():
    """Each row of an array is refused exactly when the same values as single numbers are."""
    rows = [
        dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=0.0),
        dict(M=1e-320, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=0.0),
        dict(M=1.0, K=1.0, F=0.5, b=1e-13, a1=-0.1, a2=0.05, x0=1.0, v0=0.0),
        dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1e200, v0=0.0),
        dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=-1e-300),
        dict(M=1.0, K=1e60, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=0.0),
    ]
    for i, row in enumerate(rows):
        try:
            Parameters(**{k: v for k, v in row.items() if k not in ("x0", "v0")})
            check_initial_state(row["x0"], row["v0"])
            scalar = None
        except ParameterError as err:
            scalar = (err.name, err.value, err.requirement)
        columns = {k: [rows[0][k], row[k]] for k in row}  # a good row 0, then this one as row 1
        try:
            validate_arrays(columns, state=True)
            array = None
        except ParameterError as err:
            assert err.row == 1
            array = (err.name, err.value, err.requirement)
        assert array == scalar, i
    assert scalar is not None  # the last row is refused (K out of range)


def test_the_state_is_validated_with_the_parameters_and_broadcast_with_them():
    out = validate_arrays(dict(M=1.0, K=[1.0, 4.0], F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=[0.0, 1.0]), state=True)
    assert out["x0"].tolist() == [1.0, 1.0] and out["v0"].tolist() == [0.0, 1.0]
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=[1.0, 1e-60], v0=0.0), state=True)
    assert (err.value.name, err.value.row, err.value.value) == ("x0", 1, 1e-60)
    with pytest.raises(ParameterError, match="^x0 = None is invalid: x0 must be given"):
        validate_arrays(dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, v0=0.0), state=True)


def test_arrays_of_shapes_that_do_not_broadcast_are_named():
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=[1.0, 2.0], K=[1.0, 2.0, 3.0], F=0.5, b=0.1, a1=-0.1, a2=0.05))
    assert err.value.name == "K" and "broadcastable" in err.value.requirement and "(2,)" in err.value.requirement
