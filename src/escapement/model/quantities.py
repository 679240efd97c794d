"""Every quantity of the model by name: its symbol, units and long name, defined once.

The configuration, :class:`~escapement.model.parameters.Parameters`, the netCDF writers and
readers, the figure labels and the error messages all take names, units and descriptions from
here. Units are UDUNITS strings (as CF requires) with a plain-text form for labels and messages.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Quantity", "PARAMETERS", "INITIAL_STATE", "MODEL_KEYS", "REQUIRED_KEYS", "quantity"]


@dataclass(frozen=True)
class Quantity:
    """One named quantity.

    ``name`` is the key in the configuration, in :class:`Parameters` and in the netCDF files;
    ``symbol`` the paper's symbol for labels; ``units`` the UDUNITS string; ``unit_label`` the
    units as printed in axis labels and messages.
    """

    name: str
    symbol: str
    units: str
    unit_label: str
    long_name: str

    def label(self) -> str:
        """An axis label: ``long name (units)``, or just the long name for a pure number."""
        return self.long_name if self.unit_label == "1" else f"{self.long_name} ({self.unit_label})"


def _table(*rows: Quantity) -> dict[str, Quantity]:
    return {q.name: q for q in rows}


#: Model parameters (Sec. 2-3 of the paper, SI units)
PARAMETERS = _table(
    Quantity("M", "M", "kg", "kg", "mass"),
    Quantity("K", "K", "N m-1", "N/m", "spring constant"),
    Quantity("F", "F", "N", "N", "force of the escapement over an impulse zone"),
    Quantity("b", "b", "1", "1", "impact coefficient (v+ = (1 - b) v-)"),
    Quantity("a1", "a\u2081", "m", "m", "impact position of the first half cycle (moving right)"),
    Quantity("a2", "a\u2082", "m", "m", "end of the first impulse zone"),
    Quantity("a3", "a\u2083", "m", "m", "impact position of the second half cycle (moving left)"),
    Quantity("a4", "a\u2084", "m", "m", "end of the second impulse zone"),
)

#: The state at t = 0+ (Eq. (2): after any jump)
INITIAL_STATE = _table(
    Quantity("x0", "x(0)", "m", "m", "initial displacement"),
    Quantity("v0", "v(0)", "m s-1", "m/s", "initial velocity"),
)

MODEL_KEYS = tuple(PARAMETERS)
#: a3 and a4 default to the symmetric geometry a3 = -a1, a4 = -a2
REQUIRED_KEYS = ("M", "K", "F", "b", "a1", "a2")


def quantity(name: str) -> Quantity:
    """The quantity called ``name`` (a parameter or an initial-state component)."""
    if name in PARAMETERS:
        return PARAMETERS[name]
    return INITIAL_STATE[name]
