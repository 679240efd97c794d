"""The words on the figures: values with the quantities table's symbols and units, releases, outcomes."""

import xarray as xr

from escapement.model.quantities import quantity
from escapement.plotting.captions import outcome, quantity_value, release


def test_a_value_shows_the_symbol_and_units_unbroken_with_the_minus_of_the_ticks():
    text = quantity_value("a1", -0.1)
    assert text == f"{quantity('a1').symbol}\u00a0=\u00a0\u22120.1\u00a0{quantity('a1').unit_label}"
    assert quantity_value("b", 0.1).endswith("0.1")  # a pure number has no units


def test_a_release_names_the_initial_velocity_only_when_it_is_not_zero():
    assert release(xr.Dataset({"x0": 3.0})) == "released from rest at x(0)\u00a0=\u00a03\u00a0m"
    assert release(xr.Dataset({"x0": 3.0, "v0": -0.5})).endswith("with v(0)\u00a0=\u00a0\u22120.5\u00a0m/s")


def test_only_a_run_that_did_not_complete_has_an_outcome(datasets):
    assert outcome(datasets.poincare()) is None and outcome(xr.Dataset()) is None
    assert outcome(datasets.poincare(outcome="turned_back_in_zone")) == "turned back in zone after 0 of 20 cycles"
