"""Checks of what Sec. 3.4 infers about stability: "Therefore mu1 = 1" from the two-dimensional map of
Eq. (8), and "the solution is asymptotically stable" from mu1 = 1, |mu2| < 1.

* ``map8_eigenvalues``: the map (8) as printed, ``P(y) = (a1, g(y2))``, has the Jacobian
  ``[[0, 0], [0, g']]`` at its fixed point: its eigenvalues are 0 and ``g'``, so 1 is not among them
  (the flow's trivial multiplier is 1, measured by ``trivial_multiplier``; it does not follow from (8)).
* ``phase_shift``: the theorem the paper cites gives *orbital* asymptotic stability. Two runs of the exact
  solver from the section (made by the checks scene, its variables on ``perturbation``), at the limit cycle's
  speed and at ``1 + perturbation`` times it, are compared after ``n_cycles``: orbitally, their speeds before the
  impact at a1 agree; in the sense of Lyapunov, their impact times agree too, which the permanent phase shift
  of an autonomous system forbids.
"""

from __future__ import annotations

import numpy as np

from . import printed as pe
from .checks import Evidence, Verdict, check, fig3_case, fmt, params_of, probe, within

__all__: list[str] = []


@check("map8_eigenvalues", scenes=fig3_case, args=("case",))
def map8_eigenvalues(claim, ev: Evidence) -> Verdict:
    """One of the eigenvalues of the map (8) as printed, at the fixed point of (16), is 1 (within the tolerance)."""
    p = params_of(ev.fig3[claim["args"]["case"]])
    star, step = pe.fixed_point_19(p), 1e-5

    def P(y: np.ndarray) -> np.ndarray:
        return np.array([p.a1, pe.poincare_map_16(float(y[1]), p)])

    y = np.array([p.a1, star])
    jacobian = np.column_stack([(P(y + d) - P(y - d)) / (2 * step * star) for d in np.eye(2) * step * star])
    eigenvalues = np.sort(np.linalg.eigvals(jacobian).real)
    return Verdict(
        f"eigenvalues of the map (8) at the fixed point {fmt(star)} m/s: {', '.join(fmt(e, 8) for e in eigenvalues)}",
        bool(np.any(np.abs(eigenvalues - 1.0) <= claim["tolerance"])),
        note="P(y) = (a1, g(y2)) does not depend on y1, so its Jacobian is [[0, 0], [0, g']]: the eigenvalues are 0 "
             "and g' = (1 - b)^4; mu1 = 1 is the flow's multiplier along the orbit, which the map on the section "
             "does not have",
        paper_value="Therefore mu1 = 1")


@check("phase_shift", scenes=fig3_case, args=("case", "sense", "perturbation", "n_cycles"))
def phase_shift(claim, ev: Evidence) -> Verdict:
    """The run from the section (a1, v*) and the run from (a1, (1 + perturbation) v*), v* the case's converged
    speed: ``sense: orbital`` holds when their speeds before the impact at a1 agree after ``n_cycles`` (relative,
    within the tolerance), ``sense: lyapunov`` when their impact times at a1 agree too (s)."""
    args = claim["args"]
    star = float(ev.fig3[args["case"]]["velocity_before_impact"].values[-1])
    impacts = ev.checks["perturbed_impact_time"]
    made = (impacts.attrs["case"], int(impacts.attrs["n_cycles"]),
            float(ev.checks["perturbed_speed"].attrs["converged_speed"]))
    if made != (str(args["case"]), int(args["n_cycles"]), star):
        raise ValueError(f"the checks dataset's runs from the section (case, cycles, converged speed) {made} are not "
                         f"those of the claim")
    found = [(probe(ev, "perturbed_impact_time", "perturbation", perturbation=d).values,
              float(probe(ev, "perturbed_speed", "perturbation", perturbation=d))) for d in (0.0, args["perturbation"])]
    times = [t[np.isfinite(t)] for t, _ in found]
    n = min(len(t) for t in times)
    shift = float(times[1][n - 1] - times[0][n - 1])
    speeds = [speed for _, speed in found]
    gap = abs(speeds[1] - speeds[0]) / speeds[0]
    return Verdict(
        f"after {n} impacts at a1: speeds {fmt(speeds[0])} and {fmt(speeds[1])} m/s (relative difference "
        f"{fmt(gap, 2)}), impact times {fmt(shift, 4)} s apart (first impact {fmt(times[1][0] - times[0][0], 4)} s)",
        within(gap, claim["tolerance"]) if args["sense"] == "orbital" else within(abs(shift), claim["tolerance"]),
        note=f"the speed at the section perturbed by {fmt(100 * float(args['perturbation']), 3)} %: the motion returns "
             "to the limit cycle (orbital stability) but keeps a phase shift, as any autonomous oscillator does, so it "
             "does not return to the solution it started beside (no asymptotic stability in the sense of Lyapunov)",
        paper_value="the solution is asymptotically stable")
