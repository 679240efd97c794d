"""The table of quantities: units with the dimensions the model's equations require, and the
documentation and configuration schema that state the same names and units."""

import dataclasses
import re
from pathlib import Path

import pytest
import yaml
from cf_units import Unit

from escapement.model.parameters import ParameterError, Parameters
from escapement.model.quantities import (INITIAL_STATE, MODEL_KEYS, PARAMETERS, REQUIRED_KEYS, SYMMETRIC_DEFAULTS,
                                         VARIABLES, Quantity, quantity)

SCHEMA = yaml.load((Path(__file__).parents[2] / "workflow/schemas/config.schema.yaml").read_text(),
                   Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
ALL = {**PARAMETERS, **INITIAL_STATE, **VARIABLES}
VALID = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)


def unit(name: str) -> Unit:
    return Unit(quantity(name).units)


MASS, LENGTH, TIME = Unit("kg"), Unit("m"), Unit("s")

#: what the model's equations require of the units (Sec. 2 of the paper): the SI base units of
#: mass, length and time, and M x'' + K x = F, v+ = (1 - b) v-, omega**2 = K/M
RELATIONS = {
    "the mass is in kilograms": lambda: (unit("M"), MASS),
    "a position is a length": lambda: (unit("displacement"), LENGTH),
    **{f"{name} is a position": lambda name=name: (unit(name), unit("displacement"))
       for name in ("x0", "a1", "a2", "a3", "a4", "largest_displacement", "event_position")},
    "time is in seconds": lambda: (unit("t"), TIME),
    "the period is a time": lambda: (unit("period"), unit("t")),
    "an impact time is a time": lambda: (unit("impact_time"), unit("t")),
    "velocity is length over time": lambda: (unit("velocity"), unit("displacement") / unit("t")),
    "the initial velocity is a velocity": lambda: (unit("v0"), unit("velocity")),
    "the velocity before impact is a velocity": lambda: (unit("velocity_before_impact"), unit("velocity")),
    "acceleration is velocity over time": lambda: (unit("acceleration"), unit("velocity") / unit("t")),
    "F = M x''": lambda: (unit("F"), unit("M") * unit("acceleration")),
    "K x is a force": lambda: (unit("K") * unit("displacement"), unit("F")),
    "omega**2 = K/M is 1/time**2": lambda: (unit("K") / unit("M"), TIME ** -2),
    "the zone offset F/K is a length": lambda: (unit("F") / unit("K"), LENGTH),
    "(1 - b) v is a velocity: b is a pure number": lambda: (unit("b"), Unit("1")),
    "the impulse is M (v+ - v-)": lambda: (unit("impulse"), unit("M") * unit("velocity")),
    "the energy dissipated is M v**2 / 2": lambda: (unit("energy_dissipated"), unit("M") * unit("velocity") ** 2),
    "an event's time is a time": lambda: (unit("event_time"), unit("t")),
    "the velocity before an event is a velocity": lambda: (unit("event_velocity_before"), unit("velocity")),
    "the velocity after an event is a velocity": lambda: (unit("event_velocity_after"), unit("velocity")),
    "an event's kind is a code": lambda: (unit("event_kind"), Unit("1")),
}


@pytest.mark.parametrize("relation", list(RELATIONS))
def test_units_have_the_dimensions_the_equations_require(relation):
    have, need = RELATIONS[relation]()
    assert have == need, f"{relation}: {have} is not {need}"


@pytest.mark.parametrize("name", list(ALL))
def test_each_quantity_is_found_by_its_name_and_its_printed_units_mean_its_udunits(name):
    q = quantity(name)
    assert q is ALL[name] and q.name == name
    assert Unit(q.unit_label) == Unit(q.units), f"{name}: {q.unit_label!r} is not {q.units!r}"
    assert q.dimensionless == (Unit(q.units) == Unit("1"))


def test_the_model_keys_are_the_fields_of_parameters_in_order_and_no_other_name_is_a_quantity():
    assert tuple(f.name for f in dataclasses.fields(Parameters)) == (*MODEL_KEYS, "release_force", "past_accumulation")
    with pytest.raises(KeyError):
        quantity("omega")


@pytest.mark.parametrize("name", MODEL_KEYS)
def test_a_key_may_be_left_out_exactly_when_it_has_a_symmetric_default(name):
    values = {key: value for key, value in {**VALID, "a3": 0.2, "a4": -0.01}.items() if key != name}
    if name in REQUIRED_KEYS:
        with pytest.raises(ParameterError, match=f"^{name} = None is invalid"):
            Parameters.from_mapping(values)
    else:
        assert getattr(Parameters.from_mapping(values), name) == -values[SYMMETRIC_DEFAULTS[name]]


def test_an_axis_label_shows_the_symbol_and_units_except_for_pure_numbers():
    assert Quantity("l", "L", "m", "m", "length of the pendulum", "length").axis_label() == "Length L (m)"
    assert Quantity("q", "", "1", "1", "quality factor").axis_label() == "Quality factor"
    assert Quantity("w", "\u03c9", "s-1", "1/s", "angular frequency").axis_label() == "Angular frequency \u03c9 (1/s)"


# --- the documentation and the configuration state the table's names and units ------------------


def test_the_docstring_of_parameters_documents_each_parameter_with_its_long_name_and_units():
    entries = re.findall(r"^ *(\w+) : (.*)\n *(.*)$", Parameters.__doc__, re.M)
    assert [name for name, _, _ in entries] == [*PARAMETERS, "release_force", "past_accumulation"]
    for name, kind, text in entries[:len(PARAMETERS)]:  # then the model's choices, which are no quantities
        q = PARAMETERS[name]
        assert q.long_name.lower() in text.lower(), name
        assert ("dimensionless" if q.dimensionless else f", {q.unit_label}") in text, name
        assert ("optional" in kind) == (name not in REQUIRED_KEYS), name


#: the quantities a configuration gives
CONFIGURED = {**PARAMETERS, **INITIAL_STATE}


def _refers_to(node: dict) -> set[str]:
    """The configured quantities a schema node holds, through a ``$ref`` (also of its items and alternatives)."""
    refs = [node.get("$ref"), node.get("items", {}).get("$ref")]
    for alternative in node.get("anyOf", []):
        refs += [alternative.get("$ref"), alternative.get("items", {}).get("$ref")]
    return {ref.rsplit("/", 1)[1] for ref in refs if ref} & set(CONFIGURED)


def _described(node, key=None):
    """Every node of the schema with a description, with the quantity it holds (or None)."""
    if isinstance(node, dict):
        if "description" in node:
            held = ({key} & set(CONFIGURED)) | _refers_to(node)
            yield node["description"], (held.pop() if held else None)
        for child_key, child in node.items():
            yield from _described(child, child_key)
    elif isinstance(node, list):
        for child in node:
            yield from _described(child, key)


#: each description in the schema of a quantity with units, and the quantity
DESCRIBED = [(text, name) for text, name in _described(SCHEMA) if name and not CONFIGURED[name].dimensionless]


def test_the_schema_describes_the_dimensional_parameters_in_several_places_and_titles_them_by_their_long_names():
    described = [name for _, name in DESCRIBED]
    assert set(described) == {"M", "K", "F", "a1", "a2", "a3", "a4", "x0"}
    assert described.count("K") > 1 and described.count("F") > 1
    assert {name: SCHEMA["$defs"]["model"]["properties"][name]["title"] for name in MODEL_KEYS} == {
        name: q.long_name for name, q in PARAMETERS.items()}


@pytest.mark.parametrize("text, name", DESCRIBED)
def test_each_description_of_a_quantity_in_the_schema_states_the_tables_units(text, name):
    stated = re.findall(r"\(([^()]*)\)", text)
    assert CONFIGURED[name].unit_label in stated, f"{name}: {text!r} does not state {CONFIGURED[name].unit_label}"
