"""The one check per kind of argument (escapement.model.arguments), through the public entry points that use
it: the parameters, the initial state, the limits, the ensemble's arrays; each refusal a ParameterError that
names the argument, keeps the value as given and says what it must be."""

from __future__ import annotations

import decimal
import fractions
import math

import numpy as np
import pytest

from escapement import ParameterError, Parameters, solve_ensemble, solve_exact
from escapement.model.arguments import ParameterTypeError, check_choice, check_index, real_array, real_number
from escapement.model.parameters import check_initial_state
from escapement.model.quantities import MODEL_KEYS

GOOD = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05, a3=0.1, a4=-0.05)

#: values that are not a single finite real number, each with the start of the requirement it meets
NOT_A_NUMBER = [
    (np.ma.masked, "a real number, not a masked element"),
    (np.ma.array(0.5, mask=True), "a real number, not a masked element"),
    (np.ma.array([0.5], mask=[False]), "a single real number, not an array"),
    (np.array(0.5), "a single real number, not an array"),
    (np.array([0.5]), "a single real number, not an array"),
    (np.array([[0.5]]), "a single real number, not an array"),
    ([0.5], "a single real number, not an array"),
    ((0.5,), "a single real number, not an array"),
    (True, "a real number"),
    (np.bool_(False), "a real number"),
    ("0.5", "a real number"),
    (b"0.5", "a real number"),
    (None, "given"),
    (0.5 + 0j, "a real number"),
    (np.complex64(0.5), "a real number"),
    (decimal.Decimal("0.5"), "a real number"),
    ({"value": 0.5}, "a real number"),
    (Ellipsis, "a real number"),
    (math.nan, "finite"),
    (-math.inf, "finite"),
    (np.float32("inf"), "finite"),
    (10**400, "a real number within the float64 range"),
]


#: every parameter with every value that is not a number, except None for a3 and a4: their symmetric default
REFUSED = [pytest.param(name, value, requirement, id=f"{name}-{i}") for name in MODEL_KEYS
           for i, (value, requirement) in enumerate(NOT_A_NUMBER) if not (value is None and name in ("a3", "a4"))]


@pytest.mark.parametrize(("name", "value", "requirement"), REFUSED)
def test_every_parameter_takes_a_single_finite_real_number_only(name, value, requirement):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**GOOD, name: value})
    assert err.value.name == name and err.value.value is value and err.value.row is None
    assert err.value.requirement.startswith(requirement)
    assert str(err.value).startswith(f"{name} = {value!r} is invalid: {name} must be {requirement}")


@pytest.mark.parametrize("name", ["x0", "v0"])
@pytest.mark.parametrize(("value", "requirement"), [case for case in NOT_A_NUMBER if case[0] is not None],
                         ids=[f"{i}" for i in range(len(NOT_A_NUMBER) - 1)])
def test_the_initial_state_takes_a_single_finite_real_number_only(name, value, requirement):
    state = {"x0": 1.0, "v0": 0.0, name: value}
    with pytest.raises(ParameterError) as err:
        check_initial_state(**state)
    assert err.value.name == name and err.value.value is value and err.value.requirement.startswith(requirement)
    with pytest.raises(ParameterError) as err:  # and the solver refuses it, naming it, before any work
        solve_exact(Parameters(**GOOD), **state, n_cycles=2)
    assert err.value.name == name


@pytest.mark.parametrize(("value", "expected"), [
    (2, 2.0), (np.int64(-3), -3.0), (np.uint8(7), 7.0), (np.float32(0.25), 0.25), (np.float16(0.5), 0.5),
    (fractions.Fraction(3, 8), 0.375), (1e-50, 1e-50),
])
def test_plain_real_numbers_of_every_kind_are_taken_as_floats(value, expected):
    got = real_number("x0", value)
    assert type(got) is float and got == expected
    assert check_initial_state(value, 0.0) == (expected, 0.0)


@pytest.mark.parametrize(("name", "value", "requirement"), [
    ("t_end", np.array(5.0), "a single real number, not an array"), ("t_end", [5.0], "a single real number"),
    ("t_end", np.ma.masked, "a real number, not a masked element"), ("t_end", "5", "a real number"),
    ("t_end", True, "a real number"), ("t_end", math.nan, "finite"), ("t_end", 0.0, "> 0 (s)"),
    ("t_end", -1, "> 0 (s)"),
    ("n_cycles", 3.0, "a positive integer"), ("n_cycles", np.float64(3), "a positive integer"),
    ("n_cycles", "3", "a positive integer"), ("n_cycles", True, "a positive integer"),
    ("n_cycles", np.array(3), "a positive integer"), ("n_cycles", np.ma.masked, "a positive integer"),
    ("max_events", np.bool_(True), "a positive integer"), ("max_events", [10], "a positive integer"),
    ("memory_budget", 1e9, "a positive integer"),
    ("record_trajectory", 1, "True or False"), ("record_trajectory", "yes", "True or False"),
    ("record_trajectory", None, "True or False"), ("record_trajectory", np.array(True), "True or False"),
])
def test_the_limits_and_flags_of_a_run_are_refused_naming_them(name, value, requirement):
    kwargs = {"n_cycles": 2, name: value}
    with pytest.raises(ParameterError) as err:
        solve_exact(Parameters(**GOOD), 1.0, **kwargs)
    assert err.value.name == name and err.value.value is value and err.value.requirement.startswith(requirement)


def test_numpy_integers_and_bools_are_counts_and_flags():
    run = solve_exact(Parameters(**GOOD), 1.0, n_cycles=np.int32(3), record_trajectory=np.bool_(False))
    assert len(run.cycles) == 3 and run.trajectory is None


# --- the ensemble's arrays ------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["M", "F", "b", "a1", "a2", "a3", "a4", "x0", "v0"])
@pytest.mark.parametrize("masked_row", [0, 2])
def test_a_masked_element_of_an_ensemble_input_is_refused_naming_its_row(name, masked_row):
    values = {"M": 1.0, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05, "x0": 1.0,
              "v0": 0.0}
    mask = np.zeros(3, dtype=bool)
    mask[masked_row] = True
    values[name] = np.ma.array(np.full(3, values[name]), mask=mask)
    with pytest.raises(ParameterError) as err:
        solve_ensemble(**values, n_cycles=2)
    assert (err.value.name, err.value.row, err.value.value) == (name, masked_row, np.ma.masked)
    assert "not a masked element" in err.value.requirement


def test_a_masked_array_with_nothing_masked_runs_as_its_data():
    forces = [0.5, 1.0, 2.0]
    plain = solve_ensemble(M=1.0, K=1.0, F=forces, b=0.1, a1=-0.1, a2=0.05, n_cycles=3)
    masked = solve_ensemble(M=1.0, K=1.0, F=np.ma.array(forces, mask=False), b=0.1, a1=-0.1, a2=0.05, n_cycles=3)
    np.testing.assert_array_equal(masked.cycles.period, plain.cycles.period)


def test_a_2d_masked_array_names_the_flat_index_of_its_first_masked_element():
    F = np.ma.array([[0.5, 1.0], [2.0, 3.0]], mask=[[False, False], [True, False]])
    with pytest.raises(ParameterError) as err:
        solve_ensemble(M=1.0, K=1.0, F=F, b=0.1, a1=-0.1, a2=0.05, n_cycles=2)
    assert (err.value.name, err.value.row) == ("F", 2)


@pytest.mark.parametrize(("value", "row", "requirement"), [
    (["1.0", "2.0"], 0, "a real number"),
    ([1.0, "2.0"], 1, "a real number"),
    ([1.0, None, 2.0], 1, "a real number"),
    ([1.0, 1.0 + 0j], 1, "a real number"),
    (np.array([1.0, 2.0], dtype=complex), 0, "a real number"),
    (np.array([True, False]), 0, "a real number"),
    ([1.0, True], 1, "a real number"),
    (np.array([1.0, 2.0], dtype=object), None, None),  # plain numbers in an object array are taken
    (np.array([[1.0, 2.0], [3.0, math.inf]]), 3, "finite"),
    (np.array(["2020-01-01"], dtype="datetime64[D]"), 0, "a real number"),
    ([1.0, decimal.Decimal(2)], 1, "a real number"),
    ([[1.0], [1.0, 2.0]], 0, "a real number"),  # ragged: its rows are not numbers
])
def test_ensemble_arrays_hold_plain_real_numbers_only(value, row, requirement):
    run = dict(M=value, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05, n_cycles=2)
    if requirement is None:
        assert solve_ensemble(**run).success.all()
        return
    with pytest.raises(ParameterError) as err:
        solve_ensemble(**run)
    assert (err.value.name, err.value.row) == ("M", row) and err.value.requirement == requirement


def test_a_0d_array_is_one_trajectory_in_the_ensemble():
    runs = solve_ensemble(M=np.array(1.0), K=1.0, F=np.float32(1.0), b=0.1, a1=-0.1, a2=0.05, n_cycles=2)
    assert runs.status.shape == (1,)


def test_real_array_keeps_shape_and_values_of_plain_arrays():
    np.testing.assert_array_equal(real_array("F", [[1, 2], [3, 4]]), np.array([[1.0, 2.0], [3.0, 4.0]]))
    assert real_array("F", np.int64(5)).shape == ()


# --- names, rows and classes ----------------------------------------------------------------------


@pytest.mark.parametrize("value", ["Cycles", "cycle", b"cycles", ["cycles"], None, 1])
def test_a_choice_is_one_of_the_names_exactly(value):
    with pytest.raises(ParameterError) as err:
        check_choice("table", value, ("cycles", "events"))
    assert err.value.value is value and err.value.requirement == "one of 'cycles', 'events'"


@pytest.mark.parametrize("value", [-1, 3, 1.0, "1", True, None, np.array(1)])
def test_a_row_index_is_an_integer_inside_the_ensemble(value):
    with pytest.raises(ParameterError) as err:
        check_index("i", value, 3)
    assert err.value.requirement.startswith("an integer in [0, 2]")


def test_a_row_index_may_be_a_numpy_integer():
    assert check_index("i", np.int64(2), 3) == 2


def test_a_wrong_class_is_a_type_error_of_the_same_shape():
    with pytest.raises(ParameterTypeError) as err:
        solve_exact(dict(GOOD), 1.0, n_cycles=2)
    assert isinstance(err.value, TypeError) and isinstance(err.value, ParameterError)
    assert err.value.name == "params" and err.value.value == GOOD


@pytest.mark.parametrize("entry", ["solve_exact", "iter_cycles", "solve_cycles", "iter_closed_form_cycles"])
def test_every_solver_refuses_what_is_not_parameters_with_the_same_error(entry):
    from escapement.solvers import cycles, exact, stream

    function = {"solve_exact": exact.solve_exact, "iter_cycles": stream.iter_cycles,
                "solve_cycles": cycles.solve_cycles, "iter_closed_form_cycles": cycles.iter_closed_form_cycles}[entry]
    with pytest.raises(ParameterTypeError) as err:
        result = function(dict(GOOD), 1.0, n_cycles=2)
        next(iter(result))  # the streams refuse on their first step at the latest
    assert err.value.name == "params" and err.value.value == GOOD
