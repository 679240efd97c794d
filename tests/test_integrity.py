"""Every table and dataset proves it is whole before it is read: a file cut at a line or inside one, emptied, or with
bits flipped is refused in one line naming it and the command that rebuilds it, or (a flip in unused space) reads
back byte for byte as written; a job that reads a damaged table fails in that one line."""

import re

import netCDF4
import numpy as np
import pytest
import xarray as xr

from escapement.io.netcdf import DatasetError, read_csv, read_netcdf, read_variables, write_csv, write_netcdf
from escapement.pipeline.logs import logged
from escapement.verdict.scores import COLUMNS, read_scores

ROWS = [{"step": str(i), "velocity": repr(0.1 * i)} for i in range(40)]


def dataset():
    return xr.Dataset({"velocity": ("cycle", np.linspace(-1.0, 1.0, 40), {"units": "m s-1"})},
                      coords={"cycle": ("cycle", np.arange(1.0e10, 1.0e10 + 40), {"long_name": "impact cycle"})},
                      attrs={"title": "velocities before the impacts, case a", "F": 1.0})


def refused(read, path, why):
    """The one-line refusal of ``path`` by ``read``, its reason matching ``why``."""
    with pytest.raises(DatasetError) as err:
        read(path)
    message = str(err.value)
    assert "\n" not in message
    assert re.fullmatch(rf"{re.escape(str(path))}: damaged \({why}.*\); rebuild it: "
                        rf"snakemake --cores 2 --forcerun {re.escape(str(path))}", message), message


def cut_at_line(data: bytes) -> bytes:
    return b"".join(data.splitlines(keepends=True)[:-3])


def flip(data: bytes, at: int) -> bytes:
    return data[:at] + bytes([data[at] ^ 0x10]) + data[at + 1:]


@pytest.mark.parametrize("damage, why", [
    (cut_at_line, "its content does not match its digest"),
    (lambda data: data[: len(data) // 2 + 3], "its content does not match its digest"),  # inside a line
    (lambda data: b"", "its first line is b''"),
    (lambda data: flip(data, len(data) - 5), "its content does not match its digest"),  # a value
    (lambda data: data.replace(b"# rows: 40;", b"# rows: 41;"), "it holds 40 rows, its first line says 41"),
    (lambda data: data.partition(b"\n")[2], "its first line is b'step,velocity'"),  # as written before digests
], ids=["cut at a line", "cut inside a line", "emptied", "a bit flipped", "its row count changed", "no digest"])
def test_a_damaged_table_is_refused_in_one_line(tmp_path, damage, why):
    path = tmp_path / "readings.csv"
    write_csv(ROWS, ["step", "velocity"], path)
    assert read_csv(path, ["step", "velocity"]) == ROWS
    path.write_bytes(damage(path.read_bytes()))
    refused(lambda p: read_csv(p, ["step", "velocity"]), path, re.escape(why))


@pytest.mark.parametrize("damage, why", [
    (lambda data: data[: len(data) // 2], "OSError: NetCDF: HDF error"),
    (lambda data: b"", "OSError: NetCDF: Unknown file format"),
    (lambda data: flip(data, data.find(np.arange(1.0e10, 1.0e10 + 40).tobytes()) + 100), "RuntimeError: NetCDF: HDF"),
    (lambda data: flip(data, data.find(b"case a")), "OSError: NetCDF: HDF error"),  # HDF5's header checksum
], ids=["cut in half", "emptied", "a bit flipped in the data", "a bit flipped in an attribute"])
@pytest.mark.parametrize("read", [read_netcdf, lambda path: read_variables(path, ["velocity"])], ids=["xarray", "few"])
def test_a_damaged_dataset_is_refused_in_one_line(tmp_path, damage, why, read):
    path = write_netcdf(dataset(), tmp_path / "case_a.nc")
    path.write_bytes(damage(path.read_bytes()))
    refused(read, path, re.escape(why))


def edit_attribute(path):
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr("F", 1.0000009536743164)


@pytest.mark.parametrize("make, stored", [
    (lambda path: edit_attribute(write_netcdf(dataset(), path)), "'[0-9a-f]{64}'"),
    (lambda path: dataset().to_netcdf(path, engine="netcdf4"), "None"),  # as every file written before digests
], ids=["an attribute edited in place", "no digest"])
def test_a_dataset_that_is_not_as_written_is_refused(tmp_path, make, stored):
    make(path := tmp_path / "case_a.nc")
    refused(read_netcdf, path, rf"its content does not match its digest \(sha256 = {stored}\)")


def content(ds: xr.Dataset) -> dict:
    return {"": repr(ds.attrs), **{name: (v.dims, v.values.tobytes(), repr(v.attrs))
                                   for name, v in ds.variables.items()}}


@pytest.mark.parametrize("region", ["attributes", "data", "whole file"])
def test_no_flipped_bit_reads_back_changed_data(tmp_path, region):
    """Single flips at seeded random places of the global attributes' header, of the data (the coordinate, stored
    as it is), of the whole file: each one refused, or (in unused space) the data and attributes read back byte
    for byte. Each damaged copy is a new file: HDF5 keeps a file whose opening failed open, and serves a later
    opening of the same file from what it cached."""
    path = write_netcdf(dataset(), tmp_path / "case_a.nc")
    written, data = content(read_netcdf(path)), path.read_bytes()
    coordinate = data.find(np.arange(1.0e10, 1.0e10 + 40).tobytes())
    start, end = {"attributes": (data.find(b"title"), data.find(b"product_version") + 30),
                  "data": (coordinate, coordinate + 320), "whole file": (0, len(data))}[region]
    assert 0 <= start < end
    outcomes = {"refused": 0, "same": 0}
    for i, at in enumerate(np.random.default_rng(2013).integers(start, end, 30)):
        (path := tmp_path / f"case_a_{i}.nc").write_bytes(flip(data, int(at)))
        try:
            back = read_netcdf(path)
        except DatasetError as err:
            assert str(err).endswith(f"--forcerun {path}") and "\n" not in str(err)
            outcomes["refused"] += 1
            continue
        assert content(back) == written, f"a flip at byte {at} changed the data"
        outcomes["same"] += 1
    assert outcomes["refused"] > 0


def test_a_readings_table_cut_to_97_percent_of_its_lines_fails_the_job_in_one_line(tmp_path):
    """The table the claims job reads its readings from, cut as a full disk or a killed copy would leave it."""
    path = tmp_path / "readings.csv"
    write_csv([dict.fromkeys(COLUMNS, "1") for _ in range(200)], COLUMNS, path)
    assert len(read_scores(str(path))) == 200
    lines = path.read_bytes().splitlines(keepends=True)
    path.write_bytes(b"".join(lines[: int(0.97 * len(lines))]))
    with pytest.raises(SystemExit) as failed, logged(tmp_path / "check_claims.log", "check_claims"):
        read_scores(str(path))
    assert failed.value.code == (f"check_claims failed: {path}: damaged (its content does not match its digest); "
                                 f"rebuild it: snakemake --cores 2 --forcerun {path}")
    assert "Traceback" not in (tmp_path / "check_claims.log").read_text()
