"""Studies beyond the paper's figures: the work-precision benchmark (:mod:`.benchmark`), the
long run against 50 digits (:mod:`.long_run`) and the stress cases (:mod:`.stress`)."""

from .benchmark import METHODS, run_method, work_precision
from .long_run import long_run
from .stress import CASES, run_all

__all__ = ["CASES", "METHODS", "long_run", "run_all", "run_method", "work_precision"]
