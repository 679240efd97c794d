"""Further checks on the figures of Sec. 4 and on the Poincare section of Sec. 3.4.

* ``section_crossings``: "each cycle only contains one such state", a crossing of
  Sigma = {x = a1, xdot > 0} (Eq. (7)), counted on the sampled trajectory of the exact solver for each
  Fig. 3 case between successive impacts at a1 (by the checks scene: ``crossings`` of the checks dataset);
* ``window_impact``: Fig. 4 "shows the neighborhood where the impact occurs": an impact in both printed
  time windows under every reading of Fig. 4's grid (the printed axes leave the reading undetermined; the runs'
  impacts are the ``window_impact_time`` of the checks dataset);
* ``fig5_dimensions``: "the dimensions of the limit cycles are different", at one common force
  (the panels are run at different forces);
* ``fig5_impact_visible``: "impact is also clearly shown": the velocity jump at the impact,
  ``b v1``, as a fraction of the panel's printed velocity range.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .checks import Evidence, Verdict, check, fig3_all, fmt, probe, runs_only
from .printed_axes import FIG5_PANEL_K, panel
from .section4_checks import NOT_COMPARED, common_force_runs

__all__ = ["section_crossing_counts"]


def _fig5(claim, ev: Evidence) -> dict[str, xr.Dataset]:
    return {f"Fig. 5 K = {label}": ds for label, ds in ev.fig5.items()}


# --- Sec. 3.4: one crossing of the Poincare section per cycle -----------------------------------


def section_crossing_counts(t: np.ndarray, x: np.ndarray, v: np.ndarray, a1: float, starts: np.ndarray) -> np.ndarray:
    """Crossings of Sigma (x rising through a1 with xdot > 0) of the samples ``t, x, v`` in each cycle, from one
    impact at a1 (``starts``) to the next."""
    up = np.flatnonzero((x[:-1] < a1) & (x[1:] >= a1) & (v[1:] > 0))
    crossings = t[up + 1]
    slack = 1e-9 * max(1.0, float(t[-1]))
    return np.array([np.count_nonzero((crossings >= s - slack) & (crossings < e - slack))
                     for s, e in zip(starts[:-1], starts[1:])], dtype=int)


@check("section_crossings", scenes=fig3_all, args=("samples_per_period",))
def section_crossings(claim, ev: Evidence) -> Verdict:
    made = int(ev.checks["crossings"].attrs["samples_per_period"])
    if made != int(claim["args"]["samples_per_period"]):
        raise ValueError(f"the checks dataset's crossings are counted at {made} samples per period")
    rows = []
    for label in ev.fig3:
        counts = probe(ev, "crossings", "crossing_case", crossing_case_label=label).values
        rows.append((label, counts[np.isfinite(counts)].astype(int)))
    if any(not len(counts) for _, counts in rows):
        raise ValueError("a Fig. 3 run holds no complete cycle between two impacts at a1")
    return Verdict(
        "; ".join(f"case {label}: {len(c)} cycles, crossings per cycle {int(c.min())}-{int(c.max())}"
                  for label, c in rows),
        all((counts == 1).all() for _, counts in rows),
        note=("counted on the exact solver's trajectory of each Fig. 3 case, sampled "
              f"{claim['args']['samples_per_period']} times per natural period (x rising through a1 with xdot > 0), "
              "between successive impacts at a1; the one crossing is the impact itself, which maps (a1, x1) to "
              "(a1, (1-b) x1): both states lie on Sigma, at one instant, and the map (8) takes the state before it"),
        paper_value="one state on Sigma per cycle",
    )


# --- Fig. 4: the window holds the impact --------------------------------------------------------


@check("window_impact", scenes=fig3_all)
def window_impact(claim, ev: Evidence) -> Verdict:
    """Under every reading of Fig. 4's grid (every force and release magnitude of the Fig. 3 cases, either side,
    every spring constant of Fig. 5), an impact lies in each printed time window; each run exactly to the
    windows' end, with the model's other parameters those of the Fig. 3 cases."""
    windows = [(a.low, a.high) for a in (panel("4", "velocity").x, panel("4", "acceleration").x)]
    if (t_end := ev.checks["window_impact_time"].attrs["t_end"]) < max(w[1] for w in windows):
        raise ValueError(f"the checks dataset's runs for Fig. 4 end at {t_end} s, before the windows")
    forces = sorted({float(ds["F"]) for ds in ev.fig3.values()})
    magnitudes = sorted({abs(float(ds["x0"])) for ds in ev.fig3.values()})
    held = {}
    for F in forces:
        for K in FIG5_PANEL_K.values():
            for x0 in (side * m for m in magnitudes for side in (-1.0, 1.0)):
                impacts = probe(ev, "window_impact_time", "window_run", window_F=F, window_K=K, window_x0=x0).values
                held[f"F = {fmt(F, 3)} N, K = {fmt(K, 3)} N/m, x0 = {fmt(x0, 3)} m"] = all(
                    bool(np.any((impacts >= lo) & (impacts <= hi))) for lo, hi in windows)
    return Verdict(
        f"an impact in both windows ({'; '.join(f'{fmt(lo, 3)}-{fmt(hi, 3)} s' for lo, hi in windows)}) under "
        f"{sum(held.values())} of the {len(held)} readings of the grid"
        + "".join(f"; none under {name}" for name, h in held.items() if not h), held,
        note=(f"the grid: every force and release magnitude of the Fig. 3 cases, either side, every spring constant "
              f"of the paper (K = {', '.join(fmt(k, 3) for k in FIG5_PANEL_K.values())} N/m), since the printed axes "
              "leave Fig. 4's reading undetermined (REPLICATION.md, Sec. 3)"),
        paper_value="the window holds the impact",
    )


# --- Fig. 5: the limit cycles differ, and the impact shows --------------------------------------


@check("fig5_dimensions", scenes=runs_only, threshold="'different' taken as apart by the tolerance of the larger")
def fig5_dimensions(claim, ev: Evidence) -> Verdict:
    """The limit cycles of the spring constants differ in size at one common force: their half-widths
    (the converged amplitude) or half-heights (the largest speed on the last cycle, exact) differ by more
    than ``tolerance`` of the larger, for every pair, at every force."""
    by_force, left = common_force_runs(ev)
    if left is not None:
        return left
    differ, parts = [], []
    for force, runs in by_force.items():
        rows = [(k, float(run["largest_displacement"]), float(run["largest_speed"])) for k, run in runs]
        for i, (_, x1, v1) in enumerate(rows):
            for _, x2, v2 in rows[i + 1:]:
                differ.append(max(abs(x1 - x2) / max(x1, x2), abs(v1 - v2) / max(v1, v2)) > claim["tolerance"])
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(
            f"K = {fmt(k, 3)}: {fmt(x, 4)} m x {fmt(v, 4)} m/s" for k, x, v in rows))
    return Verdict(
        "limit cycle half-width (amplitude) x half-height (largest speed): " + "; ".join(parts),
        bool(differ) and all(differ),
        note=(f"two limit cycles differ when their amplitudes or largest speeds differ by more than "
              f"{fmt(100 * claim['tolerance'], 3)} % of the larger; {NOT_COMPARED}"),
        paper_value="the limit cycles have different dimensions",
    )


def _panel_of(k: float) -> str:
    for name, panel_k in FIG5_PANEL_K.items():
        if math.isclose(k, panel_k, rel_tol=1e-12):
            return name
    raise ValueError(f"no printed panel of Fig. 5 has K = {k:g} N/m")


@check("fig5_impact_visible", scenes=_fig5, fitted="Fig. 5's force and release, and the whole trajectory drawn",
       threshold="'clearly shown' taken as a jump of the tolerance of the printed velocity range")
def fig5_impact_visible(claim, ev: Evidence) -> Verdict:
    """The impact is shown in a panel when a velocity jump the panel draws (each impact at a1 of the
    whole trajectory, b x1) is at least ``tolerance`` of the panel's printed velocity range."""
    rows = []
    for k, ds in sorted(((float(ds["K"]), ds) for ds in ev.fig5.values()), key=lambda kv: kv[0]):
        name = _panel_of(k)
        axis = panel("5", name).y
        span = axis.high - axis.low
        jumps = float(ds["b"]) * np.abs(ds["velocity_before_impact"].values)
        rows.append((k, name, float(jumps.max()), float(jumps[-1]), span))
    shown = [largest / span >= claim["tolerance"] for _, _, largest, _, span in rows]
    return Verdict(
        "largest velocity jump drawn (impacts at a1 of the whole trajectory), and on the limit cycle: " + "; ".join(
            f"({name}) K = {fmt(k, 3)}: {fmt(largest, 3)} m/s, {fmt(100 * largest / span, 3)} % of the printed "
            f"{fmt(span, 3)} m/s (limit cycle {fmt(100 * last / span, 3)} %)"
            for k, name, largest, last, span in rows),
        all(shown),
        note=(f"the jump b x1 (the impact law) at each impact at a1 against the panel's printed velocity range; "
              "'clearly shown' "
              f"taken as at least {fmt(100 * claim['tolerance'], 3)} % of it (about a millimetre on a panel 5 cm "
              "tall) for some jump the panel draws; the panels draw the whole trajectory, whose early impacts, far "
              "from the limit cycle, jump most"),
        paper_value="impact clearly shown",
    )
