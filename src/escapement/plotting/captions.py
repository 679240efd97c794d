"""The words on the figures: axis labels, values with their units, releases, outcomes, a panel's parameters and what
a study of the user's own changed; names, symbols and units from :mod:`escapement.model.quantities`.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Iterable

import xarray as xr

from ..model.quantities import INITIAL_STATE, PARAMETERS as QUANTITIES, quantity
from ..model.status import Status

__all__ = ["CHANGES_FONTSIZE", "PARAMETERS", "axis_label", "changes_legend", "outcome", "panel_parameters",
           "quantity_value", "release", "signed", "study_changes", "thinning", "unit"]

#: the model's parameters in the order a title or panel states them
PARAMETERS = ("F", "K", "M", "b", "a1", "a2", "a3", "a4")


def axis_label(name: str) -> str:
    """The axis label of the quantity ``name``, e.g. ``Force F (N)``."""
    return quantity(name).axis_label()


def unit(name: str) -> str:
    """The units of the quantity ``name`` as printed (empty for a pure number), e.g. ``N s``."""
    q = quantity(name)
    return "" if q.dimensionless else q.unit_label


def signed(value: float, spec: str) -> str:
    """``value`` formatted by ``spec`` with the minus sign of the tick labels (U+2212)."""
    return format(value, spec).replace("-", "\u2212")


def quantity_value(name: str, value: float) -> str:
    """``F = 0.5 N``: symbol, value and units joined by no-break spaces (a line never breaks inside)."""
    units = unit(name)
    return f"{quantity(name).symbol}\u00a0=\u00a0{signed(value, 'g')}" + (f"\u00a0{units}" if units else "")


def release(ds: xr.Dataset) -> str:
    """How a run was released: ``from rest at x(0) = 3 m``, or ``at x(0) = 3 m with v(0) = 0.5 m/s``."""
    x0 = quantity_value("x0", float(ds["x0"]))
    v0 = float(ds["v0"]) if "v0" in ds else 0.0
    return f"from rest at {x0}" if v0 == 0 else f"at {x0} with {quantity_value('v0', v0)}"


def panel_parameters(ds: xr.Dataset, datasets: Iterable[xr.Dataset], always: tuple[str, ...] = ("F", "K")) -> str:
    """The parameters of ``always`` and those that differ between ``datasets`` (the figure's panels), valued as in
    ``ds``: ``F = 1 N, K = 0.1 N/m``."""
    datasets = list(datasets)
    differing = {k for k in PARAMETERS if len({float(d[k]) for d in datasets if k in d}) > 1}
    return ", ".join(quantity_value(k, float(ds[k])) for k in PARAMETERS if k in ds and (k in always or k in differing))


def outcome(ds: xr.Dataset) -> str | None:
    """How a run that did not complete ended (``stopped after 2 of 50 cycles``); None if it completed."""
    status = Status(ds.attrs.get("outcome", Status.COMPLETED.value))
    if status.success:
        return None
    done = ds.sizes.get("cycle", 0)
    asked = ds.attrs.get("n_cycles")
    return f"{status.value.replace('_', ' ')} after {done}" + (f" of {asked}" if asked else "") + " cycles"


#: the font size of the line that names a study's changes (the title of the legend below the axes)
CHANGES_FONTSIZE = 7.0
#: a value with its units in a dataset's ``study_changes``: ``a3 = 0.12 m``, ``zones.wide = [-0.3, 0.2] m``
_VALUE = re.compile(r"(?P<key>[\w.]+) = (?P<value>\[[^\]]*\]|\S+?)(?P<units> (?:%s))?(?=[,;)]|$| \()" % "|".join(
    sorted({re.escape(q.unit_label) for q in (*QUANTITIES.values(), *INITIAL_STATE.values()) if q.units != "1"},
           key=len, reverse=True)))


def _unbroken(match: re.Match) -> str:
    """One value of a study's changes, by the parameter's symbol, on one line."""
    key = match["key"]
    symbol = quantity(key).symbol if key in QUANTITIES or key in INITIAL_STATE else key
    value = match["value"].replace(" ", "\u00a0")
    return f"{symbol}\u00a0=\u00a0{value}" + (f"\u00a0{match['units'].strip()}" if match["units"] else "")


def study_changes(datasets: Iterable[xr.Dataset]) -> str | None:
    """What a study of the user's own changed, as its datasets' ``study_changes`` say it (each text once), each
    parameter by its symbol, no value broken across lines; None where no dataset has it (the replication)."""
    said = dict.fromkeys(str(ds.attrs["study_changes"]) for ds in datasets if ds.attrs.get("study_changes"))
    if not said:
        return None
    text = _VALUE.sub(_unbroken, "; ".join(said))
    text = re.sub(r"\(paper: [^)]*\)", lambda m: m[0].replace(" ", "\u00a0"), text)
    return "Changed from the paper's scenes: " + re.sub(r"(?<![\w.])-(?=[\d.])", "\u2212", text)


def _wrapped(fig, text: str) -> str:
    """``text`` wrapped to the figure's width at :data:`CHANGES_FONTSIZE`, in characters of about 0.6 em."""
    return textwrap.fill(text, int(fig.get_figwidth() * 72 / (0.6 * CHANGES_FONTSIZE)), break_on_hyphens=False)


def changes_legend(fig, datasets: Iterable[xr.Dataset], note: str | None = None) -> dict:
    """The legend's keywords that title it ``note`` and :func:`study_changes`, wrapped; none if neither is."""
    said = [_wrapped(fig, text) for text in (note, study_changes(datasets)) if text]
    return {"title": "\n".join(said), "title_fontsize": CHANGES_FONTSIZE} if said else {}


def thinning(fig, samples: int, kept: int, rastered: int, column_dpi: float, dpi: float) -> str | None:
    """How a figure's lines were thinned and rastered, wrapped to its width; None if none was."""
    said = ([f"Drawn from 1 of every {samples / kept:,.0f} samples ({samples:,} as {kept:,}), each 1/{column_dpi:g}"
             "-inch column's first, last, smallest and largest kept: every extreme"] if samples else [])
    said += [f"{rastered:,} vertices drawn as a raster of {dpi:g} dpi, every one rendered"] if rastered else []
    return _wrapped(fig, "; ".join(said)) if said else None
