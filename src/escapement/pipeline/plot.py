"""The plotting jobs: netCDF files or tables in, a figure out (PNG and PDF), titled by the study.

The replication's paper figures are drawn with each printed panel's axes as the claims score them (the limits
the data's rounded out to the printed ticks, :func:`escapement.plotting.panel_axes.scene_axes`); a study of
the user's own gets matplotlib's own axes and a title that names the study, never the paper's figure. Imports
no solver and no scene."""

from __future__ import annotations

from collections.abc import Sequence

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


def plot(figure: str, study: str, inputs: Sequence[str], labels: Sequence[str] | None, png: str, pdf: str,
         log: str, case: str | None = None) -> None:
    """Draw ``figure`` (a file name: poincare_map, long_run, ...) of ``study`` from ``inputs`` (netCDF files,
    one per label of ``labels`` for the figures of several scenes; the work-precision table) to ``png`` and
    ``pdf``."""
    from .. import plotting

    with logged(log, f"plot {figure}"):
        if figure == "work_precision":
            fig = plotting.work_precision(read_work_precision(inputs[0]), case)
        elif figure == "long_run":
            fig = plotting.long_run(read_netcdf(inputs[0]))
        elif figure in ("poincare_map", "shock_detail", "phase_diagrams"):
            data = {label: read_netcdf(path) for label, path in zip(labels, inputs, strict=True)}
            axes = None
            if study == REPLICATION:
                from ..plotting.autoscale import VARIANTS
                from ..plotting.panel_axes import scene_axes
                from .scores import CLAIM_AUTOSCALE

                split = {"poincare_map": (data, None, {}), "shock_detail": ({}, data.get(""), {}),
                         "phase_diagrams": ({}, None, data)}[figure]
                axes = scene_axes(*split, VARIANTS[CLAIM_AUTOSCALE])
            draw = getattr(plotting, figure)
            fig = draw(data[""] if figure == "shock_detail" else data, title(figure, study), axes)
        else:
            fig = getattr(plotting, figure)(read_netcdf(inputs[0]), title(figure, study))
        plotting.save_figure(fig, png, pdf)
