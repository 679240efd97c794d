"""What a run is asked, checked once (escapement.model.limits): the run spec every solver entry point starts
with, the limits and their defaults, and the memory budget's one check."""

import math

import numpy as np
import pytest

from escapement.model.arguments import ParameterTypeError
from escapement.model.limits import (MAX_CYCLES, MEMORY_BUDGET, MemoryBudgetError, RunLimits, check_budget,
                                     events_for, run_spec)
from escapement.model.parameters import ParameterArrays, ParameterError, Parameters

P = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)
GOOD = dict(params=P, x0=1.0, v0=0.0, n_cycles=3)

#: every refusal of the run spec: the arguments changed, the name refused and its requirement, whole
REFUSED = [
    ({"params": dict(M=1.0)}, "params", "an escapement.Parameters (make one with Parameters(M=..., ...))"),
    ({"x0": math.nan}, "x0", "finite"),
    ({"v0": "0"}, "v0", "a real number"),
    ({"x0": 1e200}, "x0", "0 or of magnitude in [1e-50, 1e+50] (m), so that the squares and products the solvers "
                          "form (omega**2 = K/M, F/K, v/omega, squared speeds, energies) stay normal float64 numbers"),
    ({"n_cycles": None}, "n_cycles", "given (a positive integer) when t_end is not"),
    ({"n_cycles": 0}, "n_cycles", "a positive integer, at most 1_000_000_000"),
    ({"n_cycles": 2.5}, "n_cycles", "a positive integer, at most 1_000_000_000"),
    ({"n_cycles": True}, "n_cycles", "a positive integer, at most 1_000_000_000"),
    ({"n_cycles": np.array(3)}, "n_cycles", "a positive integer, at most 1_000_000_000"),
    ({"n_cycles": MAX_CYCLES + 1}, "n_cycles", "a positive integer, at most 1_000_000_000"),
    ({"n_cycles": None, "t_end": -1.0}, "t_end", "> 0 (s)"),
    ({"t_end": math.inf}, "t_end", "finite"),
    ({"t_end": [5.0]}, "t_end", "a single real number, not an array or a sequence"),
    ({"max_events": 0}, "max_events", "a positive integer, at most 5_000_000_000"),
    ({"max_events": False}, "max_events", "a positive integer, at most 5_000_000_000"),
    ({"max_events": 5 * 10**9 + 1}, "max_events", "a positive integer, at most 5_000_000_000"),
    ({"memory_budget": 2e9}, "memory_budget", "a positive integer, at most 1_000_000_000_000"),
    ({"memory_budget": 10**12 + 1}, "memory_budget", "a positive integer, at most 1_000_000_000_000"),
]


@pytest.mark.parametrize("changes, name, requirement", REFUSED, ids=[f"{n}-{i}" for i, (_, n, _) in enumerate(REFUSED)])
def test_the_run_spec_refuses_each_bad_argument_naming_it(changes, name, requirement):
    with pytest.raises(ParameterError) as err:
        run_spec(**{**GOOD, **changes})
    assert (err.value.name, err.value.requirement) == (name, requirement)
    assert str(err.value) == f"{name} = {changes[name]!r} is invalid: {name} must be {requirement}"
    assert isinstance(err.value, ParameterTypeError) == (name == "params")
    assert not isinstance(err.value, MemoryBudgetError)


def test_the_spec_holds_the_checked_run_or_rows_and_the_limits_their_defaults():
    spec = run_spec(P, 1, np.float32(0.5), n_cycles=np.int32(3))
    assert (spec.params, spec.x0, spec.v0) == (P, 1.0, 0.5) and type(spec.x0) is float
    assert spec.limits == RunLimits(n_cycles=3, max_events=4 * (3 + 2) + 8, memory_budget=MEMORY_BUDGET)
    assert type(spec.limits.n_cycles) is int
    assert run_spec(P, 1.0, t_end=5).limits == RunLimits(t_end=5.0, max_events=10**7)
    assert events_for(0) == 16 and events_for(10) == 56  # four events a cycle and a margin for the first ones
    # an ensemble's: its rows checked and flat
    spec = run_spec(dict(M=1.0, K=[[1.0, 4.0]], F=0.5, b=0.1, a1=-0.1, a2=0.05), [1.0, 2.0], 0.0, n_cycles=2,
                    rows=lambda n, k: 0)
    assert isinstance(spec.params, ParameterArrays)
    assert spec.params.K.tolist() == [1.0, 4.0] and spec.params.a3.tolist() == [0.1, 0.1]
    assert spec.params.omega.tolist() == [1.0, 2.0] and spec.params.zone_offset.tolist() == [0.5, 0.125]
    assert spec.x0.tolist() == [1.0, 2.0] and spec.v0.tolist() == [0.0, 0.0]


def test_an_ensemble_too_large_is_refused_from_its_shapes_before_its_rows_are_checked():
    asked = []

    def size(n: int, cycles: int) -> int:
        asked.append((n, cycles))
        return 10 * n * cycles

    with pytest.raises(MemoryBudgetError) as err:  # a bad row, but the size is refused first
        run_spec(dict(M=[1.0, -1.0, 1.0], K=1.0, F=0.5, b=0.1, a1=-0.1, a2=0.05), 1.0, 0.0, n_cycles=100,
                 memory_budget=1000, rows=size)
    assert (err.value.name, err.value.value, err.value.estimate) == ("n_cycles", 100, 3000)
    assert err.value.requirement.startswith("at most 33 for the run to fit its memory budget")
    assert asked[0] == (3, 100)


# --- the memory budget's one check -------------------------------------------------------------------


def linear(n: int) -> int:
    """100 bytes whatever the count, 10 bytes a unit of it."""
    return 100 + 10 * n


@pytest.mark.parametrize("counts, budget, name, value, requirement", [
    ([("n", 200, linear)], 1_000, "n", 200, "at most 90 for the run to fit its memory budget: it would store "
     "things, an estimated 2_100 bytes, over the memory budget of 1_000 bytes; store fewer"),
    ([("n", 200, linear)], 110, "n", 200, "at most 1 for the run"),
    ([("n", 200, linear)], 109, "memory_budget", 109, "at least 110 bytes, those of a run of n = 1 (it would store "
     "things, an estimated 2_100 bytes, over the memory budget of 109 bytes)"),
    # the first count that fits at 1 (the other as asked) is named: 100 + 10 n m bytes, here m
    ([("n", 5, lambda n: 100 + 10 * n * 50), ("m", 50, lambda m: 100 + 10 * 5 * m)], 500, "m", 50, "at most 8 for"),
    ([("n", 10**9, lambda n: 200 * n)], 2 * 10**9, "n", 10**9, "at most 10_000_000 for the run to fit its memory "
     "budget: it would store things, an estimated 200_000_000_000 bytes (200 GB), over the memory budget of "
     "2_000_000_000 bytes (2 GB)"),
])
def test_a_run_over_its_budget_is_refused_naming_the_most_that_fits(counts, budget, name, value, requirement):
    with pytest.raises(MemoryBudgetError) as err:
        check_budget(budget, "things", counts, "store fewer")
    assert (err.value.name, err.value.value, err.value.budget) == (name, value, budget)
    assert err.value.estimate == counts[0][2](counts[0][1]) and err.value.requirement.startswith(requirement)
    assert check_budget(1_000, "things", [("n", 90, linear)]) == 1_000  # within the budget: the estimate
