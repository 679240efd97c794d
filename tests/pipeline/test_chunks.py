"""Every size a job holds is answered at planning: a run that cannot be split and would exceed its bound is refused
in one line naming the keys that size it, and a map larger than one job's memory budget is planned in chunks of its
rows, each within the budget the ensemble checks, whose datasets join into the one dataset a single job makes."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from snakemake.utils import update_config

from escapement.model.limits import MEMORY_BUDGET, MemoryBudgetError, RunLimits, check_budget
from escapement.pipeline.config import ConfigError
from escapement.pipeline.plan import Planned, chunks, plan
from escapement.scenes.maps import existence_map, gather, stability_map
from escapement.scenes.settings import COUNTS, ExistenceMapScene, SizeError, StabilityMapScene
from escapement.solvers.ensemble import ensemble_bytes
from escapement.solvers.exact import ARC_BYTES, CYCLE_BYTES, EVENT_BYTES, PASS_BYTES

PAPER = yaml.safe_load((Path(__file__).resolve().parents[2] / "config" / "paper.yaml").read_text())


def planned(user: dict) -> dict:
    """The studies the user's blocks, laid over the paper's file, plan."""
    config = copy.deepcopy(PAPER)
    update_config(config, copy.deepcopy(user))
    return plan(config, PAPER)[0]


def scene(block: str, **axes) -> dict:
    """The flat settings of the paper's map ``block`` with its axes' counts (``F=3``) and keys replaced."""
    values = {**PAPER["model"], **copy.deepcopy(PAPER[block]), "study": "small"}
    for key, value in axes.items():
        values[key] = {**values[key], "n": value} if isinstance(values[key], dict) else value
    return values


@pytest.mark.parametrize("user, message", [
    ({"fig5": {"n_cycles": 10_000, "samples_per_period": 1001}},
     "your study 'own': fig5.n_cycles = 10000 with fig5.samples_per_period = 1001: 1.001e7 samples of one "
     "trajectory, at most 1e7 (one trajectory cannot be split)"),
    # each window within the bound, their union (which the job samples) over it
    ({"fig4": {"acceleration_window": [81.0, 180.5], "samples_per_second": 100_000}},
     "your study 'own': fig4.velocity_window = [80, 87] with fig4.acceleration_window = [81, 180.5] and "
     "fig4.samples_per_second = 100000: 1.005e7 samples of one trajectory, at most 1e7 (one trajectory cannot be "
     "split)"),
])
def test_a_trajectory_just_over_its_samples_is_refused_at_planning_in_one_line_naming_its_keys(user, message):
    with pytest.raises(ConfigError) as refusal:
        planned(user)
    assert str(refusal.value) == message
    at_bound = {"fig5": {"n_cycles": 10_000, "samples_per_period": 1000}} if "fig5" in user else \
        {"fig4": {"acceleration_window": [81.0, 180.0], "samples_per_second": 100_000}}
    assert planned(at_bound)["own"]  # 1e7 samples: planned


def test_a_map_whose_one_row_exceeds_a_job_s_budget_is_refused_in_one_line_naming_its_keys():
    checked = ExistenceMapScene.from_mapping(scene("existence_map"))  # 70 forces, 120 cycles
    row = 70 * (48 * 120 + 1000)  # bytes: the ensemble's 48 a trajectory and cycle, 1000 a trajectory
    assert chunks(checked, row) == 100  # one row a job
    with pytest.raises(SizeError) as refusal:
        chunks(checked, row - 1)
    assert str(refusal.value) == ("existence_map.F.n = 70 with existence_map.n_cycles = 120: 473200 bytes of the "
                                  "ensemble of one row of a3, at most 473199 (a row of the map cannot be split)")


@pytest.mark.parametrize("user, block, count, rows", [
    # 2000 forces of 2 cycles: 2_192_000 bytes a row of b, 912 rows a job within 2 GB
    ({"stability_map": {"b": {"n": 2000}, "F": {"n": 2000}}}, "stability_map", 3, 667),
    # 400 forces of 10_000 cycles: 192_400_000 bytes a row of a3, 10 rows a job
    ({"existence_map": {"a3": {"n": 400}, "F": {"n": 400}, "n_cycles": 10_000}}, "existence_map", 40, 10),
])
def test_a_map_over_one_job_s_budget_is_planned_in_chunks_each_within_the_ensemble_s_own_check(user, block, count,
                                                                                                rows):
    found = planned(user)["own"][block][""]
    assert found.chunks == count
    first = found.chunk(0)
    values = first.b_values if block == "stability_map" else first.a3_values
    cycles = 2 if block == "stability_map" else 10_000
    assert len(values) == rows
    trajectories = [("trajectories", rows * len(first.F_values), lambda n: ensemble_bytes(n, cycles))]
    check_budget(MEMORY_BUDGET, "a chunk", trajectories)  # the ensemble's check, which the chunk's job passes
    with pytest.raises(MemoryBudgetError):  # and the whole map's, which one job does not
        check_budget(MEMORY_BUDGET, "the map", [("trajectories", count * rows * len(first.F_values),
                                                 trajectories[0][2])])
    assert MEMORY_BUDGET == 2_000_000_000


@pytest.mark.parametrize("kind, make, settings, axis", [
    ("stability_map", stability_map, StabilityMapScene.from_mapping(scene("stability_map", b=5, F=3)), "b"),
    ("existence_map", existence_map, ExistenceMapScene.from_mapping(scene("existence_map", a3=5, F=2, n_cycles=6)),
     "a3"),
])
def test_a_map_just_over_one_job_s_budget_runs_in_chunks_that_gather_into_the_single_job_s_dataset(kind, make,
                                                                                                    settings, axis):
    cycles = 2 if kind == "stability_map" else 6
    row = ensemble_bytes(len(settings.F_values), cycles)
    count = chunks(settings, 5 * row - 1)  # five rows, a byte short of one job
    assert count == 2
    parts = Planned({}, settings, count)
    made = [make(parts.chunk(i)) for i in range(count)]
    datasets = [m[0] if isinstance(m, tuple) else m for m in made]
    assert [ds.sizes[axis] for ds in datasets] == [3, 2]
    whole = make(settings)
    xr.testing.assert_identical(gather(datasets)[0], whole[0] if isinstance(whole, tuple) else whole)


def test_the_stability_map_s_costs_per_trajectory_are_its_chunks_weighted_by_what_each_timed():
    datasets = [xr.Dataset({"outcome": (("b", "F"), np.zeros((b, 3)))}, coords={"b": np.arange(b) + s, "F": [0, 1, 2]})
                for b, s in ((3, 0), (2, 3))]  # 9 and 6 cells
    timings = [{"ensemble_seconds_per_trajectory": 1.0, "scalar_seconds_per_trajectory": 4.0},
               {"ensemble_seconds_per_trajectory": 3.0, "scalar_seconds_per_trajectory": 8.0}]
    _, costs = gather(datasets, timings)
    assert costs == pytest.approx({"ensemble_seconds_per_trajectory": 27 / 15, "scalar_seconds_per_trajectory": 84 / 15,
                                   "ensemble_speedup_per_trajectory": 84 / 27})


def test_the_longest_single_runs_the_schema_allows_fit_the_exact_solver_s_budget_so_planning_needs_no_more():
    """Fig. 3's run at its most cycles (its trajectory kept, for the largest |x| amplitude) and Fig. 4's to the end
    of its windows (at most 10**7 events) fit the budget the exact solver checks; Fig. 5's runs are shorter."""
    event = EVENT_BYTES + ARC_BYTES
    assert COUNTS["fig3.n_cycles"][1] == 1_000_000 and COUNTS["fig5.n_cycles"][1] == 10_000
    RunLimits(n_cycles=1_000_000).check_memory(event, CYCLE_BYTES, "fig3", "", PASS_BYTES)
    RunLimits(t_end=1e9).check_memory(event, CYCLE_BYTES, "fig4", "", PASS_BYTES)
    with pytest.raises(MemoryBudgetError):  # the check binds beyond them
        RunLimits(n_cycles=4_000_000).check_memory(event, CYCLE_BYTES, "fig3", "", PASS_BYTES)
