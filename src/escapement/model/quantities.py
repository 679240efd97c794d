"""Every quantity of the model by name, defined once: its symbol, units and long name, which the configuration,
:class:`~escapement.model.parameters.Parameters`, the netCDF files, the figures and the messages take from here.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Quantity", "PARAMETERS", "INITIAL_STATE", "VARIABLES", "MODEL_KEYS", "REQUIRED_KEYS", "SYMMETRIC_DEFAULTS",
           "quantity"]


@dataclass(frozen=True)
class Quantity:
    """One named quantity."""

    name: str  #: the key in the configuration, in :class:`~escapement.model.parameters.Parameters` and in files
    symbol: str  #: the paper's symbol, for labels ("" where the paper gives none)
    units: str  #: UDUNITS, as CF requires
    unit_label: str  #: the same units as printed in labels and messages
    long_name: str  #: what it is, in words (the CF ``long_name``, the configuration's ``title``)
    short_name: str = ""  #: for axis labels; default the long name

    @property
    def dimensionless(self) -> bool:
        """True for a pure number (units ``1``)."""
        return self.units == "1"

    def axis_label(self) -> str:
        """An axis label: ``Force F (N)``; a pure number has no units: ``Impact coefficient b``."""
        name = self.short_name or self.long_name
        text = " ".join(part for part in (name[:1].upper() + name[1:], self.symbol) if part)
        return text if self.dimensionless else f"{text} ({self.unit_label})"


#: the model's parameters (Sec. 2-3 of the paper)
PARAMETERS = {q.name: q for q in (
    Quantity("M", "M", "kg", "kg", "mass"),
    Quantity("K", "K", "N m-1", "N/m", "spring constant"),
    Quantity("F", "F", "N", "N", "force of the escapement over an impulse zone", "force"),
    Quantity("b", "b", "1", "1", "impact coefficient (v+ = (1 - b) v-)", "impact coefficient"),
    Quantity("a1", "a\u2081", "m", "m", "impact position of the first half cycle (moving right)"),
    Quantity("a2", "a\u2082", "m", "m", "end of the first impulse zone"),
    Quantity("a3", "a\u2083", "m", "m", "impact position of the second half cycle (moving left)"),
    Quantity("a4", "a\u2084", "m", "m", "end of the second impulse zone"),
)}

#: the state at t = 0+ (Eq. (2): after any jump)
INITIAL_STATE = {q.name: q for q in (
    Quantity("x0", "x(0)", "m", "m", "initial displacement"),
    Quantity("v0", "v(0)", "m s-1", "m/s", "initial velocity"),
)}

#: the computed variables of a run, by their names in the datasets (cycle k starts at the k-th impact at a1)
VARIABLES = {q.name: q for q in (
    Quantity("t", "t", "s", "s", "time since release", "time"),
    Quantity("displacement", "x", "m", "m", "displacement x", "displacement"),
    Quantity("velocity", "v", "m s-1", "m/s", "velocity dx/dt", "velocity"),
    Quantity("acceleration", "", "m s-2", "m/s\u00b2", "acceleration d2x/dt2 between impacts", "acceleration"),
    Quantity("impulse", "", "N s", "N s", "impulse of the impact force, M (v+ - v-)", "impulse"),
    Quantity("energy_dissipated", "", "J", "J", "kinetic energy dissipated by the impact", "energy dissipated"),
    Quantity("impact_time", "", "s", "s", "time of impact k at a1 (start of cycle k)", "impact time"),
    Quantity("velocity_before_impact", "", "m s-1", "m/s", "velocity just before impact k at a1",
             "velocity before impact"),
    Quantity("period", "", "s", "s", "time from impact k to impact k+1 at a1", "period"),
    Quantity("largest_displacement", "", "m", "m", "largest displacement between impact k and impact k+1 (right "
             "turning point)", "largest displacement"),
    Quantity("amplitude_h0", "h\u2080", "m", "m",
             "Step-1 amplitude h0(k) = sqrt(a1^2 + (v_k / omega)^2) of the free arc that ends in impact k at a1 "
             "(k = 1 .. N+1; Eqs. (9b), (22a))", "amplitude"),
    Quantity("amplitude_h4", "h\u2084", "m", "m",
             "Step-8 amplitude h4(k) = h0(k+1) of the free arc that ends cycle k (k = 1 .. N)", "amplitude"),
    Quantity("largest_abs_displacement", "", "m", "m", "largest |x| between impact k and impact k+1", "largest |x|"),
    Quantity("event_time", "", "s", "s", "time of the event", "event time"),
    Quantity("event_kind", "", "1", "1", "kind of event"),
    Quantity("event_position", "", "m", "m", "position of the event"),
    Quantity("event_velocity_before", "", "m s-1", "m/s", "velocity just before the event"),
    Quantity("event_velocity_after", "", "m s-1", "m/s", "velocity just after the event"),
)}

MODEL_KEYS = tuple(PARAMETERS)
#: the parameters that may be left out, each defaulting to minus its mirror: a3 = -a1, a4 = -a2
SYMMETRIC_DEFAULTS = {"a3": "a1", "a4": "a2"}
REQUIRED_KEYS = tuple(name for name in MODEL_KEYS if name not in SYMMETRIC_DEFAULTS)


def quantity(name: str) -> Quantity:
    """The parameter, initial-state component or computed variable called ``name`` (:class:`KeyError`: none)."""
    return {**PARAMETERS, **INITIAL_STATE, **VARIABLES}[name]
