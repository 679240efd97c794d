import pytest

from escapement.stress import CASES, StressCase, run_all, run_case


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_stress_case(case):
    result = run_case(case)
    assert result.passed, f"{case.name}: {result.outcome}: {result.detail}"


def test_a_case_that_raises_is_reported_not_raised():
    def broken():
        raise ZeroDivisionError("boom")

    result = run_case(StressCase("broken", "a regime", broken))
    assert not result.passed and result.outcome == "error" and "boom" in result.detail


def test_summary_rows():
    rows = run_all()
    assert [list(r) for r in rows] == [["case", "regime", "outcome", "check", "passed", "detail"]] * len(CASES)
