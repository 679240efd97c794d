"""Shared test configuration: hypothesis profiles and the paper's parameter sets."""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

from escapement import Parameters

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
    """Fig. 3 (a): F = 1 N (with x0 = 1 m)."""
    return paper_parameters(F=1.0)


@pytest.fixture
def case_b() -> Parameters:
    """Fig. 3 (b): F = 0.5 N (with x0 = 3 m)."""
    return paper_parameters(F=0.5)


def pytest_collection_modifyitems(config, items):
    """The end-to-end files first: each takes about a minute of one worker, so under ``-n 2`` they
    start at once on their own workers and the unit tests fill the gaps."""
    items.sort(key=lambda item: not item.path.name.startswith("test_workflow"))
