"""The project's style sheet and deterministic saving."""

from __future__ import annotations

import contextlib
import os
from importlib.resources import as_file, files
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..io.atomic import atomic_path  # noqa: E402

__all__ = ["ACCENT", "GUIDE", "INK", "MUTED", "NO_CYCLE", "SERIES", "save_figure", "style"]

#: colours of the figures, named by role
INK = "#1f4e79"
ACCENT = "#c0392b"
MUTED = "#b8b8b8"
GUIDE = "#666666"
#: fill of the cells of a map where no cycle exists: a light grey, in neither viridis nor magma
NO_CYCLE = "#dcdcdc"
#: colours of up to four series of equal standing (the impulse zones of the escapement-error figure)
SERIES = (INK, ACCENT, "#d68910", GUIDE)


@contextlib.contextmanager
def style():
    """Apply the project's style sheet inside the ``with`` block."""
    with as_file(files(__package__) / "escapement.mplstyle") as sheet, plt.style.context(str(sheet)):
        yield


def _atomic_savefig(fig, path: Path, **kwargs) -> None:
    with atomic_path(path) as tmp:
        fig.savefig(tmp, **kwargs)


def save_figure(fig, png: str | os.PathLike, pdf: str | os.PathLike) -> None:
    """Save as PNG and PDF with no software stamp or creation date, so that the same
    figure gives the same bytes on every run."""
    with style():
        _atomic_savefig(fig, Path(png), format="png", metadata={"Software": None})
        no_dates = {"Creator": None, "Producer": None, "CreationDate": None}
        _atomic_savefig(fig, Path(pdf), format="pdf", metadata=no_dates)
    plt.close(fig)
