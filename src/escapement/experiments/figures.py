"""The runs behind the paper's figures, each with only what its figure needs.

* Fig. 3 (Poincare map): events only (per cycle, and the event log); no trajectory is kept or
  sampled; the amplitude by the definition the configuration names, and Eq. (19)'s fixed point.
* Fig. 4 (shock detail): one run up to the end of its windows, sampled only inside them.
* Fig. 5 (phase diagrams): one run of ``n_cycles``, sampled at a rate set by the plot.

Each sampled run is sampled, besides its uniform grid, on each side of every jump it shows
(:func:`sample_times`), so that the values just before and just after each impact are kept. The
results are plain: the run (a :class:`~escapement.solvers.result.Solution`), the sample times and
the numbers beside it; :mod:`escapement.io.scenes` makes the datasets of them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.events import EventKind
from ..model.parameters import ParameterError, Parameters
from ..model.quantities import quantity
from ..paper.printed import fixed_point_19
from ..solvers.exact import solve_exact
from ..solvers.result import Solution
from ..studies.readings import AMPLITUDES
from .arguments import positive_int, time_window

__all__ = ["PhaseRun", "PoincareRun", "ShockRun", "phase", "poincare", "sample_times", "shock"]


@dataclass(frozen=True)
class PoincareRun:
    """The run of Fig. 3 and the numbers beside it.

    Attributes
    ----------
    solution : Solution
        The run (events and cycles; the trajectory only where the amplitude needs it).
    n_cycles : int
        The cycles asked for.
    amplitude_definition : str
        The key of the amplitude in :data:`escapement.studies.readings.AMPLITUDES`.
    amplitude_long_name : str
        What that amplitude is, in words.
    amplitude_cycle : numpy.ndarray
        The cycle number of each amplitude (the Step-1 amplitude has one more than there are cycles).
    amplitude : numpy.ndarray
        The amplitudes, m.
    fixed_point_19 : float
        The fixed point of the map (17) by Eq. (19) as printed, m/s.
    """

    solution: Solution
    n_cycles: int
    amplitude_definition: str
    amplitude_long_name: str
    amplitude_cycle: np.ndarray
    amplitude: np.ndarray
    fixed_point_19: float


@dataclass(frozen=True)
class ShockRun:
    """The run of Fig. 4, sampled over the union of its two windows.

    Attributes
    ----------
    solution : Solution
        The run, up to the end of the later window.
    t : numpy.ndarray
        The sample times, s: the uniform grid and both sides of every event inside it.
    window : tuple of float
        The union ``(start, end)`` of both windows, s.
    velocity_window, acceleration_window : tuple of float
        The windows of the velocity and acceleration panels, s.
    samples_per_second : int
        The rate of the uniform grid.
    """

    solution: Solution
    t: np.ndarray
    window: tuple[float, float]
    velocity_window: tuple[float, float]
    acceleration_window: tuple[float, float]
    samples_per_second: int


@dataclass(frozen=True)
class PhaseRun:
    """The run of one phase diagram of Fig. 5, sampled from release to the end of its last cycle.

    Attributes
    ----------
    solution : Solution
        The run.
    t : numpy.ndarray
        The sample times, s: the uniform grid and both sides of every impact inside it.
    n_cycles : int
        The cycles asked for.
    samples_per_period : int
        Samples per natural period ``2 pi sqrt(M/K)`` of the uniform grid.
    """

    solution: Solution
    t: np.ndarray
    n_cycles: int
    samples_per_period: int


def sample_times(grid: np.ndarray, jumps: np.ndarray) -> np.ndarray:
    """The times ``grid`` and, for each jump time inside it, the jump and the largest float below it.

    One sample on each side of the jump (the arc before it, the arc from it). The result increases
    strictly, as CF requires of a coordinate; a jump at the grid's first time keeps only the sample
    after it.

    Parameters
    ----------
    grid : numpy.ndarray
        Increasing sample times, s.
    jumps : numpy.ndarray
        Times of the jumps, s, in any order; those outside ``(grid[0], grid[-1]]`` are ignored.

    Returns
    -------
    numpy.ndarray
        The sorted union of the grid and both sides of each jump.
    """
    grid = np.asarray(grid, dtype=float)
    jumps = np.asarray(jumps, dtype=float)
    jumps = jumps[(jumps > grid[0]) & (jumps <= grid[-1])]
    return np.union1d(grid, np.concatenate([np.nextafter(jumps, -np.inf), jumps]))


def poincare(params: Parameters, x0: float, n_cycles: int, amplitude: str = "largest_displacement") -> PoincareRun:
    """Fig. 3: the velocity before impact, period and amplitude for cycles 1 .. ``n_cycles``.

    Parameters
    ----------
    params : Parameters
        The model.
    x0 : float
        Release position (from rest), m.
    n_cycles : int
        Cycles to run.
    amplitude : str
        The amplitude's definition, a key of :data:`escapement.studies.readings.AMPLITUDES`.

    Returns
    -------
    PoincareRun
        The run, its amplitudes and Eq. (19)'s fixed point.

    Raises
    ------
    ParameterError
        If ``amplitude`` is not a known definition or ``n_cycles`` not a positive integer.
    """
    if amplitude not in AMPLITUDES:
        raise ParameterError("amplitude", amplitude, f"one of {', '.join(AMPLITUDES)}")
    n_cycles = positive_int("n_cycles", n_cycles)
    run = solve_exact(params, x0, n_cycles=n_cycles, record_trajectory=amplitude == "largest_abs_displacement")
    cycle, values = AMPLITUDES[amplitude].values(run)
    return PoincareRun(run, n_cycles, amplitude, quantity(amplitude).long_name, cycle, values,
                       fixed_point_19(params))


def shock(params: Parameters, x0: float, velocity_window: tuple[float, float],
          acceleration_window: tuple[float, float], samples_per_second: int) -> ShockRun:
    """Fig. 4: the motion sampled only over the union of both windows.

    Parameters
    ----------
    params : Parameters
        The model.
    x0 : float
        Release position (from rest), m.
    velocity_window, acceleration_window : tuple of float
        ``[start, end]`` of each panel, s.
    samples_per_second : int
        Rate of the uniform grid.

    Returns
    -------
    ShockRun
        The run and its sample times.

    Raises
    ------
    ParameterError
        If a window is not ``[start, end]`` with ``0 <= start < end`` or the rate not a positive integer.
    """
    v_lo, v_hi = time_window("velocity_window", velocity_window)
    a_lo, a_hi = time_window("acceleration_window", acceleration_window)
    rate = positive_int("samples_per_second", samples_per_second)
    lo, hi = min(v_lo, a_lo), max(v_hi, a_hi)
    run = solve_exact(params, x0, t_end=hi)
    # the velocity jumps at the impacts, the acceleration at every event: a sample on each side of each
    t = sample_times(np.linspace(lo, hi, int(round((hi - lo) * rate)) + 1), run.events.t)
    return ShockRun(run, t, (lo, hi), (v_lo, v_hi), (a_lo, a_hi), rate)


def phase(params: Parameters, x0: float, n_cycles: int, samples_per_period: int) -> PhaseRun:
    """Fig. 5: the phase trajectory from release to the end of cycle ``n_cycles``.

    Parameters
    ----------
    params : Parameters
        The model.
    x0 : float
        Release position (from rest), m.
    n_cycles : int
        Cycles to run.
    samples_per_period : int
        Samples per natural period of the uniform grid.

    Returns
    -------
    PhaseRun
        The run and its sample times.

    Raises
    ------
    ParameterError
        If ``n_cycles`` or ``samples_per_period`` is not a positive integer.
    """
    per_period = positive_int("samples_per_period", samples_per_period)
    n_cycles = positive_int("n_cycles", n_cycles)
    run = solve_exact(params, x0, n_cycles=n_cycles)
    end = run.t_final if np.isfinite(run.t_final) else (n_cycles + 1) * params.natural_period
    n = int(np.ceil(end / params.natural_period * per_period)) + 1
    ev = run.events
    impacts = ev.t[(ev.kind == int(EventKind.IMPACT_A1)) | (ev.kind == int(EventKind.IMPACT_A3))]
    t = sample_times(np.linspace(0.0, end, n), impacts)  # a sample on each side of each velocity jump
    return PhaseRun(run, t, n_cycles, per_period)
