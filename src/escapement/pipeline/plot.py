"""The plotting jobs: netCDF files or tables in, a figure out (PNG, PDF and SVG), titled by the study.

The replication's paper figures are drawn with each printed panel's axes as the claims score them (the limits
the data's rounded out to the printed ticks, :mod:`escapement.plotting.panel_axes`); a study of
the user's own gets matplotlib's own axes and a title that names the study, never the paper's figure. Imports
no solver and no scene."""

from __future__ import annotations

from collections.abc import Mapping

from ..io.netcdf import read_netcdf
from ..scenes.settings import KINDS, REPLICATION
from .logs import logged
from .tables import read_work_precision

__all__ = ["plot", "title"]

#: the figure of each kind, by its file name: the block of the configuration it draws
BLOCKS = {kind.name: block for block, kind in KINDS.items()}


def title(figure: str, study: str) -> str:
    """What a figure shows, in one line: the paper's figure it reproduces for the replication's, else its study."""
    kind = KINDS[BLOCKS[figure]]
    shows = f"{kind.shows[:1].upper()}{kind.shows[1:]}" + ("s" if figure == "phase_diagrams" else "")
    if study == REPLICATION:
        return f"{shows} of the escapement model" + (f", {kind.figure} of Mao, Fu & Li (2013)" if kind.figure else "")
    return f"{shows} of the escapement model, study '{study}'"


def plot(figure: str, study: str, inputs: Mapping[str, str], png: str, pdf: str, svg: str, log: str) -> None:
    """Draw ``figure`` (a file name: poincare_map, long_run, ...) of ``study`` from ``inputs`` (its files by their
    labels: the netCDF file of each scene, by its label for the figures of several scenes; ``""`` for the one
    file of the others) to ``png``, ``pdf`` and ``svg``."""
    from .. import plotting

    with logged(log, f"plot {figure}"):
        if figure == "work_precision":
            fig = plotting.work_precision(read_work_precision(inputs[""]))
        elif figure == "long_run":
            fig = plotting.long_run(read_netcdf(inputs[""]))
        elif figure in ("poincare_map", "shock_detail", "phase_diagrams"):
            data = {label: read_netcdf(path) for label, path in inputs.items()}
            data = data[""] if figure == "shock_detail" else data
            axes = None
            if study == REPLICATION:  # each printed panel's axes as its claims score them
                from ..plotting import panel_axes
                from ..plotting.autoscale import VARIANTS
                from ..verdict.scores import CLAIM_AUTOSCALE

                measure = {"poincare_map": panel_axes.poincare_axes, "shock_detail": panel_axes.shock_axes,
                           "phase_diagrams": panel_axes.phase_axes}[figure]
                axes = measure(data, VARIANTS[CLAIM_AUTOSCALE])
            fig = getattr(plotting, figure)(data, title(figure, study), axes)
        else:
            fig = getattr(plotting, figure)(read_netcdf(inputs[""]), title(figure, study))
        plotting.save_figure(fig, png, pdf, svg)
