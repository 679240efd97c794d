"""The timing loop of the benchmark refuses a bad argument before it runs anything."""

import pytest

from escapement.studies.benchmark import median_wall


@pytest.mark.parametrize("kwargs, words", [
    (dict(fn=None), "fn = None is invalid: fn must be callable"),
    (dict(min_seconds=0), "min_seconds = 0 is invalid: min_seconds must be in (0, 60]"),
    (dict(min_seconds=61.0), "min_seconds = 61.0 is invalid"),
    (dict(min_seconds="0.1"), "min_seconds = '0.1' is invalid"),
    (dict(max_repeats=0), "max_repeats = 0 is invalid: max_repeats must be an integer in [1, 10000]"),
    (dict(max_repeats=True), "max_repeats = True is invalid"),
    (dict(max_repeats=2.0), "max_repeats = 2.0 is invalid"),
])
def test_a_bad_argument_is_refused_before_any_run(kwargs, words):
    calls = []
    arguments = {"fn": lambda: calls.append(1), "min_seconds": 0.01, "max_repeats": 3, **kwargs}
    with pytest.raises((TypeError, ValueError)) as refused:
        median_wall(**arguments)
    assert words in str(refused.value) and calls == []
