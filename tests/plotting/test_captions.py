"""The figures' text: values with the table's symbols and units, and the note on a run that ended early."""

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from escapement.model.quantities import quantity
from escapement.model.status import Status
from escapement.plotting.captions import axis_label, broken, outcome_note, quantity_value, release


def test_a_value_shows_the_symbol_and_units_unbroken_with_the_minus_of_the_ticks():
    text = quantity_value("a1", -0.1)
    assert text == f"{quantity('a1').symbol}\u00a0=\u00a0\u22120.1\u00a0{quantity('a1').unit_label}"
    assert " " not in text  # no place for a line break


def test_a_pure_number_shows_no_units():
    assert quantity_value("b", 0.1).endswith("0.1")


def test_axis_labels_carry_the_tables_units():
    assert axis_label("F").endswith(f"({quantity('F').unit_label})")
    assert "(" not in axis_label("b")


def test_a_release_names_the_initial_velocity_only_when_it_is_not_zero():
    at_rest = xr.Dataset({"x0": 3.0})
    assert release(at_rest).startswith("released from rest at x(0)")
    moving = xr.Dataset({"x0": 3.0, "v0": -0.5})
    assert "with v(0)\u00a0=\u00a0\u22120.5\u00a0m/s" in release(moving)


def test_a_line_is_broken_at_each_jump():
    t, y = broken(np.arange(5.0), np.arange(5.0), np.array([1.5, 3.5]))
    assert np.isnan(y).sum() == 2 and np.isnan(t).sum() == 2
    assert np.flatnonzero(np.isnan(t)).tolist() == [2, 5]


def test_only_a_run_that_did_not_complete_gets_a_note():
    fig, ax = plt.subplots()
    try:
        completed = {"outcome": Status.COMPLETED.value, "outcome_message": "50 cycles"}
        assert outcome_note(ax, xr.Dataset(attrs=completed)) == []
        assert outcome_note(ax, xr.Dataset()) == []
        stopped = xr.Dataset(attrs={"outcome": Status.STOPPED.value, "outcome_message": "the escapement stopped"})
        (note,) = outcome_note(ax, stopped)
        assert note.text.startswith(f"{Status.STOPPED.value}: the escapement stopped")
    finally:
        plt.close(fig)
