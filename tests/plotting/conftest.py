"""Small synthetic datasets with the variables the figures read, so that the figure tests run in
milliseconds and depend on no solver: the values are plausible, not computed by the model."""

from __future__ import annotations

import math
from types import SimpleNamespace

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

MEANINGS = "completed stopped turned_back_in_zone chattering event_limit"
GEOMETRY = {"b": 0.1, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05}


def _parameters(**values) -> dict:
    return {k: ((), float(v)) for k, v in {"M": 1.0, "K": 1.0, "F": 1.0, **GEOMETRY, "x0": -1.0, "v0": 0.0,
                                           **values}.items()}


def poincare(n: int = 20, outcome: str = "completed", period_offset: float = 0.0125, **values) -> xr.Dataset:
    """A Poincaré map: converging velocity, period and Step-1 amplitude; no cycle unless ``outcome`` completed."""
    p = _parameters(**values)
    n = n if outcome == "completed" else 0
    k = np.arange(1, n + 1)
    decay = 0.6561 ** k
    natural = 2 * math.pi * math.sqrt(p["M"][1] / p["K"][1])
    return xr.Dataset(
        {"velocity_before_impact": ("cycle", 1.25 - 0.25 * decay),
         "period": ("cycle", natural + period_offset + 0.01 * decay),
         "amplitude_h0": ("amplitude_cycle", 1.26 - 0.26 * 0.6561 ** np.arange(n + 1 if n else 0)),
         "fixed_point_19": ((), 1.2566), **p},
        coords={"cycle": k, "amplitude_cycle": np.arange(1, n + 2 if n else 1)},
        attrs={"amplitude_variable": "amplitude_h0", "outcome": outcome, "n_cycles": 20,
               "outcome_message": "the escapement stopped at t = 0 s"})


def shock(impacts=(84.4,)) -> xr.Dataset:
    """A velocity with a jump at each impact and an acceleration with a jump at each event."""
    impacts = np.asarray(impacts, dtype=float)
    events = np.sort(np.concatenate([impacts, impacts + 0.2]))
    t = np.linspace(80.0, 87.0, 1401)
    jumps = (t[:, None] >= impacts[None, :]).sum(axis=1)
    velocity = 0.9 * np.cos(0.3 * (t - 84.5)) - 0.09 * jumps
    before = np.interp(impacts, t, 0.9 * np.cos(0.3 * (t - 84.5))) - 0.09 * np.arange(impacts.size)
    after = before - 0.09
    return xr.Dataset(
        {"velocity": ("t", velocity), "acceleration": ("t", -0.27 * np.sin(0.3 * (t - 84.5)) + 0.05 * jumps),
         "impact_time": ("impact", impacts), "velocity_before": ("impact", before),
         "velocity_after": ("impact", after), "impulse": ("impact", after - before),
         "energy_dissipated": ("impact", 0.5 * (before**2 - after**2)), "event_time": ("event", events),
         "velocity_window": ("window_edge", [80.0, 87.0]), "acceleration_window": ("window_edge", [81.0, 85.0]),
         **_parameters(F=0.5, K=0.1, x0=-3.0)},
        coords={"t": t})


def phase(n: int = 6, outcome: str = "completed", **values) -> xr.Dataset:
    """A trajectory spiralling out to a limit cycle, an impact at a1 and a3 each half turn."""
    p = _parameters(**values)
    omega = math.sqrt(p["K"][1] / p["M"][1])
    t = np.linspace(0.0, (n + 0.5) * 2 * math.pi / omega, 400 * (n + 1))
    r = 1.25 - 0.5 * np.exp(-t / 8)
    impacts = np.arange(1, 2 * n + 1) * math.pi / omega if outcome == "completed" else np.array([])
    radius = np.interp(impacts, t, r)
    return xr.Dataset(
        {"displacement": ("t", r * np.cos(omega * t)), "velocity": ("t", -r * np.sin(omega * t)),
         "impact_time": ("impact", impacts), "impact_position": ("impact", np.where(np.arange(impacts.size) % 2,
                                                                                     0.1, -0.1)),
         "velocity_before": ("impact", radius * 1.05), "velocity_after": ("impact", radius * 0.95),
         "period": ("cycle", np.full(n if outcome == "completed" else 0, 2 * math.pi / omega)), **p},
        coords={"t": t}, attrs={"outcome": outcome, "n_cycles": n})


CYCLES = np.array([1, 2, 3, 10, 11, 50, 100, 101, 300])


def long_run(drift_ivp, error_velocity_ivp) -> xr.Dataset:
    """The long run's errors at nine sampled cycles, the exact solver's and the closed forms' at rounding level."""
    return xr.Dataset(
        {"drift_exact": ("cycle", [1e-16, 2e-16, 1e-16, 3e-16, 1e-15, 2e-15, 3e-15, 3e-15, 5e-15]),
         "drift_closed_form": ("cycle", [1e-16, 1e-16, 0.0, 3e-16, 2e-15, 2e-15, 1e-15, 3e-15, 4e-15]),
         "drift_ivp": ("cycle", drift_ivp),
         "error_velocity_exact": ("cycle", [1e-17, 4e-16, 0.0, 2e-16, 1e-16, 1e-16, 1e-16, 1e-16, 1e-16]),
         "error_velocity_closed_form": ("cycle", np.full(CYCLES.size, 2e-16)),
         "error_velocity_ivp": ("cycle", error_velocity_ivp),
         "fixed_point_period": 6.295673629674346, "fixed_point_velocity": 1.2566, **_parameters()},
        coords={"cycle": CYCLES}, attrs={"ivp_label": "solve_ivp DOP853 rtol=1e-12", "ivp_cycles": 300})


def stability(b=(0.5, 0.9, 1.1, 1.5), F=(0.5, 1.0, 2.0)) -> xr.Dataset:
    """A (b, F) map whose cells beyond b = 1 chatter."""
    b, F = np.array(b), np.array(F)
    mu = np.where(b[:, None] < 1, (1 - b[:, None]) ** 4 + 1e-13 * F[None, :], np.nan)
    outcome = np.repeat(np.where(b < 1, 0, 3)[:, None], F.size, axis=1).astype(np.int8)
    return xr.Dataset(
        {"multiplier": (("b", "F"), mu),
         "multiplier_eq21": (("b", "F"), np.repeat((1 - b[:, None]) ** 4, F.size, axis=1)),
         "outcome": (("b", "F"), outcome, {"flag_meanings": MEANINGS}),
         **{k: v for k, v in _parameters().items() if k not in ("b", "F")}},
        coords={"b": b, "F": F})


def existence() -> xr.Dataset:
    """An (a3, F) map: a limit cycle above the thresholds, the escapement stopping below."""
    a3, F = np.linspace(0.0, 0.25, 12), np.linspace(0.0, 0.014, 8)
    threshold = np.abs(0.1 - a3) * 0.055
    converged = F[None, :] > threshold[:, None]
    return xr.Dataset(
        {"outcome": (("a3", "F"), np.where(converged, 0, 1), {"flag_meanings": MEANINGS}),
         "converged": (("a3", "F"), converged.astype(np.int8)), "threshold": ("a3", np.where(a3 < 0.1, threshold, 0)),
         "threshold_mirror": ("a3", np.where(a3 > 0.1, threshold, 0)), "n_cycles": 120, "tolerance": 1e-9,
         **{k: v for k, v in _parameters().items() if k not in ("a3", "F")}},
        coords={"a3": a3, "F": F})


def escapement_error() -> xr.Dataset:
    """The rate against amplitude for two impulse zones."""
    F = np.array([0.1, 0.5, 1.0, 2.0])
    amplitude = np.array([[0.4, 0.8, 1.2, 1.8], [0.45, 0.85, 1.3, 2.0]])
    return xr.Dataset(
        {"largest_displacement": (("zone", "F"), amplitude), "rate": (("zone", "F"), -300 / amplitude),
         "rate_impacts": (("zone", "F"), -400 / amplitude), "rate_zones": (("zone", "F"), 100 / amplitude),
         "zone_name": ("zone", ["paper", "wide"]), "zone_a1": ("zone", [-0.1, -0.2]), "zone_a2": ("zone", [0.05, 0.1]),
         **{k: v for k, v in _parameters().items() if k != "F"}},
        coords={"F": F})


def work_precision() -> list[dict]:
    rows = [("exact", 1e-3, 1e-16, 0.0), ("map16", 1e-5, 1e-16, 1e-16)]
    rows += [("DOP853", w, e, e / 10) for w, e in ((0.2, 1e-3), (0.3, 1e-9), (0.5, 1e-12))]
    rows += [("CVODE-Adams", w, e, e / 10) for w, e in ((0.2, 1e-3), (0.6, 1e-10))]
    return [{"method": m, "setting": "", "wall_s": w, "repeats": 1, "error_velocity": ev, "error_time": et}
            for m, w, ev, et in rows]


@pytest.fixture
def datasets() -> SimpleNamespace:
    """The builders above."""
    return SimpleNamespace(poincare=poincare, shock=shock, phase=phase, long_run=long_run, stability=stability,
                           existence=existence, escapement_error=escapement_error, work_precision=work_precision)


@pytest.fixture(autouse=True)
def close_figures():
    """Every figure a test makes is closed after it, whatever the test's outcome."""
    yield
    plt.close("all")
