"""The stress cases of the files and the configuration: each passes, and each can fail."""

from __future__ import annotations

import pytest

from escapement.pipeline import edge_cases
from escapement.pipeline.edge_cases import EDGE_CASES, run_edge_cases
from escapement.pipeline.tables import STRESS_COLUMNS


def test_every_case_passes_with_a_row_of_the_summary():
    rows = run_edge_cases()
    assert [r["case"] for r in rows] == ["netcdf_bit_flip", "killed_writer", "fig5_label_collision",
                                         "config_yaml_error"]
    for row in rows:
        assert list(row) == STRESS_COLUMNS
        assert row["passed"] == "yes", row


def test_the_bit_flip_case_fails_without_the_checksum(monkeypatch):
    def without_checksum(ds, path):
        ds.to_netcdf(path, engine="netcdf4", encoding={n: {"_FillValue": None} for n in ds.coords})
        return path

    monkeypatch.setattr(edge_cases, "write_netcdf", without_checksum)
    row = edge_cases.netcdf_bit_flip()
    assert row["passed"] == "no" and row["detail"] == "read back without an error"


def test_the_killed_writer_case_fails_when_nothing_is_swept(monkeypatch):
    monkeypatch.setattr(edge_cases, "remove_stale_temporaries", lambda directory: [])
    assert edge_cases.killed_writer()["passed"] == "no"


def test_the_collision_case_fails_when_collisions_pass(monkeypatch):
    monkeypatch.setattr(edge_cases, "fig5_label_collision", lambda ks: None)
    assert edge_cases.label_collision()["passed"] == "no"


@pytest.mark.parametrize("case", EDGE_CASES, ids=[c.__name__ for c in EDGE_CASES])
def test_each_case_is_deterministic(case):
    first, second = case(), case()
    assert first == second  # the summary is shown in README.md, which git tracks
