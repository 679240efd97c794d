"""Replication of J. Mao, Y. Fu, P. Li, "Dynamics of periodic impulsive collision in
escapement mechanism", Shock and Vibration 20 (2013) 1001-1010, DOI 10.3233/SAV-130800."""

from importlib.metadata import PackageNotFoundError, version

from .events import EventKind, EventLog
from .exact import solve_exact
from .outcome import Status
from .parameters import ParameterError, Parameters
from .solution import Solution

try:
    __version__ = version("escapement")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = [
    "EventKind",
    "EventLog",
    "ParameterError",
    "Parameters",
    "Solution",
    "Status",
    "__version__",
    "solve_exact",
]
