"""The table of quantities: every model key once, with valid UDUNITS units that match their labels."""

import dataclasses

import pytest
from cf_units import Unit

from escapement.model.parameters import Parameters
from escapement.model.quantities import INITIAL_STATE, MODEL_KEYS, PARAMETERS, REQUIRED_KEYS, Quantity, quantity

#: SI base units of each quantity, from the model (Sec. 2 of the paper): M x'' + K x = F
SI = {"M": "kg", "K": "kg s-2", "F": "kg m s-2", "b": "1", "a1": "m", "a2": "m", "a3": "m", "a4": "m",
      "x0": "m", "v0": "m s-1"}


def test_the_model_keys_are_the_paper_symbols_in_order_and_the_fields_of_parameters():
    assert MODEL_KEYS == ("M", "K", "F", "b", "a1", "a2", "a3", "a4")
    assert tuple(f.name for f in dataclasses.fields(Parameters)) == MODEL_KEYS
    assert REQUIRED_KEYS == ("M", "K", "F", "b", "a1", "a2")
    assert tuple(INITIAL_STATE) == ("x0", "v0")


@pytest.mark.parametrize("name", list(SI))
def test_units_are_udunits_and_have_the_dimension_of_the_model(name):
    q = quantity(name)
    assert q.name == name
    unit = Unit(q.units)
    assert unit == Unit(SI[name])
    assert Unit(q.unit_label) == unit  # the plain label means the same units


def test_a_label_shows_units_except_for_pure_numbers():
    assert PARAMETERS["K"].label() == "spring constant (N/m)"
    assert PARAMETERS["b"].label() == PARAMETERS["b"].long_name
    assert Quantity("x", "x", "m", "m", "length").label() == "length (m)"
    assert quantity("v0").label() == "initial velocity (m/s)"


def test_an_unknown_name_raises():
    with pytest.raises(KeyError):
        quantity("omega")


def test_quantities_are_immutable():
    with pytest.raises(dataclasses.FrozenInstanceError):
        PARAMETERS["M"].units = "g"
