"""Parameters and the initial state: the rules, checked when the parameters are made, one rule set for a single
run and for the rows of an ensemble, and the floating-point range in which they keep every computed quantity."""

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest

from escapement.model.parameters import B_SMALLEST, ParameterError, Parameters, check_initial_state, validate_arrays

VALID = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
#: the range of a dimensional input and why, as the messages say it
RANGE = "[1e-50, 1e+50]"
WHY = ", so that the squares and products the solvers form"

#: every kind of refusal of Parameters: the inputs changed, the name refused, the start of its requirement (the
#: refusals of what is not a real number are escapement.model.arguments', tested there: one here shows them used)
REFUSED = [
    ({"M": 0.0}, "M", "> 0 (kg)"),
    ({"K": 0.0}, "K", "> 0 (N/m)"),
    ({"F": -0.1}, "F", ">= 0 (N)"),
    ({"b": 0.0}, "b", "in the open interval (0, 2)"),
    ({"b": 2.0}, "b", "in the open interval (0, 2)"),
    ({"b": 1e-13}, "b", ">= 1e-12 (and < 2), so that the impact law's factor 1 - b keeps b to 4 significant digits"),
    ({"b": 1e-12 * (1 - 1e-9)}, "b", ">= 1e-12"),
    ({"a2": -0.1}, "a2", "> a1 = -0.1 (m)"),
    ({"a1": 0.2, "a2": 0.1, "a3": -0.2, "a4": -0.3}, "a2", "> a1 = 0.2 (m)"),
    ({"a3": 0.1, "a4": 0.1}, "a4", "< a3 = 0.1 (m)"),
    ({"a3": 0.0, "a4": 0.0}, "a4", "< a3 = 0.0 (m)"),
    ({"M": 1e-320}, "M", f"in {RANGE} (kg){WHY}"),  # subnormal: blamed on M, not on K/M
    ({"M": 1e51}, "M", f"in {RANGE} (kg){WHY}"),
    ({"K": 1e300}, "K", f"in {RANGE} (N/m){WHY}"),
    ({"F": 1e-320}, "F", f"0 or of magnitude in {RANGE} (N){WHY}"),
    ({"a1": -1e51}, "a1", f"0 or of magnitude in {RANGE} (m){WHY}"),
    ({"a2": 1e-51}, "a2", f"0 or of magnitude in {RANGE} (m){WHY}"),
    ({"a3": 1e-320}, "a3", f"0 or of magnitude in {RANGE} (m){WHY}"),
    ({"a4": -1e200}, "a4", f"0 or of magnitude in {RANGE} (m){WHY}"),
    ({"M": math.nan}, "M", "finite"),
    ({"F": -math.inf}, "F", "finite"),
    ({"b": "0.1"}, "b", "a real number"),
    ({"a2": None}, "a2", "given"),
    ({"F": [1.0, 2.0]}, "F", "a single real number, not an array or a sequence"),
]


@pytest.mark.parametrize("changes, name, requirement", REFUSED, ids=[f"{n}-{i}" for i, (_, n, _) in enumerate(REFUSED)])
def test_each_value_that_breaks_a_rule_is_refused_naming_it_and_the_rule(changes, name, requirement):
    with pytest.raises(ParameterError) as err:
        Parameters(**{**VALID, **changes})
    value = changes[name]
    assert (err.value.name, err.value.row) == (name, None) and (err.value.value is value or err.value.value == value)
    assert str(err.value).startswith(f"{name} = {value!r} is invalid: {name} must be {requirement}")


@pytest.mark.parametrize("changes", [
    {"M": 1e-50, "K": 1e50, "F": 1e50}, {"M": 1e50, "K": 1e-50, "F": 1e-50},  # the ends of the range
    {"a1": -1e-50, "a2": 1e-50, "a3": 1e-50, "a4": -1e-50}, {"a1": -1e50, "a2": 1e50, "a3": 1e50, "a4": -1e50},
    {"F": 0.0, "a2": 0.0, "a4": 0.0},  # zero where it means something
    {"b": B_SMALLEST}, {"b": 1.999999},
    {"M": Fraction(1, 2), "K": np.float32(2.0), "F": np.int64(1)},  # real numbers of other kinds, as floats
])
def test_values_within_the_rules_are_stored_as_floats(changes):
    p = Parameters(**{**VALID, **changes})
    assert all(type(v) is float for v in p.as_dict().values())
    assert all(getattr(p, k) == float(v) for k, v in changes.items())


def test_the_symmetric_defaults_and_the_quantities_derived():
    p = Parameters(M=2.0, K=8.0, F=3.0, b=0.1, a1=-0.1, a2=0.05)
    assert (p.a3, p.a4, p.symmetric, p.paper_signs) == (0.1, -0.05, True, True)
    assert (p.omega, p.omega2, p.f, p.zone_offset, p.natural_period) == (2.0, 4.0, 1.5, 3.0 / 8.0, math.pi)
    q = Parameters(**VALID, a3=0.2, a4=-0.01)
    assert (q.a3, q.a4, q.symmetric) == (0.2, -0.01, False)
    assert repr(Parameters(M=1, K=4, F=0, b=1, a1=-1, a2=0)) == (
        "Parameters(M=1.0, K=4.0, F=0.0, b=1.0, a1=-1.0, a2=0.0, a3=1.0, a4=0.0)")  # a4 = -0.0 typed back as 0.0


def test_from_mapping_ignores_other_keys_and_names_a_missing_one():
    assert Parameters.from_mapping({**VALID, "x0": 3.0, "label": "case", "a3": None}) == Parameters(**VALID)
    with pytest.raises(ParameterError, match="^a2 = None is invalid: a2 must be given") as err:
        Parameters.from_mapping({k: v for k, v in VALID.items() if k != "a2"})
    assert err.value.name == "a2"


@pytest.mark.parametrize("x0, v0, name, requirement", [
    (math.nan, 0.0, "x0", "finite"), ("1", 0.0, "x0", "a real number"), (1.0, [0.0, 1.0], "v0", "a single real"),
    (1e200, 0.0, "x0", f"0 or of magnitude in {RANGE} (m)"),
    (1.0, -5e-324, "v0", f"0 or of magnitude in {RANGE} (m/s)"),
    (1.0, 1e51, "v0", f"0 or of magnitude in {RANGE} (m/s)"),
])
def test_the_initial_state_is_refused_naming_it(x0, v0, name, requirement):
    with pytest.raises(ParameterError) as err:
        check_initial_state(x0, v0)
    assert err.value.name == name and err.value.requirement.startswith(requirement)
    assert check_initial_state(1, -2) == (1.0, -2.0)
    assert check_initial_state(1e50, -1e-50) == (1e50, -1e-50) and check_initial_state(0.0, 0.0) == (0.0, 0.0)


def test_at_the_corners_of_the_range_every_derived_quantity_is_a_normal_float():
    """omega, F/K, F/M and the squares formed from them stay in float64's normal range (2.2e-308 .. 1.8e308),
    whichever corner of the range the inputs sit at."""
    tiny, huge = np.finfo(float).tiny, np.finfo(float).max
    for M, K, F, a, x, v in itertools.product((1e-50, 1e50), repeat=6):
        p = Parameters(M=M, K=K, F=F, b=0.1, a1=-a, a2=0.0)
        w = v / p.omega
        derived = [p.omega, p.omega2, p.f, p.zone_offset, p.natural_period, w, w * w, p.omega2 * x * x,
                   p.omega2 * p.zone_offset**2, p.f * a, 0.5 * p.M * v * v, 0.5 * p.K * x * x, x * p.zone_offset,
                   w * p.zone_offset]
        assert all(tiny <= abs(q) <= huge for q in derived), (M, K, F, a, x, v)


def test_every_accepted_impact_coefficient_survives_the_impact_law_to_4_digits():
    """v+ = (1 - b) v- loses b's low digits in 1 - b: from the smallest b accepted up, the b recovered from the
    velocity after a unit impact agrees to 4 digits."""
    for factor in (1.0, 1.37, 1e3, 1e11):
        p = Parameters(**{**VALID, "b": B_SMALLEST * factor})
        assert abs((1.0 - (1.0 - p.b) * 1.0) / p.b - 1.0) < 1e-4


# --- one rule set for the rows of an ensemble --------------------------------------------------------


def test_the_rules_on_arrays_are_the_scalar_rules_row_by_row():
    """Each row is refused exactly when the same values as single numbers are, with the same requirement."""
    good = dict(M=1.0, K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=0.0)
    for changes in ({}, {"M": 1e-320}, {"b": 1e-13}, {"x0": 1e200}, {"v0": -1e-300}, {"K": 1e60}, {"a2": -0.2}):
        row = {**good, **changes}
        try:
            Parameters(**{k: v for k, v in row.items() if k not in ("x0", "v0")})
            check_initial_state(row["x0"], row["v0"])
            scalar = None
        except ParameterError as err:
            scalar = (err.name, err.value, err.requirement)
        try:
            validate_arrays({k: [good[k], row[k]] for k in row}, state=True)  # a good row 0, then this one
            array = None
        except ParameterError as err:
            assert err.row == 1
            array = (err.name, err.value, err.requirement)
        assert array == scalar and (scalar is None) == (not changes), changes


def test_arrays_are_broadcast_with_the_symmetric_defaults():
    out = validate_arrays(dict(M=1.0, K=[1.0, 4.0], F=0.5, b=0.1, a1=-0.1, a2=0.05, x0=1.0, v0=[0.0, 1.0]), state=True)
    assert all(a.shape == (2,) and a.dtype == np.float64 for a in out.values())
    assert out["a3"].tolist() == [0.1, 0.1] and out["a4"].tolist() == [-0.05, -0.05]
    assert out["x0"].tolist() == [1.0, 1.0] and out["v0"].tolist() == [0.0, 1.0]
    with pytest.raises(ParameterError) as err:
        validate_arrays(dict(M=[1.0, 2.0], K=[1.0, 2.0, 3.0], F=0.5, b=0.1, a1=-0.1, a2=0.05))
    assert err.value.name == "K" and err.value.requirement == ("an array broadcastable with the inputs before it, "
                                                               "of shape (2,)")
