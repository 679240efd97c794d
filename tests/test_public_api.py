"""The public API, as a user and a type checker meet it: ``dir(escapement)`` is ``__version__``, the
exported names and the module's dunder attributes; every exported function and class, and every
public method and property of the exported classes, has a docstring and type hints (a return
annotation, an annotation on every parameter), and so has every public name of the modules of the
model, the solvers and the integrators; the package ships ``py.typed``; the results' reprs are short
and print their inputs as typed back."""

from __future__ import annotations

import enum
import importlib
import inspect
import pkgutil
import math
import re
import subprocess
import sys
from collections.abc import Callable, Iterator
from importlib.resources import files

import numpy as np
import pytest

import escapement

EXPORTED = {name: getattr(escapement, name) for name in escapement.__all__ if name != "__version__"}


def own_members(cls: type) -> Iterator[tuple[str, object]]:
    """The public methods and properties ``cls`` and its project bases define (not those of Python's
    ``object``, ``Exception``, ``Enum`` or ``str``)."""
    seen = set()
    for base in cls.__mro__:
        if not base.__module__.startswith("escapement"):
            continue
        for name, member in vars(base).items():
            if name.startswith("_") and name != "__init__" or name in seen:
                continue
            seen.add(name)
            if isinstance(member, (staticmethod, classmethod)):
                member = member.__func__
            function = member.fget if isinstance(member, property) else member
            if inspect.isfunction(function) and function.__module__.startswith("escapement"):
                yield f"{cls.__name__}.{name}", member


def public_api() -> dict[str, object]:
    """Every exported name and every public method and property of the exported classes."""
    api: dict[str, object] = {}
    for name, obj in EXPORTED.items():
        api[name] = obj
        if inspect.isclass(obj):
            api.update(own_members(obj))
    return api


API = public_api()
#: the layers whose every module's public names are held to the same standard
LAYERS = ("model", "solvers", "integrators")


def layer_api() -> dict[str, object]:
    """The functions and classes each module of the layers defines and lists in its ``__all__``, with the
    public methods and properties of the classes."""
    api: dict[str, object] = {}
    for layer in LAYERS:
        package = importlib.import_module(f"escapement.{layer}")
        for info in pkgutil.iter_modules(package.__path__, f"{package.__name__}."):
            module = importlib.import_module(info.name)
            for name in module.__all__:
                obj = getattr(module, name)
                if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__ == info.name:
                    api[f"{info.name}.{name}"] = obj
                    if inspect.isclass(obj):
                        api.update((f"{info.name}.{key}", member) for key, member in own_members(obj))
    return api


LAYER_API = layer_api()


def hint_problems(name: str, obj: object) -> list[str]:
    """What ``obj``'s docstring and type hints lack, each as one line naming it."""
    problems = []
    if inspect.isclass(obj):
        return [] if (obj.__doc__ or "").strip() else [f"{name}: no docstring"]
    function: Callable = obj.fget if isinstance(obj, property) else obj
    if not (function.__doc__ or "").strip() and not name.endswith(".__init__"):
        problems.append(f"{name}: no docstring")
    signature = inspect.signature(function)
    if signature.return_annotation is inspect.Signature.empty:
        problems.append(f"{name}: no return annotation")
    for parameter in list(signature.parameters.values())[1 if "." in name else 0:]:
        if parameter.annotation is inspect.Parameter.empty:
            problems.append(f"{name}: parameter {parameter.name} has no annotation")
    return problems


def test_the_walk_finds_the_api_and_its_methods():
    """Not an empty walk: the functions, the classes, their methods and properties are all in it."""
    assert {"solve_exact", "Parameters", "Solution", "EventLog", "EnsembleSolution"} <= set(API)
    assert {"Solution.to_dataframe", "Parameters.omega", "Parameters.from_mapping", "EventLog.of_kind"} <= set(API)
    assert not any(name.startswith("Status.") and name.endswith("__str__") for name in API)


def test_the_check_finds_what_is_missing():
    def bare(x, y: int):
        pass

    class Bare:
        @property
        def p(self):
            return 1

    assert hint_problems("bare", bare) == ["bare: no docstring", "bare: no return annotation",
                                           "bare: parameter x has no annotation"]
    assert hint_problems("Bare", Bare) == ["Bare: no docstring"]
    assert hint_problems("Bare.p", Bare.__dict__["p"]) == ["Bare.p: no docstring", "Bare.p: no return annotation"]


@pytest.mark.parametrize("name", sorted(API))
def test_every_public_name_has_a_docstring_and_type_hints(name):
    assert hint_problems(name, API[name]) == []


def test_the_layers_walk_reaches_every_module():
    modules = {name.rsplit(".", 1)[0] for name in LAYER_API}
    assert {"escapement.model.kinematics", "escapement.solvers.ensemble", "escapement.integrators.segments"} <= modules
    assert "escapement.integrators.segments.DenseSegments.sample" in LAYER_API


@pytest.mark.parametrize("name", sorted(LAYER_API))
def test_every_public_name_of_the_layers_has_a_docstring_and_type_hints(name):
    assert hint_problems(name, LAYER_API[name]) == []


def test_dir_is_the_api():
    dunders = {name for name in dir(escapement) if name.startswith("__") and name.endswith("__")}
    assert set(dir(escapement)) - dunders == set(EXPORTED)
    assert "__version__" in dunders and set(escapement.__all__) == set(EXPORTED) | {"__version__"}
    assert dir(escapement) == sorted(dir(escapement))


@pytest.mark.parametrize("layer", ["io", "solvers", "integrators", "plotting"])
def test_dir_of_a_layer_is_its_all_whether_imported_at_once_or_on_first_use(layer):
    """``escapement.io`` imports its CSV helpers at once and its netCDF functions on first use: both kinds
    are listed, and a name imported on first use is one of ``__all__``."""
    package = importlib.import_module(f"escapement.{layer}")
    dunders = {name for name in dir(package) if name.startswith("__") and name.endswith("__")}
    assert set(dir(package)) - dunders == set(package.__all__)


def test_a_job_that_writes_only_csv_does_without_xarray(tmp_path):
    code = ("import sys; from escapement.io import write_csv; "
            f"write_csv([{{'a': 1}}], ['a'], {str(tmp_path / 'a.csv')!r}); assert 'xarray' not in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_the_enumerations_are_enumerations():
    """The walk skips what an enumeration inherits, not the enumeration itself."""
    assert issubclass(escapement.Status, enum.Enum) and "Status" in API


def test_the_package_ships_py_typed():
    assert files("escapement").joinpath("py.typed").is_file()


# --- reprs: short, inputs as typed back, no negative zero, never a whole array ---------------------

#: a negative zero as a number prints it: -0, -0.0, -0. (not -0.05 or -0.1)
NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0(?:\.0*)?(?![\w.])")


def short_and_signless(text: str) -> None:
    """A repr of a few lines, without an array's repr or a negative zero."""
    assert "array(" not in text and "..." not in text, text
    assert len(text.splitlines()) <= 12 and len(text) <= 1500, text
    assert not NEGATIVE_ZERO.search(text), text


def test_the_negative_zero_pattern():
    signed = ("t = -0 s", "a4=-0.0)", "x0 = -0. m", "[-0,")
    unsigned = ("-0.05", "-0.1 m", "a4=0.0", "1e-05", "x-0")
    assert all(NEGATIVE_ZERO.search(t) for t in signed) and not any(NEGATIVE_ZERO.search(t) for t in unsigned)


def test_parameters_print_as_typed_back_without_a_negative_zero():
    p = escapement.Parameters(M=1.0, K=1.0, F=-0.0, b=1.999999, a1=-0.1, a2=0.0, a3=0.1 + 0.2)
    assert p.a4 == 0.0 and math.copysign(1.0, p.a4) == -1.0  # stored as -a2: the case the repr must hide
    assert repr(p) == "Parameters(M=1.0, K=1.0, F=0.0, b=1.999999, a1=-0.1, a2=0.0, a3=0.30000000000000004, a4=0.0)"
    assert eval(repr(p), {"Parameters": escapement.Parameters}) == p


def test_an_exit_prints_as_typed_back_without_a_negative_zero():
    text = repr(escapement.Exit(-0.0, 0.1 + 0.2))
    assert text == "Exit(turning_point=0.0, margin=0.30000000000000004, t_accumulation=nan)"


def test_an_event_log_prints_counts_and_its_time_span_not_its_arrays():
    n = 5000
    kinds = np.resize([1, 2, 3, 4], n)
    t = np.linspace(-0.0, 2.5, n)
    log = escapement.EventLog(t=t, kind=kinds, x=np.zeros(n), v_before=np.ones(n), v_after=np.ones(n))
    text = repr(log)
    short_and_signless(text)
    assert text == "<EventLog> 5000 events from t = 0 s to 2.5 s: IMPACT_A1 1250, ZONE_END_A2 1250, IMPACT_A3 1250, " \
                   "ZONE_END_A4 1250"
    one = escapement.EventLog(t=np.array([1.0000001]), kind=np.array([3]), x=np.array([0.1]), v_before=np.array([-1.0]),
                              v_after=np.array([0.9]))
    assert repr(one) == "<EventLog> 1 event at t = 1 s: IMPACT_A3 1"
    close = escapement.EventLog(t=np.array([1.0, 1.0000001]), kind=np.array([1, 1]), x=np.zeros(2),
                                v_before=np.ones(2), v_after=np.ones(2))
    assert repr(close) == "<EventLog> 2 events from t = 1 s to 1.0000001 s: IMPACT_A1 2"  # told apart


P = dict(M=1.0, K=1.0, F=1.0, b=0.1, a1=-0.1, a2=0.0)


def long_run() -> escapement.Solution:
    return escapement.solve_exact(escapement.Parameters(**P), x0=-1.0, n_cycles=600)


@pytest.mark.parametrize("make", [
    lambda: long_run(),
    lambda: long_run().events,
    lambda: long_run().cycles,
    lambda: long_run().trajectory,
    lambda: long_run().exit,
    lambda: escapement.solve_exact(escapement.Parameters(**P), x0=-0.0, n_cycles=3),  # stops at once, at -0
    lambda: escapement.solve_exact(escapement.Parameters(**P), x0=-0.0, n_cycles=3).exit,
    lambda: escapement.solve_exact(escapement.Parameters(**P), x0=-0.0, n_cycles=3).trajectory,
    lambda: escapement.solve_ensemble(1.0, 1.0, np.linspace(-0.0, 2.0, 1500), 0.1, -0.1, 0.0, x0=-1.0, n_cycles=5),
    lambda: escapement.solve_ensemble(1.0, 1.0, np.linspace(-0.0, 2.0, 1500), 0.1, -0.1, 0.0, x0=-1.0,
                                      n_cycles=5).cycles,
    lambda: escapement.solve_reference(escapement.Parameters(**P), x0=-1.0, n_cycles=2).trajectory,
    lambda: escapement.Parameters(**P),
], ids=["Solution", "EventLog", "CycleTable", "ArcTable", "Exit", "Solution stopped at -0", "Exit at -0",
        "ArcTable at -0", "EnsembleSolution", "ensemble CycleTable", "DenseSegments", "Parameters"])
def test_every_result_prints_short_and_without_a_negative_zero(make):
    short_and_signless(repr(make()))


def stream(x0: float, closed_form: bool, exhausted: bool) -> object:
    """A run's cycle stream (of the event solver or of the closed forms), before or after its end."""
    from escapement.solvers import iter_closed_form_cycles

    make = iter_closed_form_cycles if closed_form else escapement.iter_cycles
    chunks = make(escapement.Parameters(**P), x0, n_cycles=3000, chunk=1000)
    if exhausted:
        for _ in chunks:
            pass
    return chunks


@pytest.mark.parametrize("x0", [-1.0, -0.0])
@pytest.mark.parametrize("closed_form", [False, True], ids=["events", "closed forms"])
@pytest.mark.parametrize("exhausted", [False, True], ids=["fresh", "exhausted"])
def test_a_cycle_stream_prints_its_progress_in_one_line(x0, closed_form, exhausted):
    text = repr(stream(x0, closed_form, exhausted))
    short_and_signless(text)
    assert len(text.splitlines()) == 1 and "chunks of 1000 cycles" in text
    assert ("; ended " in text) == exhausted
    handed = 3000 if exhausted and x0 else 0  # a release at 0 stops at once, before any cycle
    assert re.search(rf"(?<![\d.]){handed} (of 3000 )?handed over", text), text
