"""The jobs of the studies beyond the paper: the work-precision benchmark, the speed table and the stress cases
(imported by their job alone: the timing jobs, each a process of its own, do without them)."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from ..io.netcdf import read_netcdf, write_csv
from ..model.parameters import Parameters, check_initial_state
from ..studies.benchmark import headline_ratios, per_cycle_times, work_precision
from .logs import logged
from .tables import SPEED_COLUMNS, STRESS_COLUMNS, WORK_PRECISION_COLUMNS

__all__ = ["run_speed", "run_stress", "run_work_precision"]


def _formatted(rows: list[dict], columns: list[str]) -> list[dict]:
    return [{c: (f"{row[c]:.6e}" if isinstance(row.get(c), float) else row.get(c, "")) for c in columns}
            for row in rows]


def run_work_precision(scene: Mapping, settings: Mapping[str, list], output: str, log: str) -> None:
    with logged(log, "run_work_precision") as logger:
        x0 = check_initial_state(scene["x0"], scene.get("v0", 0.0))[0]
        rows = work_precision(Parameters.from_mapping(scene), x0, scene["n_cycles"],
                              {k: list(v) for k, v in settings.items()}, scene["min_seconds"], scene["max_repeats"],
                              log=logger.info)
        assert list(rows[0]) == WORK_PRECISION_COLUMNS, list(rows[0])
        write_csv(_formatted(rows, WORK_PRECISION_COLUMNS), WORK_PRECISION_COLUMNS, output)


def run_speed(scene: Mapping, speed: Mapping, output: str, headline_output: str, log: str,
              floors: Callable[[Mapping, Parameters, float], list[dict]]) -> None:
    """The speed table (``output``): the fastest integrator setting reaching the headline's ``target`` against the
    exact solver and the closed forms, those two per cycle, and ``floors``' rows; to ``headline_output``, the
    headline's rows."""
    with logged(log, "run_speed") as logger:
        params, x0 = Parameters.from_mapping(scene), check_initial_state(scene["x0"], scene.get("v0", 0.0))[0]
        head = speed["headline"]
        h = headline_ratios(params, x0, head["n_cycles"], {k: list(v) for k, v in head["settings"].items()},
                            head["target"], ("error_time",), scene["min_seconds"], scene["max_repeats"],
                            log=logger.info)
        n, ode = h["n_cycles"], h["ode"]
        if ode is None:
            label = "fastest integrator setting reaching the target"
            note = f"no candidate setting reaches {head['target']:g} in impact time"
            ode = {"wall_s": float("nan"), "repeats": 0}
        else:
            label = f"{ode['method']} rtol {ode['setting']}"
            note = (f"the fastest candidate whose impact time at cycle {n} is within {head['target']:g} of 50 digits "
                    f"(its error {ode['error_time']:.2e}; velocity {ode['error_velocity']:.2e})")
        rows = [{"name": f"{label} / {against}", "n": n, "ratio": h[f"ode_over_{key}"], "time_s": ode["wall_s"],
                 "reference_s": h[key]["wall_s"], "repeats": ode["repeats"], "note": note}
                for against, key in (("solve_exact", "exact"), ("closed-form cycles", "closed_form"))]
        sizes = tuple(dict.fromkeys((50, n, *speed["floor"]["exact_cycles"])))  # the floors' sizes too
        for r in per_cycle_times(params, x0, sizes, scene["min_seconds"], scene["max_repeats"]):
            rows.append({"name": "solve_exact / closed-form cycles", "n": r["n_cycles"], "ratio": r["ratio"],
                         "time_s": r["exact_s_per_cycle"] * r["n_cycles"],
                         "reference_s": r["closed_form_s_per_cycle"] * r["n_cycles"],
                         "note": "per run, without the trajectory"})
        rows += floors(speed["floor"], params, x0)
        for row in rows:
            logger.info("%s, n = %s: %.4g", row["name"], row["n"], row["ratio"])
        write_csv(_formatted(rows, SPEED_COLUMNS), SPEED_COLUMNS, output)
        table = [h["exact"], h["closed_form"], *h["candidates"]]
        write_csv(_formatted(table, WORK_PRECISION_COLUMNS), WORK_PRECISION_COLUMNS, headline_output)


def run_stress(long_run: str, output: str, log: str) -> None:
    """Every stress case of the solver, and the very long run's bounds, as one CSV row each."""
    from ..studies.stress import run_all

    with logged(log, "run_stress") as logger:
        rows = run_all()
        lr = read_netcdf(long_run, ("cycle", "error_time_exact", "max_velocity_deviation", "max_period_deviation"))
        velocity, period = float(lr["max_velocity_deviation"]), float(lr["max_period_deviation"])
        time_error, n = float(lr["error_time_exact"].max()), int(lr.attrs["n_cycles"])
        bounded = velocity <= 1e-12 and period <= 1e-12 and not lr.attrs["any_nan"] and time_error <= 1e-14
        rows.append({"case": "very_long_run", "regime": f"very long runs: {n} cycles, {4 * n} events",
                     "outcome": "completed", "passed": "yes" if bounded else "no",
                     "check": "no NaN; velocity and period within 1e-12 of the fixed point once converged; impact "
                              "time within 1e-14 of 50 digits",
                     "detail": f"velocity {velocity:.1e}, period {period:.1e}, impact time {time_error:.1e}"})
        for row in rows:
            logger.info("%s: %s (%s)", row["case"], row["passed"], row["detail"])
        write_csv(rows, STRESS_COLUMNS, output)
