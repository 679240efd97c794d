"""The checks of Sec. 4 on Fig. 5, the spring-constant sweep: the limit cycles compared between spring constants at
one common force (the panels, at different forces, are not compared), and the impact shown in each panel.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ..paper import corrected as derived
from ..paper.printed_axes import FIG5_PANEL_K, panel
from .sec4_fig3 import amplitude_of
from .evidence import Evidence, Verdict, check, each, fmt, params_of, run


def common_force_runs(claim, ev: Evidence) -> dict[float, list[tuple[float, xr.Dataset]]]:
    """The claim's runs by force, each list ordered by K: only runs at one force are compared."""
    by_force: dict[float, list] = {}
    for r in each(run(ev, claim["args"]["runs"])):
        by_force.setdefault(float(r["F"]), []).append((float(r["K"]), r))
    if any(len(rows) < 2 for rows in by_force.values()):
        raise ValueError(f"the runs {claim['args']['runs']!r} must give at least two spring constants at each force")
    return {f: sorted(rows, key=lambda kv: kv[0]) for f, rows in sorted(by_force.items())}


NOT_COMPARED = ("the panels of Fig. 5 run at different forces (the configuration's fig5.F), so they are not "
                "compared with each other; each spring constant is run at each force of the figure from the "
                "figure's release and compared at one force")


def _along_K(claim, ev: Evidence, what: str, value, digits: int, unit: str, increasing: bool = False) -> Verdict:
    """Holds when ``value(run)``, ``what`` it is, decreases (or increases) with K at every common force."""
    holds, parts = [], []
    for force, rows in common_force_runs(claim, ev).items():
        values = [value(run) for _, run in rows]
        holds.append(all(b > a if increasing else a > b for a, b in zip(values, values[1:])))
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(f"K = {fmt(k, 3)}: {fmt(x, digits)} {unit}"
                                                          for (k, _), x in zip(rows, values)))
    return Verdict(f"{what}: " + "; ".join(parts), all(holds), note=NOT_COMPARED)


@check(runs=("runs",), args=("definition",))
def fig5_amplitude_common_force(claim, ev: Evidence) -> Verdict:
    """The converged amplitude (:func:`.sec4_fig3.amplitude_of`) decreases with K at each common force."""
    return _along_K(claim, ev, "converged amplitude", lambda r: amplitude_of(r, claim["args"]["definition"]), 5, "m")


#: the speeds a "maximum velocity" may be: the columns of the checks dataset
SPEEDS = {"largest_speed": "largest |v| on the limit cycle (exact, from the closed forms of its arcs)",
          "velocity": "velocity before the impact at a1 on the limit cycle"}


@check(runs=("runs",), args=("speed",))
def fig5_velocity_common_force(claim, ev: Evidence) -> Verdict:
    """The speed ``args: {speed}`` (a key of :data:`SPEEDS`) decreases with K at each common force."""
    speed = claim["args"]["speed"]
    return _along_K(claim, ev, SPEEDS[speed], lambda r: float(r[speed]), 6, "m/s")


@check(runs=("runs",), args=("measure",))
def fig5_recovery_common_force(claim, ev: Evidence) -> Verdict:
    """The velocity before the impact at a1 recovers faster for smaller K at each common force, by the ``measure``."""
    measure = claim["args"]["measure"]

    def recovery(r) -> float:
        p = params_of(r)
        x, time = derived.velocity_recovery(float(r["velocity"]), p)
        return {"seconds": time, "period": time / p.natural_period,
                "width": (x - p.a1) / (2 * float(r["largest_displacement"]))}[measure]

    unit = {"seconds": "s", "period": "of 2 pi/w", "width": "of the width"}[measure]
    return _along_K(claim, ev, "to regain the velocity before the impact at a1", recovery, 4, unit, increasing=True)


@check(runs=("runs",), threshold="'different' taken as apart by the tolerance of the larger")
def fig5_dimensions(claim, ev: Evidence) -> Verdict:
    """At every common force, every pair of limit cycles differs in half-width or half-height by over ``tolerance``."""
    differ, parts = [], []
    for force, runs in common_force_runs(claim, ev).items():
        rows = [(k, float(r["largest_displacement"]), float(r["largest_speed"])) for k, r in runs]
        differ += [max(abs(x1 - x2) / max(x1, x2), abs(v1 - v2) / max(v1, v2)) > claim["tolerance"]
                   for i, (_, x1, v1) in enumerate(rows) for _, x2, v2 in rows[i + 1:]]
        parts.append(f"F = {fmt(force, 3)} N: " + ", ".join(
            f"K = {fmt(k, 3)}: {fmt(x, 4)} m x {fmt(v, 4)} m/s" for k, x, v in rows))
    return Verdict("limit cycle half-width (amplitude) x half-height (largest speed): " + "; ".join(parts),
                   bool(differ) and all(differ), paper_value="the limit cycles have different dimensions",
                   note=(f"two limit cycles differ when their amplitudes or largest speeds differ by more than "
                         f"{fmt(100 * claim['tolerance'], 3)} % of the larger; {NOT_COMPARED}"))


@check(scenes=lambda claim, ev: {f"Fig. 5 K = {label}": ds for label, ds in ev.fig5.items()},
       fitted="Fig. 5's force and release, and the whole trajectory drawn",
       threshold="'clearly shown' taken as a jump of the tolerance of the printed velocity range")
def fig5_impact_visible(claim, ev: Evidence) -> Verdict:
    """The impact shows in a panel when a velocity jump it draws is at least ``tolerance`` of its printed range."""
    rows = []
    for k, ds in sorted(((float(ds["K"]), ds) for ds in ev.fig5.values()), key=lambda kv: kv[0]):
        name = next((n for n, panel_k in FIG5_PANEL_K.items() if math.isclose(k, panel_k, rel_tol=1e-12)), None)
        if name is None:
            raise ValueError(f"no printed panel of Fig. 5 has K = {k:g} N/m")
        jumps = float(ds["b"]) * np.abs(ds["velocity_before_impact"].values)
        rows.append((k, name, float(jumps.max()), float(jumps[-1]), panel("5", name).y.high - panel("5", name).y.low))
    return Verdict(
        "largest velocity jump drawn (impacts at a1 of the whole trajectory), and on the limit cycle: " + "; ".join(
            f"({name}) K = {fmt(k, 3)}: {fmt(largest, 3)} m/s, {fmt(100 * largest / span, 3)} % of the printed "
            f"{fmt(span, 3)} m/s (limit cycle {fmt(100 * last / span, 3)} %)" for k, name, largest, last, span in rows),
        all(largest / span >= claim["tolerance"] for _, _, largest, _, span in rows),
        note=(f"the jump b x1 (the impact law) at each impact at a1 against the panel's printed velocity range; "
              f"'clearly shown' taken as at least {fmt(100 * claim['tolerance'], 3)} % of it (about a millimetre on a "
              "panel 5 cm tall) for some jump the panel draws; the panels draw the whole trajectory, whose early "
              "impacts, far from the limit cycle, jump most"), paper_value="impact clearly shown")
