"""End to end: the benchmark target (`snakemake --cores 2 benchmark`, every setting and the speed table, which a
user runs on a quiet machine) on a reduced copy of its own: its jobs run, its figure is drawn, and no tracked file
changes. It needs nothing of the default run, so it runs beside tests/test_workflow.py."""

from __future__ import annotations

from workflow_copies import reduced_copy, snakemake, tracked_state


def test_the_benchmark_target_runs_and_draws_its_full_table(tmp_path):
    where = reduced_copy(tmp_path)
    before = tracked_state(where)
    snakemake(where, "--cores", "2", "benchmark")
    folder = where / "results/replication/benchmark"
    assert all((folder / name).is_file() for name in ("speed.csv", "headline.csv", "work_precision_full.png"))
    assert tracked_state(where) == before
