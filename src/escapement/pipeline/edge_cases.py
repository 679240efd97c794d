"""Stress cases of the files and the configuration, beside the solver's (:mod:`escapement.studies.stress`).

Each returns one row of ``results/stress/summary.csv``, checked against what must happen: a
flipped bit in a netCDF file is refused by its Fletcher-32 checksum, a writer killed outright leaves
a temporary that the next run removes, two Fig. 5 panels that would share a file are refused, and a
YAML error is named with its line. They live in the pipeline layer because they exercise its files
and its configuration.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from ..io.atomic import remove_stale_temporaries
from ..io.netcdf import DatasetError, read_netcdf, write_netcdf
from .config import ConfigError, check_config_file, fig5_label_collision

__all__ = ["EDGE_CASES", "run_edge_cases"]


def _row(case: str, regime: str, outcome: str, check: str, passed: bool, detail: str) -> dict:
    return {"case": case, "regime": regime, "outcome": outcome, "check": check, "passed": "yes" if passed else "no",
            "detail": detail}


def netcdf_bit_flip() -> dict:
    """One bit flipped in the data of a variable: the read must fail, naming the file. The
    variable is a coordinate (stored uncompressed), so its raw bytes are found in the file and no
    zlib check can catch the flip: only the Fletcher-32 checksum does."""
    values = np.arange(1, 65, dtype=np.float64) * 1.0000000001  # a pattern found once in the file
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "flip.nc"
        coords = {"n": ("n", values, {"units": "s", "long_name": "a test coordinate"})}
        write_netcdf(xr.Dataset({"x": ("n", values * 2, {"units": "m", "long_name": "a test series"})}, coords), path)
        data = bytearray(path.read_bytes())
        at = data.find(values.tobytes())
        if at < 0:
            raise RuntimeError(f"{path}: the coordinate's raw bytes are not in the file")
        data[at + 8 * 32 + 3] ^= 0x04  # one bit of the 33rd value
        path.write_bytes(bytes(data))
        refused, message = False, "read back without an error"
        try:
            read_netcdf(path)
        except DatasetError as err:
            refused = str(path) in str(err) and "Fletcher-32" in str(err)
            message = str(err).rsplit("; ", 1)[-1]
    return _row("netcdf_bit_flip", "files: one bit flipped in a netCDF variable", "refused",
                "the Fletcher-32 checksum refuses the damaged file, naming it and the variable", refused, message)


def killed_writer() -> dict:
    """A writer killed outright (SIGKILL) leaves its temporary; the next run's sweep removes it."""
    with tempfile.TemporaryDirectory() as tmp:
        target = Path(tmp) / "table.csv"
        code = (
            "import sys, time\n"
            "from escapement.io.atomic import atomic_path\n"
            "with atomic_path(sys.argv[1]) as t:\n"
            "    t.write_text('partial')\n"
            "    print('writing', flush=True)\n"
            "    time.sleep(60)\n"
        )
        child = subprocess.Popen([sys.executable, "-c", code, str(target)], stdout=subprocess.PIPE, text=True)
        child.stdout.readline()  # the temporary exists
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=30)
        left = sorted(p.name for p in Path(tmp).iterdir())
        removed = remove_stale_temporaries(tmp)
        after = sorted(p.name for p in Path(tmp).iterdir())
    ok = len(left) == 1 and ".partial" in left[0] and len(removed) == 1 and after == []
    return _row("killed_writer", "files: a writer killed outright (SIGKILL) mid-write", "removed",
                "the temporary it leaves is removed by the next run's sweep; the target never appears", ok,
                f"left {len(left)} temporary, removed {len(removed)}")


def label_collision() -> dict:
    """Two spring constants whose file labels coincide would write one file: refused."""
    problem = fig5_label_collision([1.0, 1.0000001, 10.0]) or "accepted"
    ok = "would both write K_1.nc" in problem and fig5_label_collision([0.1, 1.0, 10.0]) is None
    return _row("fig5_label_collision", "configuration: two Fig. 5 panels that would share a file", "refused",
                "K = 1 and 1.0000001 N/m both label K_1.nc: refused before any job", ok,
                problem[problem.find("(") + 1:].rstrip(")") if ok else problem)


def yaml_error() -> dict:
    """An unclosed bracket: the error names the file and the line."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "config.yaml"
        path.write_text("model:\n  M: 1.0\n  K: [1.0, 2.0\n")
        try:
            check_config_file(path)
            message = "accepted"
        except ConfigError as err:
            message = str(err)
    ok = message.startswith(f"{path}, line 4, column 1: not valid YAML")
    return _row("config_yaml_error", "configuration: a YAML syntax error", "refused",
                "the error names the file, line and column (Snakemake's own says neither)", ok,
                message.split("not valid YAML: ", 1)[-1])


EDGE_CASES = (netcdf_bit_flip, killed_writer, label_collision, yaml_error)


def run_edge_cases() -> list[dict]:
    """Every case above, as rows of the stress summary."""
    return [case() for case in EDGE_CASES]
