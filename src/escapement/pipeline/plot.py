"""The plotting jobs: netCDF files or tables in, figures out. Imports no solver and no scene."""

from __future__ import annotations

from collections.abc import Sequence

from ..io.netcdf import read_netcdf
from ..plotting import escapement_error, fig3, fig4, fig5, long_run, save_figure, stability_map, work_precision
from .logs import logged
from .tables import CYCLE_VARIABLES, ESCAPEMENT_ERROR_VARIABLES, PHASE_VARIABLES, SHOCK_VARIABLES, read_work_precision

__all__ = ["plot_escapement_error", "plot_fig3", "plot_fig4", "plot_fig5", "plot_long_run", "plot_stability_map", "plot_work_precision"]


def plot_fig3(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig3"):
        cases = {label: read_netcdf(path, CYCLE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig3(cases), png, pdf)


def plot_fig4(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig4"):
        save_figure(fig4(read_netcdf(path, SHOCK_VARIABLES)), png, pdf)


def plot_fig5(labels: Sequence[str], paths: Sequence[str], png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_fig5"):
        panels = {label: read_netcdf(path, PHASE_VARIABLES) for label, path in zip(labels, paths)}
        save_figure(fig5(panels), png, pdf)


def plot_work_precision(table: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_work_precision"):
        save_figure(work_precision(read_work_precision(table)), png, pdf)


def plot_long_run(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_long_run"):
        save_figure(long_run(read_netcdf(path, ("cycle", "drift_exact", "drift_ivp"))), png, pdf)


def plot_stability_map(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_stability_map"):
        save_figure(stability_map(read_netcdf(path, ("b", "F", "multiplier", "multiplier_eq21", "outcome"))), png, pdf)


def plot_escapement_error(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_escapement_error"):
        save_figure(escapement_error(read_netcdf(path, ESCAPEMENT_ERROR_VARIABLES)), png, pdf)
