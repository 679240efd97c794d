"""Candidate readings of the paper's unstated choices, and the data each figure panel would plot.

A :class:`Reading` is the points one panel would draw under one candidate reading, from the exact solver; their
extent is what an automatic axis scales to, so that the printed axes (:mod:`escapement.paper.printed_axes`) can tell
the readings apart, or fail to. The grid is the full product of the open choices (the tables below and each
figure's ``*_readings``); every run is made once (:class:`Runs`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..model.arguments import check_count
from ..model.events import EventKind
from ..model.parameters import Parameters
from ..paper.printed import period_23
from ..paper.printed_axes import FIG5_PANEL_K
from ..solvers.result import Solution
from .reading_series import SECTIONS, Runs, SectionCycles, critical_times, phase_series, section_cycles, window_series

__all__ = ["AMPLITUDES", "Amplitude", "FIG3_QUANTITIES", "FIG4_K", "FIG5_FORCES", "FIG5_RELEASES", "PAIRINGS",
           "RELEASES", "Reading", "Runs", "all_readings", "critical_times", "fig3_readings", "fig4_readings",
           "fig5_readings", "largest_abs_per_cycle", "step1_amplitudes", "window_series"]

#: the release sides: +1 releases at +|x0|, -1 at -|x0| (both at rest)
RELEASES: tuple[int, ...] = (+1, -1)
#: the spring constants tried for Fig. 4: the paper's (those of Fig. 5's panels), N/m
FIG4_K: tuple[float, ...] = tuple(FIG5_PANEL_K.values())
#: which printed window goes with which quantity in Fig. 4: as the panels are named, or swapped
PAIRINGS: tuple[str, ...] = ("as named", "swapped")
#: the forces tried for Fig. 5, N
FIG5_FORCES: tuple[float, ...] = (0.5, 1.0)
#: the release points tried for Fig. 5, m
FIG5_RELEASES: tuple[float, ...] = (-3.0, -1.0, 1.0, 3.0)


@dataclass(frozen=True)
class Reading:
    """The points one panel would draw under one reading; ``x`` and ``y`` pair up point by point."""

    figure: str  #: "3", "4" or "5"
    panel: str  #: the panel's name, as in :mod:`escapement.paper.printed_axes`
    name: str  #: the reading, in words
    x: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    outcome: str = "completed"  #: how the run ended (a reading of a run that left the regime says so)


#: the quantities a Fig. 3 panel may plot: panel, name, and the values for cycles k = 1..n of a section
FIG3_QUANTITIES: tuple[tuple[str, str, Callable[[SectionCycles, Parameters, int], np.ndarray]], ...] = (
    ("velocity", "speed before the impact", lambda c, p, n: c.speed[:n]),
    ("period", "period, impact to impact", lambda c, p, n: c.period[:n]),
    ("period", "Eq. (23) as printed", lambda c, p, n: np.array([period_23(float(v), p) for v in c.speed[:n]])),
    ("amplitude", "Step-1 amplitude h0(k)", lambda c, p, n: c.h0[:n]),
    ("amplitude", "Step-8 amplitude h4(k) = h0(k+1)", lambda c, p, n: c.h0[1:n + 1]),
    ("amplitude", "right turning point", lambda c, p, n: c.right[:n]),
    ("amplitude", "left turning point |x|", lambda c, p, n: c.left[:n]),
    ("amplitude", "largest |x|", lambda c, p, n: np.maximum(c.right, c.left)[:n]),
)


def _fig3_runs(runs: Runs, model: Mapping, cases: Mapping[str, Mapping], n_cycles: int) -> list[tuple]:
    """``(label, side, F, K, x0)`` per case and release side, each run's need stated: cycles k = 1..N+1 of either
    section, and h0(N+2) (N+2 cycles at a1 hold N+2 impacts at a3)."""
    keys = [(label, side, float(case["F"]), float(model["K"]), side * abs(float(case["x0"])))
            for label, case in cases.items() for side in RELEASES]
    for *_, F, K, x0 in keys:
        runs.need(F, K, x0, n_cycles=n_cycles + 2)
    return keys


def fig3_readings(model: Mapping, cases: Mapping[str, Mapping], n_cycles: int, runs: Runs | None = None
                  ) -> list[Reading]:
    """Fig. 3: per case (``F`` and ``|x0|``), release side, section, quantity and number of cycles (N or N + 1),
    the series against the cycle number."""
    check_count("n_cycles", n_cycles, 10**9)
    runs = Runs(model) if runs is None else runs
    readings = []
    for label, side, F, K, x0 in _fig3_runs(runs, model, cases, n_cycles):
        run, outcome = runs.get(F, K, x0), runs.outcome(F, K, x0, n_cycles=n_cycles + 2)
        for section in SECTIONS:
            cycles = section_cycles(run, section)
            for count, n in (("k = 1..N", n_cycles), ("k = 1..N+1", n_cycles + 1)):
                for quantity, name, values in FIG3_QUANTITIES:
                    y = np.asarray(values(cycles, run.params, n), dtype=float)
                    readings.append(Reading("3", f"{label}/{quantity}", f"from {'+' if side > 0 else '-'}x0, "
                                            f"section {section}; {name}; {count}",
                                            np.arange(1, len(y) + 1, dtype=float), y, outcome))
    return readings


@dataclass(frozen=True)
class Amplitude:
    """One definition of Fig. 3's "amplitude of oscillation": its value in each cycle of a run."""

    per_cycle: Callable[[Solution], np.ndarray] = field(repr=False)

    def values(self, run: Solution) -> tuple[np.ndarray, np.ndarray]:
        """The cycle numbers and the values of ``run``."""
        y = np.asarray(self.per_cycle(run), dtype=float)
        return np.arange(1, len(y) + 1, dtype=np.int32), y


def step1_amplitudes(run: Solution) -> np.ndarray:
    """``h0(k) = sqrt(a1**2 + (v_k / omega)**2)``, k = 1..N+1: the amplitude of the free arc ending in impact k."""
    ev = run.events
    i = ev.of_kind(EventKind.IMPACT_A1)
    return np.hypot(ev.x[i], ev.v_before[i] / run.params.omega)


def largest_abs_per_cycle(run: Solution) -> np.ndarray:
    """The largest ``|x|`` in each complete cycle (from impact k at a1 to impact k + 1)."""
    c = section_cycles(run, "a1")
    return np.maximum(c.right, c.left)[: len(run.cycles)]


#: the amplitudes a Fig. 3 scene may plot (``fig3.amplitude``), by the name of their variable, at the section a1
AMPLITUDES: dict[str, Amplitude] = {
    "amplitude_h0": Amplitude(step1_amplitudes),  # the Step-1 amplitude h0(k), k = 1..N+1
    "amplitude_h4": Amplitude(lambda run: step1_amplitudes(run)[1:len(run.cycles) + 1]),  # h0(k+1) = h4(k)
    "largest_displacement": Amplitude(lambda run: run.cycles.largest_displacement),
    "largest_abs_displacement": Amplitude(largest_abs_per_cycle),
}


def _fig4_runs(runs: Runs, cases: Mapping[str, Mapping], t_end: float, K_values: Iterable[float]) -> list[tuple]:
    """``(F, K, x0)`` for every force of the cases with every release magnitude (in the order met), ``K`` and release
    side, each run's need stated."""
    forces = dict.fromkeys(float(c["F"]) for c in cases.values())
    magnitudes = dict.fromkeys(abs(float(c["x0"])) for c in cases.values())
    keys = [(F, float(K), side * m) for F in forces for m in magnitudes for K in K_values for side in RELEASES]
    for key in keys:
        runs.need(*key, t_end=t_end)
    return keys


def fig4_readings(model: Mapping, cases: Mapping[str, Mapping], windows: Mapping[str, tuple[float, float]],
                  samples_per_second: float, K_values: Iterable[float] = FIG4_K, runs: Runs | None = None
                  ) -> list[Reading]:
    """Fig. 4: per force and release magnitude of the ``cases``, release side, ``K`` and pairing of the printed
    ``windows`` with the quantities (swapped: each over the other's window), the velocity and the acceleration."""
    if set(windows) != {"velocity", "acceleration"}:
        raise ValueError(f"windows has the keys {sorted(windows)}; it must have 'velocity' and 'acceleration'")
    runs = Runs(model) if runs is None else runs
    t_end = max(hi for _, hi in windows.values())
    readings = []
    for F, K, x0 in _fig4_runs(runs, cases, t_end, tuple(K_values)):
        run, outcome = runs.get(F, K, x0), runs.outcome(F, K, x0, t_end=t_end)
        for pairing in PAIRINGS:
            drawn = dict(windows) if pairing == "as named" else {
                "velocity": windows["acceleration"], "acceleration": windows["velocity"]}
            spans = ", ".join(f"{q} {lo:g}-{hi:g} s" for q, (lo, hi) in drawn.items())
            name = f"F = {F:g} N, x0 = {x0:+g} m, K = {K:g} N/m; {spans}"
            for quantity, (lo, hi) in drawn.items():
                t, y = window_series(run, lo, hi, samples_per_second, quantity)
                readings.append(Reading("4", quantity, name, t, y, outcome))
    return readings


def _fig5_runs(runs: Runs, panels: Mapping[str, float], n_cycles: int, forces: Iterable[float],
               releases: Iterable[float]) -> list[tuple]:
    """``(panel, F, K, x0)`` per panel (its ``K``), force and release, each run's need stated."""
    forces, releases = tuple(map(float, forces)), tuple(map(float, releases))
    keys = [(panel, F, float(K), x0) for panel, K in panels.items() for F in forces for x0 in releases]
    for _, F, K, x0 in keys:
        runs.need(F, K, x0, n_cycles=n_cycles)
    return keys


def fig5_readings(model: Mapping, panels: Mapping[str, float], n_cycles: int, samples_per_period: int,
                  forces: Iterable[float] = FIG5_FORCES, releases: Iterable[float] = FIG5_RELEASES,
                  runs: Runs | None = None) -> list[Reading]:
    """Fig. 5: per panel (its ``K``), force and release, the phase points to the end of cycle ``n_cycles`` and of
    that cycle alone."""
    runs = Runs(model) if runs is None else runs
    readings = []
    for panel, F, K, x0 in _fig5_runs(runs, panels, n_cycles, forces, releases):
        run, outcome = runs.get(F, K, x0), runs.outcome(F, K, x0, n_cycles=n_cycles)
        rate = samples_per_period / run.params.natural_period
        head = f"F = {F:g} N, x0 = {x0:+g} m"
        c = run.cycles
        n = min(len(c), n_cycles)
        if n:
            end = float(c.impact_time[n - 1] + c.period[n - 1])
        else:
            end = run.t_final if math.isfinite(run.t_final) else (n_cycles + 1) * run.params.natural_period
        x, v = phase_series(run, 0.0, end, rate)
        readings.append(Reading("5", panel, f"{head}; whole trajectory, {n_cycles} cycles", x, v, outcome))
        x, v = phase_series(run, float(c.impact_time[n - 1]), end, rate) if n else (np.full(1, np.nan),) * 2
        readings.append(Reading("5", panel, f"{head}; last cycle", x, v, outcome))
    return readings


def all_readings(settings: Mapping, runs: Runs | None = None) -> list[Reading]:
    """Every reading of Figs. 3-5 for the configuration's blocks ``settings`` (Fig. 5's panels lettered by ``K``)."""
    if missing := {"model", "fig3", "fig4", "fig5"} - set(settings):
        raise ValueError(f"settings has the blocks {sorted(settings)}; it must have {sorted(missing)}")
    model = settings["model"]
    fig3, fig4, fig5 = settings["fig3"], settings["fig4"], settings["fig5"]
    windows = {"velocity": tuple(fig4["velocity_window"]), "acceleration": tuple(fig4["acceleration_window"])}
    panels = dict(zip("abcdefghij", (float(K) for K in fig5["K"])))
    runs = Runs(model) if runs is None else runs
    _fig3_runs(runs, model, fig3["cases"], int(fig3["n_cycles"]))
    _fig4_runs(runs, fig3["cases"], max(hi for _, hi in windows.values()), FIG4_K)
    _fig5_runs(runs, panels, int(fig5["n_cycles"]), FIG5_FORCES, FIG5_RELEASES)
    return [*fig3_readings(model, fig3["cases"], int(fig3["n_cycles"]), runs),
            *fig4_readings(model, fig3["cases"], windows, float(fig4["samples_per_second"]), runs=runs),
            *fig5_readings(model, panels, int(fig5["n_cycles"]), int(fig5["samples_per_period"]), runs=runs)]
