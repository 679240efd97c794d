"""The plotting jobs: netCDF files or tables in, figures out. Figs. 3-5 draw each printed panel with
the axes its claim scores and print the readings the score table leaves tied. Imports no solver and
no scene."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import xarray as xr

from ..io.netcdf import read_netcdf
from ..plotting import (
    escapement_error,
    existence_map,
    fig3,
    fig4,
    fig5,
    long_run,
    save_figure,
    stability_map,
    work_precision,
)
from ..plotting.autoscale import VARIANTS
from ..plotting.panel_axes import PanelAxes, scene_axes
from .logs import logged
from .scores import CLAIM_AUTOSCALE, figure_caption, read_scores
from .tables import CYCLE_VARIABLES, ESCAPEMENT_ERROR_VARIABLES, PHASE_VARIABLES, SHOCK_VARIABLES, read_work_precision

__all__ = ["plot_escapement_error", "plot_existence_map", "plot_fig3", "plot_fig4", "plot_fig5", "plot_long_run",
           "plot_stability_map", "plot_work_precision"]


def _claimed(fig3: Mapping[str, xr.Dataset], fig4: xr.Dataset | None, fig5: Mapping[str, xr.Dataset]) -> PanelAxes:
    """The axes the claims score (:func:`escapement.pipeline.readings.scene_axes` at the claims' margin)."""
    return scene_axes(fig3, fig4, fig5, VARIANTS[CLAIM_AUTOSCALE])


def plot_fig3(labels: Sequence[str], paths: Sequence[str], scores: str, png: str, pdf: str, log: str) -> None:
    """Job: Fig. 3 with each printed panel's claimed axes and, under its title, the readings the
    score table ``scores`` leaves tied."""
    with logged(log, "plot_fig3"):
        cases = {label: read_netcdf(path, CYCLE_VARIABLES) for label, path in zip(labels, paths)}
        caption = figure_caption(read_scores(scores), "3", 92)
        save_figure(fig3(cases, _claimed(cases, None, {}), caption), png, pdf)


def plot_fig4(path: str, scores: str, png: str, pdf: str, log: str) -> None:
    """Job: Fig. 4 with its panels' claimed axes and the readings the score table leaves tied."""
    with logged(log, "plot_fig4"):
        ds = read_netcdf(path, SHOCK_VARIABLES)
        caption = figure_caption(read_scores(scores), "4", 105)
        save_figure(fig4(ds, _claimed({}, ds, {}), caption), png, pdf)


def plot_fig5(labels: Sequence[str], paths: Sequence[str], scores: str, png: str, pdf: str, log: str) -> None:
    """Job: Fig. 5 with its panels' claimed axes and the readings the score table leaves tied."""
    with logged(log, "plot_fig5"):
        panels = {label: read_netcdf(path, PHASE_VARIABLES) for label, path in zip(labels, paths)}
        caption = figure_caption(read_scores(scores), "5", 130)
        save_figure(fig5(panels, _claimed({}, None, panels), caption), png, pdf)


def plot_work_precision(table: str, png: str, pdf: str, log: str, case: str) -> None:
    """The work-precision figure of ``table``, measured on the Fig. 3 case ``case``."""
    with logged(log, "plot_work_precision"):
        save_figure(work_precision(read_work_precision(table), case), png, pdf)


def plot_long_run(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_long_run"):
        save_figure(long_run(read_netcdf(path, ("cycle", "drift_exact", "drift_ivp", "F", "x0"))), png, pdf)


def plot_stability_map(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_stability_map"):
        save_figure(stability_map(read_netcdf(path, ("b", "F", "multiplier", "multiplier_eq21", "outcome"))), png, pdf)


def plot_escapement_error(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_escapement_error"):
        save_figure(escapement_error(read_netcdf(path, ESCAPEMENT_ERROR_VARIABLES)), png, pdf)


def plot_existence_map(path: str, png: str, pdf: str, log: str) -> None:
    with logged(log, "plot_existence_map"):
        required = ("a3", "F", "outcome", "converged", "threshold", "threshold_mirror", "n_cycles", "tolerance", "x0")
        save_figure(existence_map(read_netcdf(path, required)), png, pdf)
