"""The environment's locks: hashed exact pins in layers that agree with pyproject.toml, the conda
file and the Quick start, and an installed environment that satisfies the package's requirements.
"""

from __future__ import annotations

import ast
import hashlib
import importlib.metadata
import importlib.util
import re
import sys
import tomllib
from pathlib import Path

import pytest
import yaml
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[1]
ENVIRONMENT = ROOT / "environment"
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
LAYERS = ["build", "runtime", "test", "tools"]  # each installed on top of the ones before it
QUICK_START_LAYERS = ["build", "runtime", "test"]
HASH = re.compile(r"--hash=sha256:[0-9a-f]{64}")
# The checkers of the code's form, which the Quick start's environment leaves out.
CI_ONLY = ["snakefmt", "black", "ruff"]
# What a test runs beyond its imports, which the Quick start's environment must hold: the CF-1.11 check of
# every netCDF output (tests/test_workflow.py) and the heavy packages it brings.
TEST_RUNS = ["compliance-checker", "pyproj", "shapely", "lxml"]


def parse_lock(text: str) -> dict[str, tuple[Version, list[str]]]:
    """{canonical name: (version, sha256 hashes)}; fails on any line that is not an exact pin."""
    logical = re.sub(r"\\\n", " ", text)
    entries: dict[str, tuple[Version, list[str]]] = {}
    for line in logical.splitlines():
        line = line.split(" #")[0].strip()
        if not line or line.startswith("#"):
            continue
        spec, _, options = line.partition(" --")
        options = "--" + options if options else ""
        requirement = Requirement(spec)
        (pin,) = requirement.specifier  # exactly one specifier ...
        assert pin.operator == "==" and "*" not in pin.version, line  # ... and an exact one
        leftover = HASH.sub("", options).strip()
        assert not leftover, f"{requirement.name}: unexpected options {leftover!r}"
        name = canonicalize_name(requirement.name)
        assert name not in entries, f"{name} is pinned twice"
        entries[name] = (Version(pin.version), HASH.findall(options))
    return entries


LOCKS = {layer: parse_lock((ENVIRONMENT / f"{layer}.lock").read_text()) for layer in LAYERS}


def pinned_up_to(layer: str) -> dict[str, Version]:
    """The versions installed once `layer` and every layer below it are."""
    versions: dict[str, Version] = {}
    for below in LAYERS[: LAYERS.index(layer) + 1]:
        versions.update({name: version for name, (version, _) in LOCKS[below].items()})
    return versions


def unsatisfied(requirements: list[str], versions: dict[str, Version]) -> list[str]:
    missing = []
    for text in requirements:
        requirement = Requirement(text)
        version = versions.get(canonicalize_name(requirement.name))
        if version is None or not requirement.specifier.contains(version, prereleases=True):
            missing.append(f"{text} (locked: {version})")
    return missing


@pytest.mark.parametrize("layer", LAYERS)
def test_every_pin_of_every_lock_is_exact_and_hashed(layer):
    assert LOCKS[layer], f"{layer}.lock pins nothing"
    for name, (_, hashes) in LOCKS[layer].items():
        assert hashes, f"{layer}.lock: {name} has no hash (pip --require-hashes refuses it)"


def test_the_lock_parser_refuses_what_pip_would():
    with pytest.raises(AssertionError, match="pinned twice"):
        parse_lock("a==1 --hash=sha256:" + "0" * 64 + "\nA==1 --hash=sha256:" + "0" * 64 + "\n")
    with pytest.raises(AssertionError):
        parse_lock("numpy>=2 --hash=sha256:" + "0" * 64 + "\n")
    with pytest.raises(AssertionError, match="unexpected options"):
        parse_lock("numpy==2 --hash=md5:0\n")
    assert parse_lock("numpy==2.4.6 \\\n    --hash=sha256:" + "a" * 64 + "\n    # via x\n")["numpy"][1]
    assert not parse_lock("numpy==2.4.6\n")["numpy"][1]


def test_no_package_is_pinned_in_two_layers():
    seen: dict[str, str] = {}
    for layer in LAYERS:
        for name in LOCKS[layer]:
            assert name not in seen, f"{name} is in both {seen[name]}.lock and {layer}.lock"
            seen[name] = layer


def test_the_build_lock_holds_exactly_the_pinned_build_backend():
    requires = PYPROJECT["build-system"]["requires"]
    for text in requires:
        (pin,) = Requirement(text).specifier
        assert pin.operator == "==", f"the build backend must be pinned exactly: {text}"
    assert not unsatisfied(requires, pinned_up_to("build"))
    assert set(LOCKS["build"]) == {canonicalize_name(Requirement(text).name) for text in requires}


def test_each_layer_satisfies_its_part_of_pyproject():
    project = PYPROJECT["project"]
    extras = project["optional-dependencies"]
    assert not unsatisfied(project["dependencies"] + extras["slurm"], pinned_up_to("runtime"))
    assert not unsatisfied(extras["test"], pinned_up_to("test"))
    assert not unsatisfied(extras["tools"], pinned_up_to("tools"))
    assert set(extras) == {"slurm", "test", "tools"}, "a new extra needs a layer in environment/lock.py"


def test_the_checkers_stay_out_of_the_quick_start_environment_and_what_the_tests_run_is_in_it():
    installed = pinned_up_to("test")
    assert [name for name in CI_ONLY if name in installed] == []
    assert all(name in LOCKS["tools"] for name in CI_ONLY)
    assert [name for name in TEST_RUNS if name not in LOCKS["test"]] == []
    assert {"pytest", "hypothesis"} <= set(LOCKS["test"]) and "pytest" not in LOCKS["runtime"]


def test_the_slurm_profile_has_its_executor_plugin_in_the_runtime_lock():
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    assert f"snakemake-executor-plugin-{profile['executor']}" in LOCKS["runtime"]


def test_the_conda_file_installs_the_build_and_runtime_locks_and_names_their_digests():
    """Through pip's -r, from the locks beside it (conda runs pip in the environment file's folder), each with its
    sha256: Snakemake hashes the file's text, so a changed lock must change it."""
    environment = yaml.safe_load((ENVIRONMENT / "environment.yml").read_text())
    conda = [entry for entry in environment["dependencies"] if isinstance(entry, str)]
    assert "python=3.11" in conda and "pip" in conda
    (pip,) = [entry["pip"] for entry in environment["dependencies"] if isinstance(entry, dict)]
    assert pip == ["-r build.lock", "-r runtime.lock"]
    for layer in ("build", "runtime"):
        digest = hashlib.sha256((ENVIRONMENT / f"{layer}.lock").read_bytes()).hexdigest()
        assert f"-r {layer}.lock # sha256 {digest}\n" in (ENVIRONMENT / "environment.yml").read_text()


def test_the_conda_file_is_the_one_the_lock_script_writes():
    spec = importlib.util.spec_from_file_location("environment_lock", ENVIRONMENT / "lock.py")
    lock = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(lock)
    assert (ENVIRONMENT / "environment.yml").read_text() == lock.conda_yaml()
    assert [name for name, _, _ in lock.LAYERS] == LAYERS


def test_the_quick_start_installs_the_lower_layers_hash_checked_and_ci_the_tools():
    commands = re.search(r"## Quick start\n.*?```bash\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    install = commands.group(1).splitlines()[0]
    assert re.findall(r"-r environment/(\w+)\.lock", install) == QUICK_START_LAYERS
    assert "pip install --require-hashes -r" in install
    assert "pip install --no-deps --no-build-isolation -e ." in install
    ci = (ROOT / ".ci" / "run").read_text()
    assert ".venv/bin/pip install --quiet --require-hashes -r environment/tools.lock" in ci
    assert ci.index("environment/tools.lock") < ci.index("snakefmt --check") < ci.index("compliance-checker --test")
    assert sorted(path.stem for path in ENVIRONMENT.glob("*.lock")) == sorted(LAYERS)


def imported_by_the_tests() -> set[str]:
    """The top-level modules that tests/ imports, less the standard library and the project's own."""
    tests = ROOT / "tests"
    # the project's own: the package, the benchmarks, and the tests' modules and folders (tests/ is on the path)
    own = {"escapement", "benchmarks"} | {path.stem for path in tests.rglob("*.py")} | {
        path.name for path in tests.rglob("*") if path.is_dir()}
    found: set[str] = set()
    for path in tests.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                found |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
    return {name for name in found if name not in sys.stdlib_module_names and name not in own}


def test_every_module_the_tests_import_comes_from_the_runtime_or_test_lock():
    """The Quick start installs no linter (tools.lock): a test importing one would fail there."""
    providers = importlib.metadata.packages_distributions()
    installed = pinned_up_to("test")
    imported = imported_by_the_tests()
    assert {"pytest", "hypothesis", "numpy"} <= imported
    outside = {}
    for module in sorted(imported):
        names = {canonicalize_name(name) for name in providers.get(module, [])}
        if not names & set(installed):
            outside[module] = sorted(names) or "not installed"
    assert outside == {}


def test_the_running_environment_satisfies_the_installed_package():
    """`pip install --no-deps -e .` checks nothing: a dependency missing from the locks shows here."""
    try:
        requires = importlib.metadata.requires("escapement") or []
    except importlib.metadata.PackageNotFoundError:
        pytest.skip("escapement is not installed (imported from the source tree)")
    missing = []
    for text in requires:
        requirement = Requirement(text)
        if requirement.marker and not requirement.marker.evaluate({"extra": "test"}):
            continue  # the slurm and tools extras: not needed to run the tests
        try:
            version = importlib.metadata.version(requirement.name)
        except importlib.metadata.PackageNotFoundError:
            missing.append(f"{text} (not installed)")
            continue
        if not requirement.specifier.contains(version, prereleases=True):
            missing.append(f"{text} (installed: {version})")
    assert missing == []
