"""The rules' code inputs (escapement.pipeline.code_inputs): on a small package written here, each kind of import
statement; on the workflow's scripts, against the modules a fresh interpreter really loads."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from workflow_copies import REPO, loaded_files

from escapement.pipeline.code_inputs import code_inputs

SCRIPTS = sorted(path.name for path in (REPO / "workflow/scripts").glob("*.py"))

PACKAGE = {
    "pkg/__init__.py": "from ._lazy import table\n_EXPORTS = {'Late': 'late', 'solve': 'sub'}\n",
    "pkg/_lazy.py": "",
    "pkg/eager.py": "from . import helper\nfrom .deep.leaf import f\n",
    "pkg/helper.py": "def run():\n    from .inner import g\n",
    "pkg/inner.py": "",
    "pkg/deep/__init__.py": "",
    "pkg/deep/leaf.py": "from ... import unused_name\n",
    "pkg/late.py": "class Late: ...\n",
    "pkg/sub/__init__.py": "_EXPORTS = {'solve': 'exact'}\n",
    "pkg/sub/exact.py": "",
    "pkg/sub/other.py": "",
    "pkg/never.py": "",
    "pkg/style.py": "SHEET = 'look.mplstyle'\n",
    "pkg/look.mplstyle": "lines.linewidth: 1\n",
}


@pytest.fixture
def package(tmp_path):
    for name, text in PACKAGE.items():
        (tmp_path / "src" / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / "src" / name).write_text(text)
    return tmp_path


def _rel(where: Path, script: str, monkeypatch) -> set[str]:
    """The inputs of a script of the given text, relative to the package's ``src``."""
    (where / "script.py").write_text(script)
    monkeypatch.chdir(where / "src")
    return set(code_inputs("script.py", base=where, roots=("src",)))


def test_a_module_brings_its_packages_and_what_it_imports_anywhere(package, monkeypatch):
    assert _rel(package, "from pkg.eager import x\n", monkeypatch) == {
        "pkg/__init__.py", "pkg/_lazy.py", "pkg/eager.py", "pkg/helper.py", "pkg/inner.py",
        "pkg/deep/__init__.py", "pkg/deep/leaf.py"}


def test_a_lazy_name_brings_the_modules_its_tables_map_it_to_and_no_other(package, monkeypatch):
    assert _rel(package, "import pkg\n", monkeypatch) == {"pkg/__init__.py", "pkg/_lazy.py"}
    assert _rel(package, "from pkg import Late\n", monkeypatch) == {"pkg/__init__.py", "pkg/_lazy.py", "pkg/late.py"}
    # through two tables: pkg.solve -> pkg.sub -> pkg.sub.exact
    assert _rel(package, "import pkg\npkg.solve()\n", monkeypatch) == {
        "pkg/__init__.py", "pkg/_lazy.py", "pkg/sub/__init__.py", "pkg/sub/exact.py"}
    assert _rel(package, "from pkg import sub\nsub.other.x\n", monkeypatch) == {
        "pkg/__init__.py", "pkg/_lazy.py", "pkg/sub/__init__.py", "pkg/sub/other.py"}


def test_a_data_file_named_beside_a_module_counts(package, monkeypatch):
    assert "pkg/look.mplstyle" in _rel(package, "import pkg.style\n", monkeypatch)


def test_the_figures_style_sheet_is_an_input_of_the_plots():
    assert "src/escapement/plotting/escapement.mplstyle" in code_inputs("workflow/scripts/plot_fig3.py", base=REPO)


def _deferred(files: set[str]) -> tuple[str, ...]:
    """The modules of the package (and of the benchmarks) that one of ``files`` imports inside a function body,
    run only when the function is called."""
    names = set()
    for file in files:
        module = file.removeprefix("src/").removesuffix(".py").replace("/", ".").removesuffix(".__init__")
        package = module if file.endswith("__init__.py") else module.rpartition(".")[0]
        functions = [n for n in ast.walk(ast.parse((REPO / file).read_text()))
                     if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]
        for node in (inner for function in functions for inner in ast.walk(function)):
            if isinstance(node, ast.ImportFrom):
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1]) if node.level else ""
                names.add(".".join(part for part in (base, node.module) if part))
            elif isinstance(node, ast.Import):
                names.update(alias.name for alias in node.names)
    return tuple(sorted(n for n in names if n.partition(".")[0] in ("escapement", "benchmarks")))


@pytest.mark.parametrize("script", SCRIPTS)
def test_the_code_inputs_are_the_modules_the_script_loads(script):
    """Every file of the package (or of the benchmarks) that the script's imports load is an input; and every
    input is loaded once the imports that functions make when they run (the solvers' results import the
    dataset writers) are made too: no input is a module the script never runs."""
    computed = {p for p in code_inputs(f"workflow/scripts/{script}", base=REPO) if p.endswith(".py")}
    loaded, with_deferred = loaded_files(REPO, f"workflow/scripts/{script}", _deferred(computed))
    assert loaded, script
    assert loaded <= computed, f"loaded by {script} but not an input: {sorted(loaded - computed)}"
    assert computed <= with_deferred, f"inputs of {script} that it never loads: {sorted(computed - with_deferred)}"
