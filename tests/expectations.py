"""What the suite expects of the paper's claims that the replication does not reproduce."""

import pytest


def paper_fails(reason: str):
    """A claim of the paper that the replication does not reproduce: a strict xfail that expects the
    assertion to fail (a crash inside the test is a failure, not the expected one), and fails the suite
    if the test passes."""
    return pytest.mark.xfail(strict=True, raises=AssertionError, reason=reason)
