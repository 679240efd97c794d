"""The plotting jobs: netCDF files or tables in, a figure out (PNG, PDF and SVG), titled by the study; the
replication's paper figures with each printed panel's axes as the claims score them. Imports no solver or scene."""

from __future__ import annotations

from collections.abc import Mapping

from ..io.netcdf import read_csv, read_netcdf
from ..scenes.settings import KINDS, REPLICATION
from .logs import logged
from .tables import WORK_PRECISION_COLUMNS

__all__ = ["plot", "title"]


def title(figure: str, study: str) -> str:
    """What a figure shows, in one line: the paper's figure it reproduces for the replication's, else its study."""
    kind = next(kind for kind in KINDS.values() if kind.name == figure)
    shows = f"{kind.shows[:1].upper()}{kind.shows[1:]}" + ("s" if figure == "phase_diagrams" else "")
    if study == REPLICATION:
        return f"{shows} of the escapement model" + (f", {kind.figure} of Mao, Fu & Li (2013)" if kind.figure else "")
    return f"{shows} of the escapement model, study '{study}'"


def plot(figure: str, study: str, inputs: Mapping[str, str], png: str, pdf: str, svg: str, log: str) -> None:
    """Draw ``figure`` (a file name: poincare_map, long_run, ...) of ``study`` from ``inputs`` (its files by scene
    label, ``""`` for a kind of one file) to ``png``, ``pdf`` and ``svg``."""
    from .. import plotting

    with logged(log, f"plot {figure}"):
        if figure == "work_precision":
            fig = plotting.work_precision(read_csv(inputs[""], WORK_PRECISION_COLUMNS))
        elif figure == "long_run":
            fig = plotting.long_run(read_netcdf(inputs[""]))
        elif figure in ("poincare_map", "shock_detail", "phase_diagrams"):
            data = {label: read_netcdf(path) for label, path in inputs.items()}
            data = data[""] if figure == "shock_detail" else data
            axes = None
            if study == REPLICATION:  # each printed panel's axes as its claims score them (poincare_axes, ...)
                from ..plotting import panel_axes
                from ..plotting.autoscale import VARIANTS
                from ..verdict.scores import CLAIM_AUTOSCALE

                axes = getattr(panel_axes, f"{figure.split('_')[0]}_axes")(data, VARIANTS[CLAIM_AUTOSCALE])
            fig = getattr(plotting, figure)(data, title(figure, study), axes)
        else:
            fig = getattr(plotting, figure)(read_netcdf(inputs[""]), title(figure, study))
        plotting.save_figure(fig, png, pdf, svg)
