"""netCDF files as written and read: compressed, checksummed, renamed into place, refused by name when damaged."""

import os

import netCDF4
import numpy as np
import pytest
import xarray as xr

from escapement.io.netcdf import DatasetError, read_netcdf, write_netcdf


def small_dataset():
    return xr.Dataset(
        {"v": ("t", np.arange(5.0), {"units": "m s-1", "long_name": "velocity"})},
        coords={"t": ("t", np.linspace(0, 1, 5), {"units": "s", "long_name": "time"})},
        attrs={"title": "test"},
    )


def test_round_trip_compressed_without_fill_value_on_coordinates(tmp_path):
    path = write_netcdf(small_dataset(), tmp_path / "x.nc", history="a test")
    with netCDF4.Dataset(path) as nc:
        assert "_FillValue" not in nc["t"].ncattrs()
        assert nc["v"].filters()["zlib"] is True
    back = read_netcdf(path, required=("v", "t"))
    assert back["v"].values.tolist() == [0, 1, 2, 3, 4]
    assert back.attrs["title"] == "test" and back.attrs["history"].endswith(": a test")


def test_written_file_respects_the_umask(tmp_path):
    old = os.umask(0o022)
    try:
        path = write_netcdf(small_dataset(), tmp_path / "x.nc")
    finally:
        os.umask(old)
    assert (path.stat().st_mode & 0o777) == 0o644


def test_failed_write_leaves_nothing_behind(tmp_path):
    bad = small_dataset()
    bad.attrs["bad"] = {"a dict": "cannot be an attribute"}
    with pytest.raises(Exception):
        write_netcdf(bad, tmp_path / "x.nc")
    assert list(tmp_path.iterdir()) == []


def test_truncated_file_is_named_in_the_error(tmp_path):
    path = write_netcdf(small_dataset(), tmp_path / "x.nc")
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 3])
    with pytest.raises(DatasetError, match=r"x\.nc: not a readable netCDF file"):
        read_netcdf(path)


def test_garbage_file_is_named_in_the_error(tmp_path):
    path = tmp_path / "junk.nc"
    path.write_text("this is not netCDF")
    with pytest.raises(DatasetError, match=r"junk\.nc"):
        read_netcdf(path)


def test_missing_file_and_missing_variable(tmp_path):
    with pytest.raises(DatasetError, match="no such netCDF file"):
        read_netcdf(tmp_path / "none.nc")
    path = write_netcdf(small_dataset(), tmp_path / "x.nc")
    with pytest.raises(DatasetError, match=r"x\.nc: lacks the variable\(s\) w"):
        read_netcdf(path, required=("v", "w"))


# -- checksums ---------------------------------------------------------------------------------------------------------

#: distinctive values of a coordinate, found in the file by their bytes (stored uncompressed)
TIMES = np.array([1.2345678901234e10 + i for i in range(5)])


def flip_bit(path, pattern: bytes, offset: int = 10) -> None:
    """Flip one bit of ``path`` inside the only occurrence of ``pattern``."""
    data = bytearray(path.read_bytes())
    assert data.count(pattern) == 1
    data[data.find(pattern) + offset] ^= 0x04
    path.write_bytes(data)


def test_every_variable_is_checksummed(tmp_path):
    path = write_netcdf(small_dataset(), tmp_path / "x.nc")
    with netCDF4.Dataset(path) as nc:
        assert {name: nc[name].filters()["fletcher32"] for name in ("v", "t")} == {"v": True, "t": True}


def test_flipped_bit_in_an_uncompressed_variable_fails_its_checksum(tmp_path):
    ds = xr.Dataset({"v": ("t", np.arange(5.0))}, coords={"t": ("t", TIMES)})
    path = write_netcdf(ds, tmp_path / "x.nc")
    flip_bit(path, TIMES.tobytes())
    with pytest.raises(DatasetError, match=r"x\.nc: not a readable netCDF file"):
        read_netcdf(path)
    # The same file without the checksum: the flipped bit is read back as data.
    bare = tmp_path / "bare.nc"
    ds.to_netcdf(bare, engine="netcdf4", encoding={"t": {"_FillValue": None}})
    flip_bit(bare, TIMES.tobytes())
    with xr.open_dataset(bare, engine="netcdf4") as back:
        changed = back["t"].values != TIMES
    assert changed.tolist() == [False, True, False, False, False]


def test_flipped_bit_in_a_compressed_variable_is_detected(tmp_path):
    """Random bytes do not compress: zlib stores them as they come from the shuffle filter (byte k of
    every value, then byte k + 1), where they can be found. zlib's own check would catch this flip too."""
    values = np.random.default_rng(1).integers(-(2**62), 2**62, size=512, dtype=np.int64)
    path = write_netcdf(xr.Dataset({"v": ("n", values)}), tmp_path / "x.nc")
    with netCDF4.Dataset(path) as nc:
        assert nc["v"].filters()["zlib"] and nc["v"].filters()["shuffle"]
    shuffled = np.frombuffer(values.tobytes(), np.uint8).reshape(-1, 8).T.tobytes()
    flip_bit(path, shuffled[2000:2064])
    with pytest.raises(DatasetError, match=r"x\.nc: not a readable netCDF file"):
        read_netcdf(path)


# -- failures of the netCDF library --------------------------------------------------------------------------------


def test_other_netcdf_failure_names_the_file(tmp_path, monkeypatch):
    def fail(*args, **kwargs):
        raise RuntimeError("NetCDF: Not a valid data type or _FillValue type mismatch")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", fail)
    with pytest.raises(DatasetError, match=r"x\.nc: cannot write the netCDF file \(RuntimeError: NetCDF: Not a valid"):
        write_netcdf(small_dataset(), tmp_path / "x.nc")
    assert list(tmp_path.iterdir()) == []
