"""The exact solver for many trajectories at once, one per array element.

The same hybrid automaton and closed forms as :mod:`escapement.exact`, advanced in
lock-step: every pass of the loop moves each active trajectory to its next event; a
trajectory that ends (cycles done, stopped, turned back, chattering) is masked out.
Parameters and initial states broadcast to a common shape ``(N,)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .limits import EVENTS_PER_CYCLE
from .outcome import Status

__all__ = ["EnsembleCycles", "STATUS_CODES", "solve_ensemble"]

TWO_PI = 2.0 * np.pi
FREE, ZONE_RIGHT, ZONE_LEFT = 0, 1, 2
EITHER, A1, A3 = 0, 1, 3
#: integer codes of the outcomes, as stored in netCDF files
STATUS_CODES = {status: code for code, status in enumerate(Status)}
_RUNNING = -1


@dataclass(frozen=True)
class EnsembleCycles:
    """Per-cycle arrays of shape ``(N, n_cycles)`` (NaN where a trajectory ended earlier)."""

    impact_time: np.ndarray
    velocity_before_impact: np.ndarray
    period: np.ndarray
    amplitude: np.ndarray
    status: np.ndarray  #: codes of :data:`STATUS_CODES`

    def outcome(self, i: int) -> Status:
        return list(Status)[int(self.status[i])]


def _crossing(centre, x0, v0, omega, target, direction):
    """Vectorised :func:`escapement.arcs.crossing`: ``(tau, v, angle)``, NaN where the arc never passes."""
    v_sq = v0 * v0 + (omega * omega) * ((x0 - target) * (x0 + target - 2.0 * centre))
    reach = v_sq > 0.0
    v1 = np.where(reach, direction * np.sqrt(np.where(reach, v_sq, 0.0)), np.nan)
    u0, q = x0 - centre, target - centre
    w0, w1 = v0 / omega, v1 / omega
    angle = np.arctan2(w0 * q - u0 * w1, u0 * q + w0 * w1)
    angle = np.where(angle <= 0.0, angle + TWO_PI, angle)
    return angle / omega, v1, angle


def _arc_maximum(centre, x0, v0, omega, angle, x1):
    u0, w0 = x0 - centre, v0 / omega
    start = np.arctan2(w0, u0)
    to_top = np.where(start >= 0.0, start, start + TWO_PI)
    return np.where(to_top <= angle, centre + np.hypot(u0, w0), np.maximum(x0, x1))


def solve_ensemble(
    M, K, F, b, a1, a2, a3=None, a4=None, x0=1.0, v0=0.0, *, n_cycles: int, max_events=None, amplitude: bool = True
):
    """Integrate every trajectory for ``n_cycles`` complete cycles (or until it leaves the regime).

    Inputs are validated like :class:`escapement.Parameters` (the first invalid element is
    named in the error). With ``amplitude=False`` the per-cycle maxima are not computed.
    """
    from .parameters import Parameters

    a3 = -np.asarray(a1, float) if a3 is None else a3
    a4 = -np.asarray(a2, float) if a4 is None else a4
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (M, K, F, b, a1, a2, a3, a4, x0, v0)))
    M, K, F, b, a1, a2, a3, a4, x, v = (np.array(a, dtype=float).ravel() for a in arrays)
    valid = (M > 0) & (K > 0) & (F >= 0) & (b > 0) & (b < 2) & (a1 < a2) & (a4 < a3)
    valid &= np.all(np.isfinite(np.stack([M, K, F, b, a1, a2, a3, a4, x, v])), axis=0)
    if not valid.all():  # the same checks, and errors, as the scalar model
        i = int(np.flatnonzero(~valid)[0])
        Parameters(M=M[i], K=K[i], F=F[i], b=b[i], a1=a1[i], a2=a2[i], a3=a3[i], a4=a4[i])
        raise ValueError(f"element {i}: x0 = {x[i]!r}, v0 = {v[i]!r} must be finite")
    n = len(M)
    omega, offset, keep = np.sqrt(K / M), F / K, 1.0 - b
    bound = EVENTS_PER_CYCLE * (n_cycles + 2) + 8 if max_events is None else max_events

    t = np.zeros(n)  # compensated (Neumaier) sum of the durations: t + t_err
    t_err = np.zeros(n)
    elapsed = np.zeros(n)  # time since the last impact at a1
    periods = np.full((n, n_cycles), np.nan)
    mode = np.full(n, FREE)
    expect = np.full(n, EITHER)
    status = np.full(n, _RUNNING)
    count = np.zeros(n, dtype=int)
    cycle_max = np.full(n, -np.inf)
    times = np.full((n, n_cycles + 1), np.nan)
    speeds = np.full((n, n_cycles + 1), np.nan)
    maxima = np.full((n, n_cycles), np.nan)

    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(bound):
            running = status == _RUNNING
            if not running.any():
                break
            groups = [(g, np.flatnonzero(running & (mode == g))) for g in (FREE, ZONE_RIGHT, ZONE_LEFT)]
            for group, ii in groups:
                if len(ii) == 0:
                    continue
                xs, vs, om = x[ii], v[ii], omega[ii]
                if group == FREE:
                    centre = 0.0
                    ex = expect[ii]
                    dt1, v1, an1 = _crossing(0.0, xs, vs, om, a1[ii], 1.0)
                    dt3, v3, an3 = _crossing(0.0, xs, vs, om, a3[ii], -1.0)
                    dt1[ex == A3] = np.nan
                    dt3[ex == A1] = np.nan
                    take1 = ~np.isnan(dt1) & (np.isnan(dt3) | (dt1 <= dt3))
                    dt = np.where(take1, dt1, dt3)
                    v_new = np.where(take1, v1, v3)
                    angle = np.where(take1, an1, an3)
                    target = np.where(take1, a1[ii], a3[ii])
                    kind = np.where(take1, 1, 3)
                    ended_status = STATUS_CODES[Status.STOPPED]
                else:
                    right = group == ZONE_RIGHT
                    centre = offset[ii] if right else -offset[ii]
                    target = a2[ii] if right else a4[ii]
                    dt, v_new, angle = _crossing(centre, xs, vs, om, target, 1.0 if right else -1.0)
                    kind = np.full(len(ii), 2 if right else 4)
                    ended_status = STATUS_CODES[Status.TURNED_BACK_IN_ZONE]
                ended = np.isnan(dt)
                status[ii[ended]] = ended_status
                go = ~ended
                jj = ii[go]
                if amplitude:
                    c = centre if np.isscalar(centre) else centre[go]
                    cycle_max[jj] = np.maximum(cycle_max[jj], _arc_maximum(c, xs[go], vs[go], om[go], angle[go], target[go]))
                d, before = dt[go], t[jj]
                total = before + d
                t_err[jj] += np.where(np.abs(before) >= d, (before - total) + d, (d - total) + before)
                t[jj] = total
                elapsed[jj] += d
                x[jj] = target[go]
                kind, v_new = kind[go], v_new[go]
                if group == FREE:
                    hit1 = kind == 1
                    i1 = jj[hit1]
                    k = count[i1]
                    times[i1, k] = t[i1] + t_err[i1]
                    speeds[i1, k] = v_new[hit1]
                    later = k > 0
                    if amplitude:
                        maxima[i1[later], k[later] - 1] = cycle_max[i1[later]]
                    periods[i1[later], k[later] - 1] = elapsed[i1[later]]
                    elapsed[i1] = 0.0
                    cycle_max[i1] = x[i1]
                    count[i1] += 1
                    done = np.zeros(len(jj), dtype=bool)
                    done[hit1] = count[i1] >= n_cycles + 1
                    status[jj[done]] = STATUS_CODES[Status.COMPLETED]
                    v_after = keep[jj] * v_new
                    reversed_ = ~done & (v_after * v_new < 0.0)
                    status[jj[reversed_]] = STATUS_CODES[Status.CHATTERING]
                    v[jj] = v_after
                    mode[jj] = np.where(hit1, ZONE_RIGHT, ZONE_LEFT)
                else:
                    v[jj] = v_new
                    mode[jj] = FREE
                    expect[jj] = A3 if group == ZONE_RIGHT else A1
        status[status == _RUNNING] = STATUS_CODES[Status.EVENT_LIMIT]

    # Like the scalar table: only complete cycles (an impact that starts an unfinished cycle is dropped).
    incomplete = np.arange(n_cycles)[None, :] >= (count - 1)[:, None]
    times, speeds = times[:, :n_cycles], speeds[:, :n_cycles]
    times[incomplete] = np.nan
    speeds[incomplete] = np.nan
    return EnsembleCycles(
        impact_time=times,
        velocity_before_impact=speeds,
        period=periods,
        amplitude=maxima,
        status=status.astype(np.int8),
    )
