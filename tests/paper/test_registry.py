"""The one list of the register's checks: every marked check is in it, and nothing registers on import."""

import importlib
import pkgutil

import pytest

import escapement.paper
from escapement.paper import checks, registry
from escapement.paper.checks import Check, check, runs_only
from escapement.paper.registry import CHECKS, REGISTERED, by_name


def _marked_checks() -> set[str]:
    """The names of every function marked as a check in the paper's modules."""
    names = set()
    for module in pkgutil.iter_modules(escapement.paper.__path__):
        namespace = vars(importlib.import_module(f"escapement.paper.{module.name}"))
        names |= {value.check.name for value in namespace.values() if isinstance(getattr(value, "check", None), Check)}
    return names


def test_every_marked_check_is_listed_once():
    assert len(CHECKS) == len(REGISTERED)
    assert set(CHECKS) == _marked_checks()


def test_each_entry_is_the_check_of_its_function():
    for function in REGISTERED:
        assert CHECKS[function.check.name].function is function


def test_marking_a_function_registers_nothing():
    before = dict(CHECKS)

    @check("a_new_check", scenes=runs_only)
    def a_new_check(claim, ev):
        return None

    assert a_new_check.check == Check("a_new_check", a_new_check, runs_only, ())
    assert CHECKS == before and "a_new_check" not in registry.CHECKS


def test_an_unmarked_function_or_a_repeated_name_is_refused():
    with pytest.raises(ValueError, match="not marked as a check"):
        by_name([len])
    with pytest.raises(ValueError, match="two checks are named 'fixed_point'"):
        by_name([checks.fixed_point, checks.fixed_point])
