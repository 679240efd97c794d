"""The configuration as Snakemake is given it, end to end without a run: each file given with
``--configfile`` held to the checks of ``config/config.yaml``, and nested ``--config`` values used with
the types a file gives them, or refused in one line before any job."""

from __future__ import annotations

import pytest
from workflow_copies import copy_repository, snakemake


@pytest.fixture(scope="module")
def copy(tmp_path_factory):
    """One copy of the repository: every run below stops or only plans, so none changes it."""
    return copy_repository(tmp_path_factory.mktemp("config"))


def _refused(where, *args) -> str:
    result = snakemake(where, "--dry-run", *args, check=False)
    assert result.returncode != 0, result.stdout
    assert not (where / "results").exists()
    return result.stdout + result.stderr


@pytest.mark.parametrize(
    "name, text, where, problem",
    [
        ("dup.yaml", "fig3:\n  n_cycles: 40\nmodel:\n  M: 1.0\n  M: 2.0\n", "line 5, column 3",
         "not valid YAML: the key 'M' is given twice (first on line 4)"),
        ("dup.json", '{"fig3": {"n_cycles": 40},\n "fig3": {"n_cycles": 50}}\n', "line 2, column 2",
         "not valid JSON: the key 'fig3' is given twice (first on line 1)"),
    ],
)
def test_a_configfile_that_gives_a_key_twice_is_refused_naming_its_line(copy, tmp_path, name, text, where, problem):
    path = tmp_path / name
    path.write_text(text)
    message = _refused(copy, "--configfile", str(path))
    assert f"{path}, {where}: {problem}" in message


def test_the_second_of_two_configfiles_is_checked_too(copy, tmp_path):
    first, second = tmp_path / "first.yaml", tmp_path / "second.yaml"
    first.write_text("fig3:\n  n_cycles: 40\n")
    second.write_text("fig3:\n  n_cycles: 40\n  n_cycles: 50\n")
    message = _refused(copy, "--configfile", str(first), str(second))
    assert f"{second}, line 3, column 3: not valid YAML: the key 'n_cycles' is given twice" in message


def test_a_configfile_with_a_yaml_error_stops_snakemake_before_the_workflow(copy, tmp_path):
    """Snakemake reads a --configfile with its command line, before the workflow: its own message
    (without the line) is the one given, and no job starts."""
    path = tmp_path / "bad.yaml"
    path.write_text("fig3:\n  n_cycles: [40\n")
    assert "Config file is not valid JSON or YAML" in _refused(copy, "--configfile", str(path))


def test_a_configfile_value_is_checked_after_the_merge(copy, tmp_path):
    path = tmp_path / "low.yaml"
    path.write_text("fig3:\n  n_cycles: 0\n")
    assert "fig3.n_cycles = 0 is invalid: n_cycles must be an integer in [1, 1000000]" in _refused(
        copy, "--configfile", str(path))
    # --config overrides every file, as in Snakemake, and its nested value is an integer
    result = snakemake(copy, "--dry-run", "--configfile", str(path), "--config", "fig3={n_cycles: 40}")
    assert "simulate_fig3" in result.stdout


@pytest.mark.parametrize(
    "entries",
    [
        ["fig3={n_cycles: 40}"],
        ["fig5={K: [0.1, 1.0], F: [1.0, 0.5], x0: -1.0}"],
        ["stability_map={b: {start: 0.0, stop: 2.0, n: 8}, chunks: 4}", "speed={headline: {target: 1.0e-9}}"],
    ],
)
def test_a_nested_config_override_is_used(copy, entries):
    result = snakemake(copy, "--dry-run", "--config", *entries)
    assert "simulate_fig3" in result.stdout


@pytest.mark.parametrize(
    "entry, message",
    [
        ("stability_map={chunks: 2.0}",
         "stability_map.chunks = 2.0 is invalid: chunks must be an integer in [1, 1000] (write it without a decimal "
         "point)"),
        ("fig5={K: []}", "fig5.K = [] is invalid: K must be a list of one or more distinct numbers > 0 (N/m)"),
        ("model={M: 1e-3}", "model.M = '1e-3' is invalid: M must be a number > 0 (kg) (YAML reads 1e-3 as text: "
                            "write it 1.0e-3)"),
        ("fig3={n_cycles: 40", "--config 'fig3={n_cycles: 40', column 19: not valid YAML"),
        ("model={M: 1.0, M: 2.0}", "the key 'M' is given twice (first at column 8); a nested value may also be given "
                                   "in a file, with --configfile"),
    ],
)
def test_a_nested_config_override_that_is_invalid_is_refused_in_one_line(copy, entry, message):
    assert message in _refused(copy, "--config", entry)
