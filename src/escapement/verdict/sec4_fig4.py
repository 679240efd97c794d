"""The checks of Sec. 4 on Fig. 4, the shock detail: the velocity jump read off the graph, the step of the
acceleration at the impact, and an impact in each printed time window under every reading of the figure's grid.
"""

from __future__ import annotations

import numpy as np

from ..model.events import EventKind
from ..paper.printed_axes import panel
from .evidence import Evidence, Verdict, check, each, fig4_scene, fmt, run, within


@check(scenes=fig4_scene, law="the impact law v+ = (1 - b) v- (Eq. (A-2))", fitted="Fig. 4's force, spring and release")
def shock_readout(claim, ev: Evidence) -> Verdict:
    ds = ev.fig4
    m, b, vb = float(ds["M"]), float(ds["b"]), ds["velocity_before"].values
    j, e = ds["impulse"].values, ds["energy_dissipated"].values
    if not len(j):
        return Verdict("no impact in the window", False, note="the shock detail holds no impact to read off",
                       paper_value="no number given")
    consistent = (np.allclose(j, -b * m * vb, rtol=1e-12, atol=0)
                  and np.allclose(e, 0.5 * m * vb**2 * (2 * b - b * b), rtol=1e-12, atol=0))
    return Verdict(
        f"{len(j)} impacts in the window: |impulse| {fmt(np.min(np.abs(j)), 4)}-{fmt(np.max(np.abs(j)), 4)} N s, "
        f"energy dissipated {fmt(np.min(e), 4)}-{fmt(np.max(e), 4)} J per impact", bool(consistent),
        note="read off the velocity jump: impulse M (v+ - v-) = -b M v-, energy M v-^2 (2b - b^2)/2; the figure "
             "labels both", paper_value="no number given")


@check(scenes=fig4_scene, fitted="Fig. 4's force, spring and release")
def impact_force_step(claim, ev: Evidence) -> Verdict:
    """A finite impact force read off the acceleration graph: some step of it at an impact is not F/M."""
    ds = ev.fig4
    t, a, f = ds["t"].values, ds["acceleration"].values, float(ds["F"]) / float(ds["M"])
    steps = [(float(a[i - 1]), float(a[i])) for i in np.searchsorted(t, ds["impact_time"].values)]  # at each impact
    worst = max((abs((after - before) - f) / f for before, after in steps), default=0.0)
    return Verdict(
        "; ".join(f"acceleration {fmt(b, 4)} -> {fmt(a_, 4)} m/s^2 at the impact" for b, a_ in steps)
        + f"; F/M = {fmt(f, 4)} m/s^2", bool(steps) and not within(worst, claim["tolerance"]),
        note="an impulsive model has no finite impact force: the impact is a jump of the velocity, and the step the "
             "acceleration graph shows at it is the escape wheel's force F switching on over the impulse zone",
        paper_value="the impact force evaluated from the graph")


@check(runs=("runs",))
def window_impact(claim, ev: Evidence) -> Verdict:
    """Under every reading of Fig. 4's grid (a run each, from rest past the later window) an impact in each window."""
    windows = [(a.low, a.high) for a in (panel("4", "velocity").x, panel("4", "acceleration").x)]
    runs, held = run(ev, claim["args"]["runs"]), {}
    if (t_end := float(runs["t_end"].min())) < max(w[1] for w in windows):
        raise ValueError(f"the runs {claim['args']['runs']!r} end at {t_end} s, before the windows")
    for r in each(runs):
        kind, time = r["event_kind"].values, r["event_time"].values
        impacts = time[(kind == int(EventKind.IMPACT_A1)) | (kind == int(EventKind.IMPACT_A3))]
        held[f"F = {fmt(r['F'], 3)} N, K = {fmt(r['K'], 3)} N/m, x0 = {fmt(r['x0'], 3)} m"] = all(
            bool(np.any((impacts >= lo) & (impacts <= hi))) for lo, hi in windows)
    return Verdict(
        f"an impact in both windows ({'; '.join(f'{fmt(lo, 3)}-{fmt(hi, 3)} s' for lo, hi in windows)}) under "
        f"{sum(held.values())} of the {len(held)} readings of the grid"
        + "".join(f"; none under {name}" for name, h in held.items() if not h), held,
        note=(f"the grid: every force and release magnitude of the Fig. 3 cases, either side, every spring constant "
              f"of the paper (K = {', '.join(fmt(k, 3) for k in dict.fromkeys(runs['K'].values.tolist()))} N/m), "
              "since the printed axes leave Fig. 4's reading undetermined (REPLICATION.md, Sec. 3)"),
        paper_value="the window holds the impact")
