"""The jobs of the studies beyond the paper: the work-precision benchmark and the stress cases."""

from __future__ import annotations

from collections.abc import Mapping

from ..io.atomic import write_csv
from ..io.netcdf import read_netcdf
from ..model.parameters import Parameters, check_initial_state
from ..studies.benchmark import work_precision
from ..studies.stress import run_all
from .edge_cases import run_edge_cases
from .logs import logged
from .tables import STRESS_COLUMNS, WORK_PRECISION_COLUMNS

__all__ = ["run_stress", "run_work_precision"]


def run_work_precision(scene: Mapping, settings: Mapping[str, list], output: str, log: str) -> None:
    with logged(log, "run_work_precision") as logger:
        x0 = check_initial_state(scene["x0"], scene.get("v0", 0.0))[0]
        rows = work_precision(
            Parameters.from_mapping(scene), x0, scene["n_cycles"],
            {k: list(v) for k, v in settings.items()}, scene["min_seconds"], scene["max_repeats"], log=logger.info,
        )
        formatted = [{k: (f"{v:.6e}" if isinstance(v, float) else v) for k, v in row.items()} for row in rows]
        assert list(rows[0]) == WORK_PRECISION_COLUMNS, list(rows[0])
        write_csv(formatted, list(rows[0]), output)


def run_stress(long_run: str, output: str, log: str) -> None:
    """Every stress case (the solver's, then the files' and the configuration's), and the very long
    run's bounds, as one CSV row each."""
    with logged(log, "run_stress") as logger:
        rows = run_all() + run_edge_cases()
        lr = read_netcdf(long_run, ("cycle", "error_time_exact", "max_velocity_deviation", "max_period_deviation"))
        velocity, period = float(lr["max_velocity_deviation"]), float(lr["max_period_deviation"])
        bounded = (velocity <= 1e-12 and period <= 1e-12
                   and not lr.attrs["any_nan"] and float(lr["error_time_exact"].max()) <= 1e-14)
        rows.append({
            "case": "very_long_run",
            "regime": f"very long runs: {int(lr.attrs['n_cycles'])} cycles, {4 * int(lr.attrs['n_cycles'])} events",
            "outcome": "completed",
            "check": "no NaN; velocity and period within 1e-12 of the fixed point once converged; impact time within "
                     "1e-14 of 50 digits",
            "passed": "yes" if bounded else "no",
            "detail": f"velocity {velocity:.1e}, period {period:.1e}, "
                      f"impact time {float(lr['error_time_exact'].max()):.1e}",
        })
        for row in rows:
            logger.info("%s: %s (%s)", row["case"], row["passed"], row["detail"])
        write_csv(rows, STRESS_COLUMNS, output)
