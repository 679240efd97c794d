"""The words on the figures: axis labels, quantities with their values and units, how a run was
released, which parameters a panel states, and how a run that did not complete ended.

Names, symbols and units come from :mod:`escapement.model.quantities`, values and outcomes from the
datasets. A figure's title is its caller's; what a figure assumes or how it scores goes in the
caption its caller writes, not here.
"""

from __future__ import annotations

from collections.abc import Iterable

import xarray as xr

from ..model.quantities import quantity
from ..model.status import Status

__all__ = ["PARAMETERS", "axis_label", "outcome", "panel_parameters", "quantity_value", "release",
           "shared_parameters", "signed", "unit"]

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
    """``released from rest at x(0) = 3 m``, or ``released at x(0) = 3 m with v(0) = 0.5 m/s``."""
    x0 = quantity_value("x0", float(ds["x0"]))
    v0 = float(ds["v0"]) if "v0" in ds else 0.0
    return f"released from rest at {x0}" if v0 == 0 else f"released at {x0} with {quantity_value('v0', v0)}"


def _differing(datasets: list[xr.Dataset]) -> set[str]:
    return {k for k in PARAMETERS if len({float(ds[k]) for ds in datasets if k in ds}) > 1}


def panel_parameters(ds: xr.Dataset, datasets: Iterable[xr.Dataset], always: tuple[str, ...] = ("F", "K")) -> str:
    """The parameters a panel states: those of ``always`` and those that differ between ``datasets`` (the
    figure's panels), with their values in ``ds``, e.g. ``F = 1 N, K = 0.1 N/m``."""
    differing = _differing(list(datasets))
    return ", ".join(quantity_value(k, float(ds[k])) for k in PARAMETERS if k in ds and (k in always or k in differing))


def shared_parameters(datasets: Iterable[xr.Dataset], leave_out: tuple[str, ...] = ("F", "K")) -> str:
    """The parameters the panels share (all of :data:`PARAMETERS` but ``leave_out`` and those that
    differ), for a caller's title, e.g. ``M = 1 kg, b = 0.1, a₁ = −0.1 m, ...``."""
    datasets = list(datasets)
    differing = _differing(datasets)
    first = datasets[0]
    return ", ".join(quantity_value(k, float(first[k])) for k in PARAMETERS
                     if k in first and k not in leave_out and k not in differing)


def outcome(ds: xr.Dataset, count: str = "cycle") -> str | None:
    """How a run that did not complete ended, in a few words (``stopped after 2 of 50 cycles``); None if
    it completed. The dataset's ``outcome_message`` says more, for the caption."""
    status = Status(ds.attrs.get("outcome", Status.COMPLETED.value))
    if status.success:
        return None
    done = ds.sizes.get(count, 0)
    asked = ds.attrs.get("n_cycles")
    return f"{status.value.replace('_', ' ')} after {done}" + (f" of {asked}" if asked else "") + " cycles"
