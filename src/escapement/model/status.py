"""How a run ended, as a typed outcome instead of an exception, with the integer code written to files (fixed in
:data:`CODES`, not taken from the members' order) and its CF flags (:func:`flag_attributes`)."""

from __future__ import annotations

from enum import Enum

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["CODES", "Status", "flag_attributes", "succeeded"]


class Status(str, Enum):
    """How a run ended: ``value`` is the name written in text, :attr:`code` the stored integer.

    Parameters
    ----------
    value : str
        The name written in text: ``Status("stopped")`` is :attr:`STOPPED` (:meth:`from_code` takes the code).

    Attributes
    ----------
    COMPLETED : str
        Code 0: the requested number of cycles, or the requested end time (s), was reached.
    STOPPED : str
        Code 1: the free swing's turning point lies short of the next impact position, or on it: no more impacts.
    TURNED_BACK_IN_ZONE : str
        Code 2: the velocity vanished inside an impulse zone before its end, outside the model.
    CHATTERING : str
        Code 3: an impact reversed the velocity (``b > 1``); the impacts accumulate in finite time, a Zeno point.
    EVENT_LIMIT : str
        Code 4: the bound on the number of events was reached first.

    Examples
    --------
    >>> from escapement import Status
    >>> Status("stopped").code, Status.STOPPED.success, Status.COMPLETED.success, Status.from_code(2)
    (1, False, True, <Status.TURNED_BACK_IN_ZONE: 'turned_back_in_zone'>)
    """

    COMPLETED = "completed"
    STOPPED = "stopped"
    TURNED_BACK_IN_ZONE = "turned_back_in_zone"
    CHATTERING = "chattering"
    EVENT_LIMIT = "event_limit"

    @property
    def code(self) -> int:
        """The stable integer code of this outcome (stored in netCDF files)."""
        return CODES[self]

    @property
    def success(self) -> bool:
        """True when the requested cycles or end time were reached: the one outcome that is a success."""
        return self is Status.COMPLETED

    @classmethod
    def from_code(cls, code: int) -> Status:
        """The outcome whose :attr:`code` is ``code`` (0 to 4); :class:`ValueError` if none has it."""
        for status, value in CODES.items():
            if value == int(code):
                return status
        raise ValueError(f"code = {code!r} is invalid: code must be one of {sorted(CODES.values())}")


#: The stored codes. Never renumber: files written before would change meaning.
CODES = {Status.COMPLETED: 0, Status.STOPPED: 1, Status.TURNED_BACK_IN_ZONE: 2, Status.CHATTERING: 3,
         Status.EVENT_LIMIT: 4}


def succeeded(codes: ArrayLike) -> np.ndarray:
    """True where a stored code is that of an outcome that is a :attr:`Status.success`."""
    return np.isin(codes, [status.code for status in Status if status.success])


def flag_attributes() -> dict:
    """CF attributes of a variable holding :attr:`Status.code` values."""
    ordered = sorted(CODES, key=CODES.get)
    return {"flag_values": np.array([CODES[status] for status in ordered], dtype=np.int8),
            "flag_meanings": " ".join(status.value for status in ordered)}
