"""The public API's docstrings: every name ``escapement.__all__`` exports, the method of
:class:`escapement.Solution` and the function of :mod:`escapement.io` that a notebook reaches
for, has numpydoc sections (Parameters with a type and, for the model's quantities, the SI unit;
Returns for functions; Examples), and the examples run as doctests."""

from __future__ import annotations

import doctest
import enum
import inspect
import re

import pytest

import escapement
import escapement.scenes
from escapement.model.quantities import INITIAL_STATE, PARAMETERS

EXPORTED = {name: getattr(escapement, name) for name in escapement.__all__ if name != "__version__"}
METHODS = {
    "Solution.to_dataframe": escapement.Solution.to_dataframe,
    "scenes.run_dataset": escapement.scenes.run_dataset,
}
DOCUMENTED = {**EXPORTED, **METHODS}
#: the unit each quantity's entry names: the plain-text label of escapement.model.quantities
UNITS = {name: q.unit_label for name, q in {**PARAMETERS, **INITIAL_STATE}.items()} | {"b": "dimensionless",
                                                                                        "t_end": "s", "step": "s"}
FLAGS = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS


def sections(doc: str) -> dict[str, list[str]]:
    """The numpydoc sections of ``doc``: each title (a line underlined by as many dashes) to its lines."""
    lines = inspect.cleandoc(doc).splitlines()
    found: dict[str, list[str]] = {}
    current = None
    for i, line in enumerate(lines):
        below = lines[i + 1].strip() if i + 1 < len(lines) else ""
        if line.strip() and re.fullmatch(r"-+", below) and len(below) == len(line.strip()):
            current = line.strip()
            found[current] = []
        elif current is not None and not (re.fullmatch(r"-+", line.strip()) and not found[current]):
            found[current].append(line)
    return found


def entries(lines: list[str]) -> dict[str, str]:
    """The entries of a Parameters section: each name to its type line and description."""
    out: dict[str, str] = {}
    name = None
    for line in lines:
        head = re.fullmatch(r"(\w+)( : .+)?", line)
        if head:
            name = head.group(1)
            out[name] = line
        elif name is not None:
            out[name] += "\n" + line
    return out


def signature_names(obj) -> set[str] | None:
    """The parameters ``obj`` is called with (None for an enumeration: it takes its member's value)."""
    if inspect.isclass(obj) and issubclass(obj, enum.Enum):
        return None
    return {name for name in inspect.signature(obj).parameters if name != "self"}


def test_the_parser_finds_sections_and_entries():
    doc = """One line.

    Parameters
    ----------
    x0 : float
        Initial displacement, m.
    flag : bool

    Returns
    -------
    int
    """
    found = sections(doc)
    assert list(found) == ["Parameters", "Returns"]
    assert set(entries(found["Parameters"])) == {"x0", "flag"}
    assert "m." in entries(found["Parameters"])["x0"]


@pytest.mark.parametrize("name", sorted(DOCUMENTED))
def test_numpydoc_sections(name):
    obj = DOCUMENTED[name]
    found = sections(obj.__doc__ or "")
    assert "Examples" in found, f"{name}: no Examples section"
    if inspect.isroutine(obj):
        assert "Returns" in found, f"{name}: no Returns section"
    expected = signature_names(obj)
    if expected == set():
        assert "Parameters" not in found, f"{name} takes no argument"
        return
    assert "Parameters" in found, f"{name}: no Parameters section"
    documented = entries(found["Parameters"])
    if expected is None:  # an enumeration: called with its member's value
        assert set(documented) == {"value"}, name
        assert "Attributes" in found, f"{name}: its members are not listed under Attributes"
    else:
        assert set(documented) == expected, f"{name}: documented {sorted(documented)}, takes {sorted(expected)}"
    for entry, text in documented.items():
        assert " : " in text.splitlines()[0], f"{name}: parameter {entry} has no type"
        if entry in UNITS:
            assert re.search(rf"(?<![\w/]){re.escape(UNITS[entry])}(?![\w/])", text), \
                f"{name}: parameter {entry} does not give its unit {UNITS[entry]}"


def collect() -> list[doctest.DocTest]:
    """The doctests of every exported name (classes with their methods) and of :data:`METHODS`, each once."""
    finder = doctest.DocTestFinder()
    found: dict[str, doctest.DocTest] = {}
    for name, obj in DOCUMENTED.items():
        for test in finder.find(obj, name, globs={}):  # empty globals: each example imports what it uses
            if test.examples:
                found.setdefault(test.name.removeprefix("escapement."), test)
    return [found[key] for key in sorted(found)]


DOCTESTS = collect()


def test_every_documented_name_has_a_doctest():
    names = {test.name for test in DOCTESTS}
    assert set(DOCUMENTED) <= names, sorted(set(DOCUMENTED) - names)


@pytest.mark.parametrize("test", DOCTESTS, ids=[test.name for test in DOCTESTS])
def test_examples_run(test):
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report: list[str] = []
    result = runner.run(test, out=report.append)
    assert result.attempted == len(test.examples) > 0
    assert result.failed == 0, "".join(report)
