"""The model layer: parameters, the hybrid automaton, closed-form kinematics, events, outcomes, run specs."""

from .automaton import Mode, Surface
from .events import EventKind, EventLog
from .limits import RunLimits, RunSpec, run_spec
from .parameters import ParameterError, Parameters, check_initial_state
from .quantities import INITIAL_STATE, PARAMETERS, Quantity
from .status import Status

__all__ = ["EventKind", "EventLog", "INITIAL_STATE", "Mode", "PARAMETERS", "ParameterError", "Parameters", "Quantity",
           "RunLimits", "RunSpec", "Status", "Surface", "check_initial_state", "run_spec"]
