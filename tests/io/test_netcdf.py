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
    path = write_netcdf(small_dataset(), tmp_path / "sub" / "x.nc")
    with netCDF4.Dataset(path) as nc:
        assert "_FillValue" not in nc["t"].ncattrs()
        assert nc["v"].filters()["zlib"] is True
    back = read_netcdf(path, required=("v", "t"))
    assert back["v"].values.tolist() == [0, 1, 2, 3, 4]
    assert back.attrs["title"] == "test"


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
