"""The words on the figures: values with the quantities table's symbols and units, releases, outcomes."""

import xarray as xr

from escapement.model.quantities import quantity
from escapement.plotting.captions import outcome, quantity_value, release


def test_values_releases_and_outcomes_in_words(datasets):
    # the symbol and units unbroken, with the minus of the ticks; a pure number has no units
    a1 = quantity("a1")
    assert quantity_value("a1", -0.1) == f"{a1.symbol}\u00a0=\u00a0\u22120.1\u00a0{a1.unit_label}"
    assert quantity_value("b", 0.1).endswith("0.1")
    # the initial velocity only when it is not zero
    assert release(xr.Dataset({"x0": 3.0})) == "released from rest at x(0)\u00a0=\u00a03\u00a0m"
    assert release(xr.Dataset({"x0": 3.0, "v0": -0.5})).endswith("with v(0)\u00a0=\u00a0\u22120.5\u00a0m/s")
    # only a run that did not complete has an outcome
    assert outcome(datasets.poincare()) is None and outcome(xr.Dataset()) is None
    assert outcome(datasets.poincare(outcome="turned_back_in_zone")) == "turned back in zone after 0 of 20 cycles"
