"""The paper's layer: its equations as printed (:mod:`.printed`) and as corrected here
(:mod:`.corrected`), the measurement of the Poincare map on simulated motion (:mod:`.poincare`),
and the claims register with its checks (:mod:`.claims`)."""

from . import corrected, printed
from .poincare import CycleMeasurement, NoReturn, measure_cycle, return_map, stability_grid

__all__ = ["CycleMeasurement", "NoReturn", "corrected", "measure_cycle", "printed", "return_map", "stability_grid"]
