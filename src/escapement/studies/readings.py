"""Candidate readings of the paper's unstated choices, and the data each figure panel would plot.

The paper leaves open how its Figs. 3-5 were made: where the mass is released, what "amplitude"
means, which case Fig. 4 shows, which force and initial displacement Fig. 5 uses. Each candidate
reading is a :class:`Reading`: the points ``(x, y)`` one panel would draw under it, from the
exact solver (:func:`escapement.solvers.exact.solve_exact`). Their extent is what an automatic
axis scales to, so the printed axes (:mod:`escapement.paper.printed_axes`) can tell the readings
apart; the scoring is :mod:`escapement.pipeline.readings`.

The readings:

* **Release.** From rest at ``+x0`` (the first event is the impact at a3) or at ``-x0`` (the
  paper's Step 1: the first half cycle moves left to right, from the left turning point, and
  Eq. (22a) takes ``h0`` as the initial amplitude; the first event is the impact at a1).
* **Fig. 3**, per case and release: the velocity before the impact at a1, cycles 1..N; the
  period, impact to impact, and Eq. (23) as printed at the same velocities; four amplitudes:
  the largest displacement in each cycle, the largest ``|x|`` in each cycle, the Step-1
  amplitude ``h0(k) = sqrt(a1**2 + (v_k / omega)**2)`` of the free arc that ends in impact k
  for ``k = 1..N+1`` (Eq. (9b): ``h0(k+1) = h4(k)``, so the run's last impact gives one more),
  and the Step-8 amplitude ``h4(k) = h0(k+1)``, ``k = 1..N``.
* **Fig. 4**: case (a) or (b), ``K`` of 0.1, 1 or 10 N/m, release side; the velocity or the
  acceleration over each printed window. The velocity jumps at each impact: both the velocity
  before and after it are drawn. The acceleration is the smooth ``-omega**2 (x - centre)``,
  which jumps by ``F/M`` where an impulse zone begins or ends: both one-sided values are drawn
  (the impact itself is a Dirac impulse, not a plottable value).
* **Fig. 5**, per panel (its ``K``): ``F`` of 0.5 or 1 N, release at -3, -1, +1 or +3 m; the whole
  phase trajectory from the release to the end of cycle N, or the last cycle only (the limit
  cycle as drawn after convergence). Impacts are vertical jumps.

Every series holds its exact extremes: besides a regular grid, each harmonic arc is sampled where
its phase is a multiple of pi/2 (the turning points and the passages through the arc's centre,
where ``|v|`` peaks), and each event adds its one-sided values.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..model.events import EventKind
from ..model.parameters import Parameters
from ..paper.printed import period_23
from ..solvers.exact import solve_exact
from ..solvers.result import Solution

__all__ = [
    "AMPLITUDES",
    "Amplitude",
    "FIG4_K",
    "FIG5_FORCES",
    "FIG5_RELEASES",
    "RELEASES",
    "Reading",
    "all_readings",
    "critical_times",
    "fig3_readings",
    "fig4_readings",
    "fig5_readings",
    "largest_abs_per_cycle",
    "release_name",
    "step1_amplitudes",
    "window_series",
]

#: the release sides: +1 releases at +x0, -1 at -x0 (both at rest)
RELEASES: tuple[int, ...] = (+1, -1)
#: the spring constants tried for Fig. 4, N/m
FIG4_K: tuple[float, ...] = (0.1, 1.0, 10.0)
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


def release_name(side: int) -> str:
    """``"release +x0"`` or ``"release -x0"``."""
    return "release +x0" if side > 0 else "release -x0"


def _params(model: Mapping, **override: float) -> Parameters:
    return Parameters.from_mapping({**model, **override})


def _outcome(run: Solution) -> str:
    return run.status.value if run.success else f"{run.status.value}: {run.message}"


# --- exact extremes of the sampled motion ------------------------------------------------------


def critical_times(run: Solution, lo: float, hi: float) -> np.ndarray:
    """The times in ``[lo, hi]`` at which an arc of ``run`` has a phase that is a multiple of pi/2:
    the turning points (extremes of ``x`` and of the acceleration) and the passages through the
    arc's centre (extremes of the velocity)."""
    arcs = run.trajectory
    if arcs is None:
        raise ValueError("the run kept no trajectory; solve with record_trajectory=True")
    start = np.asarray(arcs.t_start, dtype=float)
    end = np.append(start[1:], arcs.t_final)
    keep = (end >= lo) & (start <= hi)
    start, end = start[keep], end[keep]
    u0 = np.asarray(arcs.x_start)[keep] - np.asarray(arcs.centre)[keep]
    w = arcs.omega
    # x - centre = A cos(w (t - start) - phi): critical where w (t - start) = phi + k pi/2
    phi = np.arctan2(np.asarray(arcs.v_start)[keep] / w, u0)
    quarter = 0.5 * math.pi
    k_first = np.ceil(-phi / quarter).astype(int)
    k_last = np.floor((w * (np.minimum(end, hi) - start) - phi) / quarter).astype(int)
    times = [s + (p + np.arange(a, b + 1) * quarter) / w
             for s, p, a, b in zip(start, phi, k_first, k_last) if b >= a]
    if not times:
        return np.empty(0)
    t = np.concatenate(times)
    return np.sort(t[(t >= lo) & (t <= hi)])


def _events_in(run: Solution, lo: float, hi: float) -> np.ndarray:
    return np.flatnonzero((run.events.t >= lo) & (run.events.t <= hi))


def _centres_at_events(run: Solution, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The centre of oscillation just before and just after each event of ``index``."""
    arcs = run.trajectory
    t_event = run.events.t[index]
    after = np.searchsorted(arcs.t_start, t_event, side="left")
    if np.any(after >= len(arcs.t_start)) or not np.array_equal(arcs.t_start[after], t_event):
        raise ValueError("an event has no arc starting at its time")
    return arcs.centre[after - 1], arcs.centre[after]


def window_series(run: Solution, lo: float, hi: float, samples_per_second: float, quantity: str
                  ) -> tuple[np.ndarray, np.ndarray]:
    """``(t, values)`` of ``quantity`` ("displacement", "velocity" or "acceleration") over ``[lo, hi]``
    as a plot would draw it: a regular grid, the exact extremes of each arc, and at each event in
    the window its values just before and just after (in that order, at the event's time)."""
    n = max(2, int(round((hi - lo) * samples_per_second)) + 1)
    t = np.union1d(np.linspace(lo, hi, n), critical_times(run, lo, hi))
    column = {"displacement": 0, "velocity": 1, "acceleration": 2}[quantity]
    values = run.sample(t)[column]
    index = _events_in(run, lo, hi)
    if quantity == "displacement":
        before = after = run.events.x[index]
    elif quantity == "velocity":
        before, after = run.events.v_before[index], run.events.v_after[index]
    else:
        w2 = run.params.omega2
        c_before, c_after = _centres_at_events(run, index)
        before = -w2 * (run.events.x[index] - c_before)
        after = -w2 * (run.events.x[index] - c_after)
    t_events = np.repeat(run.events.t[index], 2)
    jumps = np.ravel(np.column_stack([before, after]))
    order = np.argsort(np.concatenate([t, t_events]), kind="stable")
    return np.concatenate([t, t_events])[order], np.concatenate([values, jumps])[order]


def _phase_series(run: Solution, lo: float, hi: float, samples_per_second: float) -> tuple[np.ndarray, np.ndarray]:
    """``(x, v)`` over ``[lo, hi]``: the regular grid, the arcs' extremes, and each event as a
    vertical jump at its position."""
    n = max(2, int(round((hi - lo) * samples_per_second)) + 1)
    t = np.union1d(np.linspace(lo, hi, n), critical_times(run, lo, hi))
    x, v, _ = run.sample(t)
    index = _events_in(run, lo, hi)
    ev = run.events
    t_all = np.concatenate([t, np.repeat(ev.t[index], 2)])
    x_all = np.concatenate([x, np.repeat(ev.x[index], 2)])
    v_all = np.concatenate([v, np.ravel(np.column_stack([ev.v_before[index], ev.v_after[index]]))])
    order = np.argsort(t_all, kind="stable")
    return x_all[order], v_all[order]


# --- amplitudes --------------------------------------------------------------------------------


@dataclass(frozen=True)
class Amplitude:
    """One definition of Fig. 3's "amplitude of oscillation": its long name, and the values per
    cycle with the cycle numbers they belong to."""

    label: str  #: short name, as the score table of the readings names it
    long_name: str
    values: Callable[[Solution], tuple[np.ndarray, np.ndarray]] = field(repr=False)


def _per_cycle(values: Callable[[Solution], np.ndarray]) -> Callable[[Solution], tuple[np.ndarray, np.ndarray]]:
    def of(run: Solution) -> tuple[np.ndarray, np.ndarray]:
        y = np.asarray(values(run), dtype=float)
        return np.arange(1, len(y) + 1, dtype=np.int32), y
    return of


#: The definitions of the amplitude a Fig. 3 scene may plot (the configuration's ``fig3.amplitude``).
#: The printed axes favour ``step1`` (REPLICATION.md, the readings of the printed axes).
AMPLITUDES: dict[str, Amplitude] = {
    "step1": Amplitude(
        "Step-1 amplitude h0(k), k = 1..N+1",
        "Step-1 amplitude h0(k) = sqrt(a1^2 + (v_k / omega)^2) of the free arc that ends in impact k at a1 "
        "(k = 1 .. N+1; Eqs. (9b), (22a))",
        _per_cycle(lambda run: step1_amplitudes(run)),
    ),
    "step8": Amplitude(
        "Step-8 amplitude h4(k) = h0(k+1), k = 1..N",
        "Step-8 amplitude h4(k) = h0(k+1) of the free arc that ends cycle k (k = 1 .. N)",
        _per_cycle(lambda run: step1_amplitudes(run)[1:len(run.cycles) + 1]),
    ),
    "largest_displacement": Amplitude(
        "largest displacement per cycle",
        "largest displacement between impact k and impact k+1 (right turning point)",
        _per_cycle(lambda run: run.cycles.amplitude),
    ),
    "largest_abs": Amplitude(
        "largest |x| per cycle",
        "largest |x| between impact k and impact k+1",
        _per_cycle(lambda run: largest_abs_per_cycle(run)),
    ),
}


def step1_amplitudes(run: Solution) -> np.ndarray:
    """``h0(k)``, k = 1, 2, ...: the amplitude ``sqrt(a1**2 + (v / omega)**2)`` of the free arc
    that ends in the k-th impact at a1 (``v`` the velocity before it), for every such impact of
    the run (N + 1 of them in a run of N complete cycles)."""
    ev = run.events
    i = ev.of_kind(EventKind.IMPACT_A1)
    return np.hypot(ev.x[i], ev.v_before[i] / run.params.omega)


def largest_abs_per_cycle(run: Solution) -> np.ndarray:
    """The largest ``|x|`` in each complete cycle (from impact k at a1 to impact k + 1)."""
    c = run.cycles
    out = np.empty(len(c))
    for k, (t0, period) in enumerate(zip(c.impact_time, c.period)):
        t = np.union1d([t0, t0 + period], critical_times(run, t0, t0 + period))
        out[k] = np.nanmax(np.abs(run.sample(t)[0]))
    return out


# --- the figures -------------------------------------------------------------------------------


def fig3_readings(model: Mapping, cases: Mapping[str, Mapping], n_cycles: int) -> list[Reading]:
    """Fig. 3: per case (a mapping with ``F`` and ``x0``) and release side, the velocity, period
    and amplitude series against the cycle number."""
    readings = []
    for label, case in cases.items():
        p = _params(model, F=float(case["F"]))
        x0 = abs(float(case["x0"]))
        for side in RELEASES:
            run = solve_exact(p, side * x0, n_cycles=n_cycles)
            outcome = _outcome(run)
            c = run.cycles
            k = np.arange(1, len(c) + 1, dtype=float)
            release = release_name(side)

            def add(quantity: str, name: str, y: np.ndarray, x: np.ndarray = k) -> None:
                readings.append(Reading("3", f"{label}/{quantity}", f"{release}; {name}", x, np.asarray(y, float),
                                        outcome))

            add("velocity", "velocity before the impact at a1", c.velocity_before_impact)
            add("period", "period, impact to impact", c.period)
            add("period", "Eq. (23) as printed", [period_23(float(v), p) for v in c.velocity_before_impact])
            for name in ("largest_displacement", "largest_abs", "step1", "step8"):
                cycle, values = AMPLITUDES[name].values(run)
                add("amplitude", AMPLITUDES[name].label, values, cycle.astype(float))
    return readings


def fig4_readings(model: Mapping, cases: Mapping[str, Mapping], windows: Mapping[str, tuple[float, float]],
                  samples_per_second: float, K_values: Iterable[float] = FIG4_K) -> list[Reading]:
    """Fig. 4: per case, ``K``, release side, panel (its window) and quantity (velocity or
    acceleration), the series against time. ``windows`` maps each panel's name to its window."""
    readings = []
    t_end = max(hi for _, hi in windows.values())
    for label, case in cases.items():
        for K in K_values:
            p = _params(model, F=float(case["F"]), K=float(K))
            x0 = abs(float(case["x0"]))
            for side in RELEASES:
                run = solve_exact(p, side * x0, t_end=t_end)
                for panel, (lo, hi) in windows.items():
                    for quantity in ("velocity", "acceleration"):
                        t, y = window_series(run, lo, hi, samples_per_second, quantity)
                        name = (f"case ({label}) F = {p.F:g} N, x0 = {side * x0:+g} m, K = {p.K:g} N/m; "
                                f"{quantity} over {lo:g}-{hi:g} s")
                        readings.append(Reading("4", panel, name, t, y, _outcome(run)))
    return readings


def fig5_readings(model: Mapping, panels: Mapping[str, float], n_cycles: int, samples_per_period: int,
                  forces: Iterable[float] = FIG5_FORCES, releases: Iterable[float] = FIG5_RELEASES) -> list[Reading]:
    """Fig. 5: per panel (its ``K``), force and release point, the phase points of the whole
    trajectory (release to the end of cycle ``n_cycles``) and of the last cycle."""
    readings = []
    for panel, K in panels.items():
        for F in forces:
            p = _params(model, F=float(F), K=float(K))
            rate = samples_per_period / p.natural_period
            for x0 in releases:
                run = solve_exact(p, float(x0), n_cycles=n_cycles)
                outcome = _outcome(run)
                head = f"F = {p.F:g} N, x0 = {float(x0):+g} m"
                end = run.t_final if math.isfinite(run.t_final) else (n_cycles + 1) * p.natural_period
                x, v = _phase_series(run, 0.0, end, rate)
                readings.append(Reading("5", panel, f"{head}; whole trajectory, {n_cycles} cycles", x, v, outcome))
                if len(run.cycles):
                    t0 = float(run.cycles.impact_time[-1])
                    x, v = _phase_series(run, t0, t0 + float(run.cycles.period[-1]), rate)
                else:
                    x = v = np.full(1, np.nan)
                readings.append(Reading("5", panel, f"{head}; last cycle", x, v, outcome))
    return readings


def all_readings(settings: Mapping) -> list[Reading]:
    """Every reading of Figs. 3-5 for ``settings``, a mapping with the configuration's blocks
    ``model``, ``fig3`` (``n_cycles``, ``cases``), ``fig4`` (``velocity_window``,
    ``acceleration_window``, ``samples_per_second``) and ``fig5`` (``K``, ``n_cycles``,
    ``samples_per_period``); the Fig. 5 panels are lettered a, b, c in the order of ``K``."""
    model = settings["model"]
    fig3, fig4, fig5 = settings["fig3"], settings["fig4"], settings["fig5"]
    windows = {"velocity": tuple(fig4["velocity_window"]), "acceleration": tuple(fig4["acceleration_window"])}
    letters = "abcdefghij"
    return [
        *fig3_readings(model, fig3["cases"], int(fig3["n_cycles"])),
        *fig4_readings(model, fig3["cases"], windows, float(fig4["samples_per_second"])),
        *fig5_readings(model, dict(zip(letters, (float(K) for K in fig5["K"]))), int(fig5["n_cycles"]),
                       int(fig5["samples_per_period"])),
    ]
