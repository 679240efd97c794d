"""The package's layers import one way only.

Every ``import`` and ``from ... import`` in the source of ``src/escapement`` (at module level or
inside a function, relative or absolute) is an edge from the layer of the importing module to the
layer it names. The graph of the layers has no cycle, and every edge goes down the declared order;
:mod:`escapement.io` reads and writes files, so it reaches only the package's root (its version).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[1] / "src" / "escapement"

#: the layers, bottom to top: each may import only those before it. ``_lazy`` holds the package
#: root (``escapement/__init__.py`` and the helper of its lazy exports); ``cli`` the command line.
LAYERS = (
    "_lazy", "model", "solvers", "integrators", "paper", "studies", "scenes", "io", "plotting", "verdict", "pipeline",
    "cli",
)
#: the top-level modules and the layer each belongs to
TOP_LEVEL = {"__init__": "_lazy", "_lazy": "_lazy", "cli": "cli", "__main__": "cli"}
#: layers held to fewer imports than the order allows: io reads and writes files, whatever made them; the paper as
#: printed is written in the model's terms; the verdict reads datasets (its tables through io, which checks them
#: whole), so it reaches neither a solver nor an integrator, not even through another layer
ONLY = {"io": {"_lazy"}, "paper": {"_lazy", "model"}, "verdict": {"_lazy", "model", "paper", "io"}}


def layer_of(module: tuple[str, ...]) -> str | None:
    """The layer of the dotted module ``escapement.<...>`` (as a tuple of its parts), or None
    outside the package."""
    if not module or module[0] != "escapement":
        return None
    if len(module) == 1:
        return TOP_LEVEL["__init__"]
    head = module[1]
    if (SOURCE / head).is_dir():
        return head
    return TOP_LEVEL.get(head, TOP_LEVEL["__init__"])  # a name of the package root itself


def imported_modules(path: Path, root: Path = SOURCE) -> list[tuple[tuple[str, ...], int]]:
    """Every module the file at ``path`` imports, with the line: absolute names as written,
    relative ones resolved against the file's package; ``from X import a`` counts as ``X.a``
    as well as ``X`` (``a`` may be a submodule)."""
    relative = path.relative_to(root).with_suffix("").parts
    package = ("escapement", *relative[:-1])  # a package's __init__ is in its own package too
    found = []
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            found += [(tuple(alias.name.split(".")), node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
            else:
                base = ()
            module = (*base, *(node.module.split(".") if node.module else ()))
            found.append((module, node.lineno))
            found += [((*module, alias.name), node.lineno) for alias in node.names if alias.name != "*"]
    return found


def layer_edges(root: Path = SOURCE) -> dict[tuple[str, str], list[str]]:
    """Each edge ``(importer's layer, imported layer)`` between two layers, with where it is made."""
    edges: dict[tuple[str, str], list[str]] = {}
    for path in sorted(root.rglob("*.py")):
        relative = path.relative_to(root)
        source = relative.parts[0] if len(relative.parts) > 1 else TOP_LEVEL[relative.stem]
        for module, line in imported_modules(path, root):
            target = layer_of(module)
            if target is not None and target != source:
                edges.setdefault((source, target), []).append(f"{relative}:{line}")
    return edges


def cycles(edges) -> list[list[str]]:
    """The cycles of the graph ``edges`` (one per strongly connected set of layers, by depth-first search)."""
    graph: dict[str, set[str]] = {}
    for source, target in edges:
        graph.setdefault(source, set()).add(target)
        graph.setdefault(target, set())
    found = []
    state: dict[str, str] = {}

    def visit(node: str, trail: list[str]) -> None:
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                found.append([*trail[trail.index(nxt):], nxt])
            elif nxt not in state:
                visit(nxt, [*trail, nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    return found


def violations(edges) -> list[str]:
    """The edges that go up the declared order or outside a layer's allowed set, each with where it is made."""
    rank = {layer: i for i, layer in enumerate(LAYERS)}
    wrong = []
    for (source, target), where in sorted(edges.items()):
        if rank[target] >= rank[source] or target not in ONLY.get(source, {target}):
            wrong.append(f"{source} -> {target}: {', '.join(dict.fromkeys(where))}")
    return wrong


@pytest.fixture(scope="module")
def edges():
    return layer_edges()


def test_every_subpackage_has_its_place_in_the_order():
    subpackages = {p.parent.name for p in SOURCE.glob("*/__init__.py")}
    assert subpackages == set(LAYERS) - {"_lazy", "cli"}
    assert {p.stem for p in SOURCE.glob("*.py")} == set(TOP_LEVEL)


def test_the_layers_have_no_cycle(edges):
    assert cycles(edges) == []


def test_every_import_goes_down_the_declared_order(edges):
    assert violations(edges) == []


def _registers_a_check(tree: ast.AST) -> bool:
    """Whether the module defines a function decorated by ``check(...)``."""
    return any(isinstance(node, ast.FunctionDef) and any(
        isinstance(d, ast.Call) and isinstance(d.func, ast.Name) and d.func.id == "check" for d in node.decorator_list)
        for node in ast.walk(tree))


def test_every_check_sits_in_the_verdict_and_none_simulates(edges):
    """Every module that registers a check is in :mod:`escapement.verdict`, and the verdict imports neither a solver
    nor an integrator, directly or through the layers it may import (:data:`ONLY`)."""
    registering = {str(path.relative_to(SOURCE)) for path in SOURCE.rglob("*.py")
                   if _registers_a_check(ast.parse(path.read_text()))}
    assert len(registering) >= 10 and all(path.startswith("verdict/") for path in registering), registering
    reach, grown = {"verdict"}, True
    while grown:
        more = {target for source, target in edges if source in reach} - reach
        reach |= more
        grown = bool(more)
    assert reach.isdisjoint({"solvers", "integrators", "studies", "scenes"}), reach
