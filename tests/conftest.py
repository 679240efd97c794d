"""Shared test configuration: hypothesis profiles and the paper's parameter sets."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

from escapement import Parameters, solve_exact

settings.register_profile(
    "ci", derandomize=True, max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile("dev", max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def paper_parameters(F: float, K: float = 1.0) -> Parameters:
    """Sec. 4: M = 1 kg, b = 0.1, a1 = -0.1 m, a2 = 0.05 m, symmetric geometry."""
    return Parameters(M=1.0, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)


@pytest.fixture
def case_a() -> Parameters:
    """Fig. 3 (a)'s model: F = 1 N (the configuration releases it from rest at -1 m)."""
    return paper_parameters(F=1.0)


@pytest.fixture
def case_b() -> Parameters:
    """Fig. 3 (b)'s model: F = 0.5 N (the configuration releases it from rest at -3 m)."""
    return paper_parameters(F=0.5)


@pytest.fixture(scope="session")
def run50():
    """Fig. 3 (a)'s model (M = 1 kg, K = 1 N/m, F = 1 N, b = 0.1, a1 = -0.1 m, a2 = 0.05 m) released from rest at
    +1 m (the mirror of the configuration's -1 m), 50 cycles."""
    return solve_exact(paper_parameters(F=1.0), 1.0, n_cycles=50)


@pytest.fixture(scope="session")
def stopped():
    """Released at 0.01 m from rest, the free swing (radius 0.01 m) never reaches a1 = -0.1 m or a3 = 0.1 m."""
    return solve_exact(paper_parameters(F=1.0), 0.01, n_cycles=5)


#: the files that take a worker longest, longest first: under ``--dist loadfile`` each goes whole to a worker, the
#: next file to the first worker free, so that the two workers start on the longest and the short files, run last,
#: fill both of them to the end
LONGEST = ("test_workflow.py", "solvers/test_memory.py", "plotting/test_layout.py", "paper/test_claims.py",
           "pipeline/test_readings.py", "pipeline/test_speed.py", "solvers/test_grazing.py", "test_benchmark_target.py")


def pytest_collection_modifyitems(config, items):
    """The longest files first (:data:`LONGEST`), the others after them in the order they were collected."""
    rank = {name: i for i, name in enumerate(LONGEST)}
    tests = Path(__file__).parent

    def place(item) -> int:
        name = item.path.relative_to(tests).as_posix() if item.path.is_relative_to(tests) else ""
        return rank.get(name, len(LONGEST))

    items.sort(key=place)
