"""Typed outcomes: stable integer codes (written to files), success, and the CF flag attributes."""

import pytest

from escapement.model.status import Status, flag_attributes
from escapement.solvers.outcomes import chattering_message, event_limit_message, stopped_message, turned_back_message

#: the codes as fixed in files already written: never renumber
STORED = {"completed": 0, "stopped": 1, "turned_back_in_zone": 2, "chattering": 3, "event_limit": 4}


@pytest.mark.parametrize("value, code", list(STORED.items()))
def test_codes_are_fixed_and_round_trip(value, code):
    status = Status(value)
    assert status.code == code
    assert Status.from_code(code) is status
    assert Status.from_code(float(code)) is status  # as read back from a float array


def test_every_outcome_has_a_code():
    assert {s.value for s in Status} == set(STORED)


@pytest.mark.parametrize("code", [-1, 5, 99])
def test_unknown_code_is_rejected(code):
    with pytest.raises(ValueError, match=f"code = {code!r} is invalid"):
        Status.from_code(code)


def test_only_completed_is_success():
    assert [s.value for s in Status if s.success] == ["completed"]


def test_status_is_its_text_value():
    assert Status.STOPPED == "stopped"
    assert f"{Status.CHATTERING.value}" == "chattering"


def test_flag_attributes_follow_the_codes():
    attrs = flag_attributes()
    assert attrs["flag_values"].tolist() == [0, 1, 2, 3, 4]
    assert attrs["flag_values"].dtype.name == "int8"
    assert attrs["flag_meanings"] == "completed stopped turned_back_in_zone chattering event_limit"


def test_messages_name_the_numbers():
    text = stopped_message(1.5, 0.05, {"a1": -0.1, "a3": 0.1})
    assert "t = 1.5 s" in text and "x = -0.05 m and x = 0.05 m" in text
    assert "a1 = -0.1 m (moving right) or a3 = 0.1 m (moving left)" in text
    text = turned_back_message(2.0, "(a4, a3)", -0.021, -0.0001, -0.1)
    assert "(a4, a3) at t = 2 s" in text and "turns at x = -0.021 m" in text and "at -0.1 m" in text
    assert "v+ = -0.5 v-" in chattering_message(3.0, "a1", 1.5, -0.5, 4.25)
    assert "accumulate at t = 4.25 s" in chattering_message(3.0, "a1", 1.5, -0.5, 4.25)
    # NaN: the centre of oscillation lies in the direction of the rebound, so the mass is not driven back
    text = chattering_message(3.0, "a3", 1.5, -0.5, float("nan"))
    assert "does not drive the mass back to a3 (no Zeno point)" in text and "accumulate" not in text
    assert event_limit_message(1.0, 7) == "ended after max_events = 7 events at t = 1 s; raise max_events to go on"
    assert "max_events = 1 event at t = 0 s" in event_limit_message(-0.0, 1)  # one event; no signed zero
