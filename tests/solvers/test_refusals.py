"""What every entry point refuses before any work, a ParameterError naming the argument, its value and what it must
be: the run spec (tested whole in tests/model), each solver's options, the ensemble's rows, the results' methods."""

from __future__ import annotations

import math
from unittest import mock

import numpy as np
import pytest

from escapement import ParameterError, Parameters, solve_ensemble, solve_exact
from escapement.integrators.high_precision import solve_high_precision
from escapement.integrators.naive import solve_naive
from escapement.integrators.reference import solve_reference
from escapement.model.arguments import ParameterTypeError
from escapement.model.limits import MemoryBudgetError, run_spec
from escapement.solvers.cycles import iter_closed_form_cycles, solve_cycles
from escapement.solvers.stream import CHUNK_BYTES_PER_CYCLE, MAX_CHUNK, iter_cycles

P = Parameters(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.05)

#: every scalar entry point, as it is called for a short run (the arguments of the run spec given by name)
SOLVERS = {"solve_exact": solve_exact, "iter_cycles": iter_cycles, "solve_cycles": solve_cycles,
           "iter_closed_form_cycles": iter_closed_form_cycles,
           "solve_reference": lambda *a, **k: solve_reference(*a, **k, record_trajectory=False),
           "solve_high_precision": lambda *a, **k: solve_high_precision(*a, **k, dps=20),
           "solve_naive": lambda *a, **k: solve_naive(*a, **k, step=1e-3)}
#: bad arguments of the run spec, one of each kind: the checked parameters, the release, the counts
BAD_RUNS = {"params": dict(params={"M": 1.0}), "x0": dict(x0=math.nan), "v0": dict(v0=1e51),
            "n_cycles": dict(n_cycles=2.5)}


@pytest.mark.parametrize("argument", list(BAD_RUNS))
@pytest.mark.parametrize("entry", list(SOLVERS))
def test_every_scalar_solver_refuses_a_bad_run_as_the_run_spec_does(entry, argument):
    arguments = {"params": P, "x0": 1.0, "v0": 0.0, "n_cycles": 2, **BAD_RUNS[argument]}
    with pytest.raises(ParameterError) as spec:
        run_spec(**arguments)
    with pytest.raises(ParameterError) as err:
        SOLVERS[entry](arguments.pop("params"), arguments.pop("x0"), **arguments)
    assert str(err.value) == str(spec.value) and type(err.value) is type(spec.value)
    assert isinstance(err.value, ParameterTypeError) == (argument == "params")


@pytest.fixture(scope="module")
def run():
    return solve_exact(P, 1.0, n_cycles=2)


#: each solver's own options, and the methods of a run of 2 cycles: the call, the name refused, the flat index and
#: the start of the requirement
REFUSALS = [
    (lambda r: solve_exact(P, 1.0, n_cycles=2, record_trajectory="no"), "record_trajectory", None, "True or False"),
    (lambda r: solve_exact(P, 1.0, n_cycles=2, record_trajectory=1), "record_trajectory", None, "True or False"),
    (lambda r: iter_cycles(P, 1.0, n_cycles=2, chunk=0), "chunk", None, "a positive integer, at most 10_000_000"),
    (lambda r: iter_cycles(P, 1.0, n_cycles=2, chunk=True), "chunk", None, "a positive integer, at most 10_000_000"),
    (lambda r: iter_cycles(P, 1.0, n_cycles=2, chunk=MAX_CHUNK + 1), "chunk", None, "a positive integer, at most"),
    (lambda r: iter_closed_form_cycles(P, 1.0, n_cycles=2, chunk="100"), "chunk", None, "a positive integer"),
    (lambda r: iter_cycles(P, 1.0, n_cycles=10, chunk=1000, memory_budget=1000 * CHUNK_BYTES_PER_CYCLE - 1), "chunk",
     None, "at most 999 for the run to fit its memory budget: it would store chunks of 128 bytes a cycle, an "
     "estimated 128_000 bytes, over the memory budget of 127_999 bytes"),
    (lambda r: solve_reference(P, 1.0, n_cycles=2, method="rk4"), "method", None,
     "one of 'RK23', 'RK45', 'DOP853', 'Radau', 'BDF', 'LSODA', 'CVODE-Adams', 'CVODE-BDF'"),
    (lambda r: solve_reference(P, 1.0, n_cycles=2, rtol=1.0), "rtol", None,
     "in the open interval (0, 1), dimensionless"),
    (lambda r: solve_reference(P, 1.0, n_cycles=2, atol=0.0), "atol", None,
     "> 0 (m), or None for rtol times the run's length scale"),
    (lambda r: solve_reference(P, 1.0, n_cycles=2, method="CVODE-BDF"), "record_trajectory", None,
     "False with method = 'CVODE-BDF', which keeps no dense output"),
    (lambda r: solve_high_precision(P, 1.0, n_cycles=2, dps=16), "dps", None, "an integer >= 17, at most 1_000"),
    (lambda r: solve_high_precision(P, 1.0, n_cycles=2, dps=1.5), "dps", None, "an integer >= 17, at most 1_000"),
    # RK4 on x'' = -w**2 x is unstable from w h = 2.8 and passes events unseen well before: at most 1/20 of the
    # natural period 2 pi / w, printed as typed back (a step just above it cannot print below it)
    (lambda r: solve_naive(P, 1.0, n_cycles=1, step=2 * math.pi / 20 * (1 + 1e-12)), "step", None,
     "> 0 and at most 0.3141592653589793 s, 1/20 of the natural period 2 pi / omega"),
    (lambda r: solve_naive(P, 1.0, n_cycles=1, step=0.0), "step", None, "> 0 and at most 0.3141592653589793 s"),
    (lambda r: solve_naive(P, 1.0, n_cycles=1, step=np.array(0.01)), "step", None,
     "a single real number, not an array"),
    (lambda r: r.sample(None), "t", None, "a real number or a 1-d array of them (s)"),
    (lambda r: r.sample("1.0"), "t", None, "a real number"),
    (lambda r: r.sample([0.0, np.bool_(True)]), "t", 1, "a real number"),
    (lambda r: r.sample(np.ma.array([1.0, 2.0], mask=[False, True])), "t", 1, "a real number, not a masked element"),
    (lambda r: r.sample([0.0, math.inf]), "t", 1, "finite"),
    (lambda r: r.sample([[0.5]]), "t", None, "a real number or a 1-d array of them (s), not of shape (1, 1)"),
    (lambda r: r.trajectory.sample("1.0"), "t", None, "a real number"),
    (lambda r: r.to_dataframe("impacts"), "table", None, "one of 'cycles', 'events'"),
    (lambda r: r.to_dataframe(["cycles"]), "table", None, "one of 'cycles', 'events'"),
    (lambda r: solve_exact(P, 1.0, n_cycles=2, record_trajectory=False).sample([0.5]), "record_trajectory", None,
     "True in the solve that made this run, to sample its trajectory (this run kept none: solve again with "
     "record_trajectory=True)"),
    (lambda r: solve_ensemble(1.0, 1.0, [0.5, 1.0], 0.1, -0.1, 0.05, n_cycles=2).outcome(2), "i", None,
     "an integer in [0, 1], a row of the 2 trajectories"),
    (lambda r: solve_ensemble(1.0, 1.0, [0.5, 1.0], 0.1, -0.1, 0.05, n_cycles=2).outcome(True), "i", None,
     "an integer in [0, 1], a row of the 2 trajectories"),
]


@pytest.mark.parametrize("call, name, row, requirement", REFUSALS, ids=[f"{r[1]}-{i}" for i, r in enumerate(REFUSALS)])
def test_each_solver_option_and_each_results_method_refuses_a_bad_argument_naming_it(run, call, name, row,
                                                                                     requirement):
    with pytest.raises(ParameterError) as err:
        call(run)
    assert (err.value.name, err.value.row) == (name, row) and err.value.requirement.startswith(requirement), \
        err.value.requirement


#: the ensemble's own refusals: the inputs changed (each a column of three rows), the name, row and requirement
ENSEMBLE = [
    ({"b": [0.1, 0.2, True]}, "b", 2, "a real number"),
    ({"M": [1.0, 1.0, "1.0"]}, "M", 2, "a real number"),
    ({"F": np.ma.array([1.0, 1.0, 1.0], mask=[False, True, False])}, "F", 1,
     "a real number, not a masked element (it holds no value)"),
    ({"b": [0.1, 2.5, 0.1]}, "b", 1, "in the open interval (0, 2)"),
    ({"K": [1.0, 1e60, 1.0]}, "K", 1, "in [1e-50, 1e+50] (N/m)"),
    ({"a2": [0.05, 0.05, -0.2]}, "a2", 2, "> a1 = -0.1 (m)"),
    ({"x0": [1.0, 1.0, 1e200]}, "x0", 2, "0 or of magnitude in [1e-50, 1e+50] (m)"),
    ({"v0": [0.0, math.nan, 0.0]}, "v0", 1, "finite"),
    ({"x0": [1.0, 2.0]}, "x0", None, "an array broadcastable with the inputs before it, of shape (3,)"),
    ({"n_cycles": 0}, "n_cycles", None, "a positive integer, at most 1_000_000_000"),
    ({"max_events": 2.0}, "max_events", None, "a positive integer, at most 5_000_000_000"),
    ({"largest_displacement": "no"}, "largest_displacement", None, "True or False"),
    ({"n_cycles": 10**6, "memory_budget": 10**6}, "n_cycles", None, "at most 6_923 for the run to fit its memory "
     "budget: "
     "it would store the cycle tables of 3 trajectories, an estimated 144_003_000 bytes, over the memory budget"),
    ({"memory_budget": 10}, "memory_budget", None, "at least 1_144 bytes, those of a run of trajectories = 1"),
]


@pytest.mark.parametrize("changes, name, row, requirement", ENSEMBLE,
                         ids=[f"{n}-{i}" for i, (_, n, _, _) in enumerate(ENSEMBLE)])
def test_the_ensemble_refuses_a_bad_input_naming_it_and_its_row(changes, name, row, requirement):
    """The rules of Parameters and of the run spec, row by row; the memory of 3 trajectories of n cycles,
    3 (48 n + 1000) bytes, refused naming the most cycles that fit (6_923 in 1 MB) or, if not one, the budget."""
    inputs = {"M": [1.0] * 3, "K": 1.0, "F": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05, "x0": 1.0, "n_cycles": 3,
              **changes}
    with pytest.raises(ParameterError) as err:
        solve_ensemble(**inputs)
    assert (err.value.name, err.value.row) == (name, row) and err.value.requirement.startswith(requirement)
    prefix = "" if row is None else f"row {row}: "
    assert str(err.value).startswith(f"{prefix}{name} = ")


def test_inputs_too_large_are_refused_from_their_shapes_before_any_array_is_made():
    """10**8 trajectories given as a broadcast view (no memory of its own): refused naming the trajectories, the
    most that fit 2e9 / (48 * 20 + 1000) bytes each."""
    with mock.patch("escapement.model.limits.validate_arrays") as validate:
        with pytest.raises(MemoryBudgetError, match=r"^trajectories = 100000000 is invalid: trajectories must be at "
                                                     r"most 1_020_408 for the run to fit its memory budget"):
            solve_ensemble(M=1.0, K=1.0, F=np.broadcast_to(1.0, (10**8,)), b=0.1, a1=-0.1, a2=0.05, n_cycles=20)
    assert not validate.called
