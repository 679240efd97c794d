"""The settings an experiment checks itself: time windows and positive counts."""

import numpy as np
import pytest

from escapement.experiments.arguments import positive_int, time_window
from escapement.model.parameters import ParameterError


def test_a_window_is_two_times_in_order():
    assert time_window("w", [80, 87.5]) == (80.0, 87.5)
    for bad in ((87.0, 80.0), (-1.0, 2.0), (0.0, np.inf), "80-87", (1.0,)):
        with pytest.raises(ParameterError, match="^w = "):
            time_window("w", bad)


def test_a_count_is_a_positive_integer():
    assert positive_int("n", np.int64(3)) == 3 and type(positive_int("n", np.int64(3))) is int
    for bad in (0, -2, 2.0, True, "3"):
        with pytest.raises(ParameterError, match="^n = .*a positive integer"):
            positive_int("n", bad)
