"""The source files a workflow script runs: a rule's code inputs, read from the import statements.

Snakemake tracks a rule's script, not the modules it imports. :func:`code_inputs` follows the script's
imports through the modules found under ``roots`` (the package's ``src``; the repository, for ``benchmarks``),
read with :mod:`ast`, nothing imported. Every ``import`` and ``from ... import`` counts, at a module's top level
or inside a function, relative ones resolved; a module brings the ``__init__.py`` of every package above it.
``from pkg import name`` counts the submodule ``pkg.name`` if there is one, else, if ``pkg`` re-exports ``name``
on first use (its ``_EXPORTS`` table, :mod:`escapement._lazy`), the module the table maps it to, and so on
down; ``pkg.name`` as an attribute counts alike, and a table's unused names add nothing. A data file a module
names beside itself (the figures' style sheet) counts with it. An edit of one of these files reruns the
rule's jobs; an edit of any other does not.
"""

from __future__ import annotations

import ast
import os
import re
from functools import cache
from pathlib import Path

__all__ = ["code_inputs", "module_files"]

#: a string that may name a data file beside the module: ``escapement.mplstyle``
_FILE_NAME = re.compile(r"[\w-]+\.[A-Za-z]+")


def _find(roots: tuple[Path, ...], name: str) -> Path | None:
    """The file of module ``name`` (a package's ``__init__.py``) under the first root that has it."""
    for root in roots:
        base = root.joinpath(*name.split("."))
        for path in (base / "__init__.py", base.with_suffix(".py")):
            if path.is_file():
                return path
    return None


def _tree(path: Path) -> ast.Module:
    return _parse(path, path.stat().st_mtime_ns)[0]


def _nodes(path: Path) -> tuple[ast.AST, ...]:
    """Every node of the module's tree, walked once for the three readings of it."""
    return _parse(path, path.stat().st_mtime_ns)[1]


@cache
def _parse(path: Path, mtime: int) -> tuple[ast.Module, tuple[ast.AST, ...]]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    return tree, tuple(ast.walk(tree))


def _exports(roots: tuple[Path, ...], package: str) -> dict[str, str]:
    """A package's lazy re-exports: each name and the module (absolute) that defines it."""
    path = _find(roots, package)
    if path is None or path.name != "__init__.py":
        return {}
    for node in _tree(path).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "_EXPORTS" for t in node.targets):
            pairs = zip(node.value.keys, node.value.values) if isinstance(node.value, ast.Dict) else ()
            return {key.value: f"{package}.{value.value}" for key, value in pairs
                    if isinstance(key, ast.Constant) and isinstance(value, ast.Constant)}
    return {}


def _member(roots: tuple[Path, ...], module: str, name: str) -> list[str]:
    """The modules that ``module.name`` loads: the submodule, or the chain of lazy re-exports to it."""
    if _find(roots, f"{module}.{name}"):
        return [f"{module}.{name}"]
    target = _exports(roots, module).get(name)
    return [target, *_member(roots, target, name)] if target else []


def _dotted(node: ast.expr) -> list[str]:
    """``a.b.c`` as ``["a", "b", "c"]``; empty for any other expression."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    return [node.id, *reversed(parts)] if isinstance(node, ast.Name) else []


def _imports(roots: tuple[Path, ...], module: str, path: Path) -> frozenset[str]:
    """The modules that the statements of one module (or script: ``module`` empty) import."""
    return _imports_of(roots, module, path, path.stat().st_mtime_ns)


@cache
def _imports_of(roots: tuple[Path, ...], module: str, path: Path, mtime: int) -> frozenset[str]:
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()
    bound: dict[str, str] = {}  # local name -> module it is bound to
    nodes = _nodes(path)
    for node in nodes:
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.add(alias.name)
                head = alias.name if alias.asname else alias.name.split(".")[0]
                bound[alias.asname or head] = head
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*parent, *([base] if base else [])])
            found.add(base)
            for alias in node.names:
                if alias.name != "*":
                    loaded = _member(roots, base, alias.name)
                    found.update(loaded)
                    if loaded and _find(roots, loaded[-1]) and loaded[-1].endswith(f".{alias.name}"):
                        bound[alias.asname or alias.name] = loaded[-1]
    for node in nodes:  # names used as attributes of a bound module: pkg.name
        parts = _dotted(node) if isinstance(node, ast.Attribute) else []
        if parts and parts[0] in bound:
            current = bound[parts[0]]
            for name in parts[1:]:
                loaded = _member(roots, current, name)
                found.update(loaded)
                if not (loaded and loaded[-1] == f"{current}.{name}"):
                    break
                current = loaded[-1]
    return frozenset(name for name in found if name and _find(roots, name))


def module_files(roots, script) -> set[Path]:
    """Every file under ``roots`` that running ``script`` may load: modules and their data files."""
    roots = tuple(Path(r).resolve() for r in roots)
    pending, seen = list(_imports(roots, "", Path(script).resolve())), set()
    while pending:
        name = pending.pop()
        if name in seen:
            continue
        seen.add(name)
        parts = name.split(".")
        pending += [".".join(parts[:i]) for i in range(1, len(parts))]  # the packages above it
        pending += _imports(roots, name, _find(roots, name))
    modules = {_find(roots, name) for name in seen}
    return modules.union(*(_data_files(path, path.stat().st_mtime_ns) for path in modules))


@cache
def _data_files(path: Path, mtime: int) -> frozenset[Path]:
    """The files beside the module ``path`` that it names in a string: a style sheet it loads."""
    names = {node.value for node in _nodes(path)
             if isinstance(node, ast.Constant) and isinstance(node.value, str) and _FILE_NAME.fullmatch(node.value)}
    return frozenset(path.parent / name for name in names
                     if (path.parent / name).suffix != ".py" and (path.parent / name).is_file())


def code_inputs(script, base=".", roots=("src", ".")) -> list[str]:
    """The files a rule's ``script`` runs, beyond the script itself: the modules it imports, transitively,
    found under ``roots`` (the package's ``src``; the repository, for ``benchmarks``), both relative to the
    repository ``base``; as sorted paths relative to the working directory, as Snakemake records its inputs."""
    base = Path(base)
    return sorted(os.path.relpath(path) for path in module_files([base / r for r in roots], base / script))
