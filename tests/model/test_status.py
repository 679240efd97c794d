"""Typed outcomes: stable integer codes (written to files), success, and the CF flag attributes."""

import numpy as np
import pytest

from escapement.model.status import Status, flag_attributes, succeeded

#: the codes as fixed in files already written: never renumber
STORED = {"completed": 0, "stopped": 1, "turned_back_in_zone": 2, "chattering": 3, "event_limit": 4}


def test_codes_are_fixed_and_round_trip():
    assert {s.value: s.code for s in Status} == STORED
    for value, code in STORED.items():
        assert Status.from_code(code) is Status(value) is Status.from_code(float(code))  # as read from floats
    for code in (-1, 5):
        with pytest.raises(ValueError, match=rf"^code = {code} is invalid: code must be one of \[0, 1, 2, 3, 4\]$"):
            Status.from_code(code)


def test_only_a_completed_run_is_a_success_and_the_flag_attributes_follow_the_codes():
    assert [s.value for s in Status if s.success] == ["completed"]
    assert succeeded(np.array([0, 1, 2, 3, 4, 0], dtype=np.int8)).tolist() == [True] + [False] * 4 + [True]
    attrs = flag_attributes()
    assert attrs["flag_values"].tolist() == [0, 1, 2, 3, 4] and attrs["flag_values"].dtype.name == "int8"
    assert attrs["flag_meanings"] == "completed stopped turned_back_in_zone chattering event_limit"
