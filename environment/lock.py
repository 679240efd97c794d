"""Write the hashed locks of the environment, layer by layer, and the conda file from them.

    python3.11 environment/lock.py             # re-resolve, keeping every version already locked
    python3.11 environment/lock.py --upgrade   # take the newest versions pyproject.toml allows
    python3.11 environment/lock.py --conda     # only rewrite environment.yml from the locks (offline)

Each layer is pyproject.toml resolved by pip-compile (pip-tools, pinned below, in a throwaway venv)
with the layers below it as constraints, less the packages those layers already hold, so that the
files can be installed together and no package is pinned twice:

    build.lock    the build backend of pyproject's [build-system] (for `pip install --no-build-isolation -e .`)
    runtime.lock  [project] dependencies + the `slurm` extra: what `snakemake` needs, profiles/slurm included
    test.lock     the `test` extra: what tests/ imports or runs beyond the runtime (compliance-checker included)
    tools.lock    the `tools` extra: the checkers CI runs (snakefmt and its black, ruff)

Every pin carries the sha256 of each file PyPI holds for that version (all platforms), so
`pip install --require-hashes` accepts any of them and nothing else. The resolution is for
CPython 3.11 on Linux; it runs against PyPI alone (pip's own configuration is set aside, so a
local mirror or wheel folder cannot leak its files or hashes into the locks).
"""

from __future__ import annotations

import argparse
import hashlib
import os
import re
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
INDEX = "https://pypi.org/simple"
# The locking tool itself, pinned: another pip-tools may annotate or order the files differently.
LOCKER = ["pip==26.0.1", "pip-tools==7.6.2"]

# name, pip-compile options selecting what the layer resolves (cumulative), purpose
LAYERS = [
    ("build", ["--only-build-deps", "--build-deps-for", "editable"], "the build backend of pyproject.toml"),
    ("runtime", ["--extra", "slurm"], "the package's dependencies and Snakemake's SLURM executor plugin"),
    ("test", ["--extra", "slurm", "--extra", "test"], "the test suite's packages beyond the runtime layer"),
    ("tools", ["--extra", "slurm", "--extra", "test", "--extra", "tools"], "the checkers CI runs"),
]
CONDA_LAYERS = ["build", "runtime"]

REQUIREMENT = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==(\S+)")


def canonical(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def blocks(text: str) -> list[tuple[str, str, str]]:
    """The requirements of a pip-compile output: (canonical name, version, the block's text)."""
    found: list[tuple[str, str, str]] = []
    for line in text.splitlines(keepends=True):
        match = REQUIREMENT.match(line)
        if match:
            found.append((canonical(match.group(1)), match.group(2), line))
        elif found and line.startswith((" ", "\t")):
            name, version, block = found[-1]
            found[-1] = (name, version, block + line)
    return found


def pins(path: Path) -> dict[str, str]:
    """{canonical name: version} of a lock file."""
    return {name: version for name, version, _ in blocks(path.read_text())} if path.exists() else {}


def locker_env() -> dict[str, str]:
    """The environment for pip and pip-compile: PyPI only, whatever pip.conf or PIP_* say."""
    env = {key: value for key, value in os.environ.items() if not key.startswith("PIP_") or key == "PIP_CERT"}
    env["PIP_CONFIG_FILE"] = os.devnull
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


def make_locker(where: Path) -> Path:
    venv.EnvBuilder(with_pip=True).create(where)
    python = where / "bin" / "python"
    subprocess.run(
        [python, "-m", "pip", "install", "--quiet", "--index-url", INDEX, *LOCKER], check=True, env=locker_env()
    )
    return where / "bin" / "pip-compile"


def compile_layer(compiler: Path, index: int, upgrade: bool, scratch: Path) -> None:
    name, options, purpose = LAYERS[index]
    lower = [HERE / f"{below}.lock" for below, _, _ in LAYERS[:index]]
    target = HERE / f"{name}.lock"
    # pip-compile keeps the versions it finds in its output file: start it from every layer's pins (the
    # lower ones bind anyway, as constraints; a package moved from one layer to another keeps its version).
    output = scratch / f"{name}.txt"
    output.write_text("".join(p.read_text() for p in (HERE / f"{layer}.lock" for layer, _, _ in LAYERS) if p.exists()))
    command = [
        compiler,
        "--quiet",
        "--no-config",
        "--generate-hashes",
        "--allow-unsafe",
        "--strip-extras",
        "--no-header",
        "--no-emit-index-url",
        "--no-emit-find-links",
        "--annotation-style=line",
        "--index-url",
        INDEX,
        *(["--upgrade"] if upgrade else []),
        *options,
        *[arg for path in lower for arg in ("--constraint", str(path))],
        "--output-file",
        str(output),
        "pyproject.toml",
    ]
    subprocess.run(command, check=True, cwd=ROOT, env=locker_env())
    below = set().union(*(pins(path) for path in lower))
    kept = [block for package, _, block in blocks(output.read_text()) if package not in below]
    header = (
        f"# {name}.lock: {purpose}.\n"
        "# CPython 3.11 on Linux. Exact versions, with the sha256 of every file PyPI has for each.\n"
        "# Generated by `python3.11 environment/lock.py` from pyproject.toml: do not edit by hand.\n"
    )
    target.write_text(header + "".join(kept))
    print(f"{target.relative_to(ROOT)}: {len(kept)} packages")


def conda_yaml() -> str:
    """environment.yml: conda-forge's Python 3.11 and pip, then the build and runtime locks for pip, each with
    its sha256, so that Snakemake (which hashes this file's text) builds a new environment when a lock changes."""
    lines = [
        "# Conda environment of the workflow's rules (snakemake --software-deployment-method conda).",
        "# Generated by `python3.11 environment/lock.py --conda` from build.lock and runtime.lock: do not",
        "# edit by hand. conda-forge gives Python and pip only; pip installs every other package from the",
        "# locks beside this file (conda runs pip from this folder), pinned and hash-checked exactly as in",
        "# the Quick start (the same files as a pip install, which conda-forge's own builds are not). Each",
        "# lock's sha256 follows it, so that a changed lock gives a new environment. environment.post-deploy.sh",
        "# then installs the package itself, editable, from the working directory (the clone's root).",
        "name: escapement",
        "channels:",
        "  - conda-forge",
        "  - nodefaults",
        "dependencies:",
        "  - python=3.11",
        "  - pip",
        "  - pip:",
    ]
    for layer in CONDA_LAYERS:
        digest = hashlib.sha256((HERE / f"{layer}.lock").read_bytes()).hexdigest()
        lines.append(f"      - -r {layer}.lock # sha256 {digest}")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--upgrade", action="store_true", help="take the newest versions pyproject.toml allows")
    parser.add_argument("--conda", action="store_true", help="only rewrite environment.yml from the locks")
    args = parser.parse_args()
    if sys.version_info[:2] != (3, 11):
        sys.exit("run this with Python 3.11: the locks are resolved for the interpreter that runs it")
    if not args.conda:
        with tempfile.TemporaryDirectory(prefix="escapement-lock-") as scratch:
            compiler = make_locker(Path(scratch) / "venv")
            for index in range(len(LAYERS)):
                compile_layer(compiler, index, args.upgrade, Path(scratch))
    (HERE / "environment.yml").write_text(conda_yaml())
    print("environment/environment.yml written")


if __name__ == "__main__":
    main()
