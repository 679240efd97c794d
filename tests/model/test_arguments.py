"""The one check per kind of argument (escapement.model.arguments): a single real number, an array of them (the
ensemble's rows), sample times, a name from a list, a row index, an object of a class. Each refusal is a
ParameterError that names the argument, keeps the value as given and says what it must be."""

import decimal
import fractions
import math

import numpy as np
import pytest

from escapement.model.arguments import (ParameterError, ParameterTypeError, check_choice, check_count, check_flag,
                                        check_index, real_array, real_number, sample_times)

#: what is not a single finite real number, each with the start of the requirement it meets
NOT_A_NUMBER = [
    (np.ma.masked, "a real number, not a masked element"),
    (np.ma.array(0.5, mask=True), "a real number, not a masked element"),
    (np.ma.array([0.5], mask=[False]), "a single real number, not an array"),
    (np.array(0.5), "a single real number, not an array"),
    (np.array([[0.5]]), "a single real number, not an array"),
    ((0.5,), "a single real number, not an array"),
    (True, "a real number"),
    (np.bool_(False), "a real number"),
    (b"0.5", "a real number"),
    (0.5 + 0j, "a real number"),
    (np.complex64(0.5), "a real number"),
    (decimal.Decimal("0.5"), "a real number"),
    ({"value": 0.5}, "a real number"),
    (None, "a real number"),
    (np.float32("inf"), "finite"),
    (10**400, "a real number within the float64 range"),
]


@pytest.mark.parametrize("value, requirement", NOT_A_NUMBER, ids=[str(i) for i in range(len(NOT_A_NUMBER))])
def test_a_single_real_number_is_finite_and_nothing_else(value, requirement):
    with pytest.raises(ParameterError) as err:
        real_number("x0", value)
    assert (err.value.name, err.value.row) == ("x0", None) and err.value.value is value
    assert err.value.requirement.startswith(requirement)
    assert str(err.value).startswith(f"x0 = {value!r} is invalid: x0 must be {requirement}")


def test_real_numbers_of_every_kind_are_floats():
    for value, expected in [(2, 2.0), (np.int64(-3), -3.0), (np.uint8(7), 7.0), (np.float16(0.5), 0.5),
                            (fractions.Fraction(3, 8), 0.375), (1e-50, 1e-50)]:
        got = real_number("x0", value)
        assert type(got) is float and got == expected
    assert real_number("t_end", 5.0, lambda t: t > 0, "> 0 (s)") == 5.0
    with pytest.raises(ParameterError, match=r"^t_end = -1 is invalid: t_end must be > 0 \(s\)$"):
        real_number("t_end", -1, lambda t: t > 0, "> 0 (s)")


#: array-likes with an element that is not a plain real number (and sample times that are not a 1-d array of them):
#: the element's flat index and the requirement
BAD_ELEMENTS = [(real_array, *case) for case in [
    (["1.0", "2.0"], 0, "a real number"),
    ([1.0, None, 2.0], 1, "a real number"),
    ([1.0, 1.0 + 0j], 1, "a real number"),
    (np.array([1.0, 2.0], dtype=complex), 0, "a real number"),
    (np.array([True, False]), 0, "a real number"),  # NumPy would turn True into 1.0
    ([1.0, True], 1, "a real number"),
    ([0.1, [0.2, 0.3]], 1, "a real number"),
    ([[1.0], [1.0, 2.0]], 0, "a real number"),  # ragged: its rows are not numbers
    (np.array(["2020-01-01"], dtype="datetime64[D]"), 0, "a real number"),
    ([1.0, decimal.Decimal(2)], 1, "a real number"),
    ([0.1, 10**400], 1, "a real number within the float64 range"),
    (np.array([[1.0, 2.0], [3.0, math.inf]]), 3, "finite"),
    (np.ma.array([[0.5, 1.0], [2.0, 3.0]], mask=[[False, False], [True, False]]), 2,
     "a real number, not a masked element (it holds no value)"),
]] + [(sample_times, *case) for case in [
    (None, None, "a real number or a 1-d array of them (s)"),
    ("1.0", None, "a real number"),
    ([0.0, np.bool_(True)], 1, "a real number"),
    (math.nan, None, "finite"),
    (np.array([[0.0, 1.0]]), None, "a real number or a 1-d array of them (s), not of shape (1, 2)"),
]]


@pytest.mark.parametrize("check, value, row, requirement", BAD_ELEMENTS, ids=[str(i) for i in range(len(BAD_ELEMENTS))])
def test_an_array_holds_plain_real_numbers_and_its_first_bad_element_is_named(check, value, row, requirement):
    with pytest.raises(ParameterError) as err:
        check("F", value)
    assert (err.value.name, err.value.row, err.value.requirement) == ("F", row, requirement)


def test_plain_arrays_keep_their_shape_and_values():
    np.testing.assert_array_equal(real_array("F", [[1, 2], [3, 4]]), np.array([[1.0, 2.0], [3.0, 4.0]]))
    assert real_array("F", np.int64(5)).shape == () and real_array("F", np.array([1.0, 2.0], dtype=object)).size == 2
    assert real_array("F", np.ma.array([1.0, 2.0], mask=False)).tolist() == [1.0, 2.0]  # nothing masked: its data
    assert sample_times("t", 1).shape == () and sample_times("t", [0, 1]).tolist() == [0.0, 1.0]


@pytest.mark.parametrize("check, value, requirement", [
    (lambda v: check_choice("table", v, ("cycles", "events")), "Cycles", "one of 'cycles', 'events'"),
    (lambda v: check_choice("table", v, ("cycles", "events")), ["cycles"], "one of 'cycles', 'events'"),
    (lambda v: check_index("i", v, 3), -1, "an integer in [0, 2], a row of the 3 trajectories"),
    (lambda v: check_index("i", v, 3), True, "an integer in [0, 2], a row of the 3 trajectories"),
    (lambda v: check_index("i", v, 3), 1.0, "an integer in [0, 2], a row of the 3 trajectories"),
    (lambda v: check_index("i", v, 0), 0, "a row of the trajectories, and there are none"),
    (lambda v: check_count("dps", v, 1000, 17), 16, "an integer >= 17, at most 1_000"),
    (lambda v: check_count("n", v, 10), np.True_, "a positive integer, at most 10"),
    (lambda v: check_flag("record", v), "no", "True or False"),
    (lambda v: check_flag("record", v), 0, "True or False"),
])
def test_a_name_a_row_a_count_or_a_flag_is_one_of_those_there_are(check, value, requirement):
    with pytest.raises(ParameterError) as err:
        check(value)
    assert err.value.value is value and err.value.requirement == requirement
    assert check_index("i", np.int64(2), 3) == 2 and check_choice("table", "events", ("cycles", "events")) == "events"
    assert check_count("n", np.int32(10), 10) == 10 and check_flag("record", np.False_) is False


def test_a_wrong_class_is_a_type_error_of_the_same_shape():
    err = ParameterTypeError("params", {"M": 1.0}, "an int")
    assert isinstance(err, TypeError) and isinstance(err, ParameterError)
    assert str(err) == "params = {'M': 1.0} is invalid: params must be an int"
