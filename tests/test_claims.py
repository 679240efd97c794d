"""The claims machinery: the register's form, the evaluation, the CSV."""

import pytest
import yaml

from escapement.claims import (
    CHECKS,
    COLUMNS,
    STATUSES,
    Evidence,
    evaluate,
    fmt,
    load_claims,
    read_claims_csv,
    write_claims_csv,
)
from escapement.scenes import checks_scene, phase_scene, poincare_scene, shock_scene
from escapement.scene_config import parameters_from

from test_paper_claims import REGISTER


@pytest.fixture(scope="module")
def evidence():
    model = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
    p = lambda **kw: parameters_from({**model, **kw})  # noqa: E731
    cases = [
        {**model, "F": 1.0, "x0": 1.0, "group": "paper", "label": "fig3a"},
        {**model, "F": 0.5, "x0": 3.0, "group": "paper", "label": "fig3b"},
        {**model, "F": 1.0, "x0": 3.0, "group": "initial_condition", "label": "ic"},
        {**model, "F": 1.0, "x0": 1.0, "b": 0.5, "group": "b", "label": "b=0.5"},
        {**model, "F": 1.0, "x0": 1.0, "b": 1.5, "group": "b", "label": "b=1.5"},
        {**model, "F": 2.0, "x0": 1.0, "group": "symmetric", "label": "sym"},
        {**model, "F": 1.0, "x0": 1.0, "a3": 0.2, "a4": -0.02, "group": "asymmetric", "label": "asym"},
    ]
    return Evidence(
        fig3={"a": poincare_scene(p(F=1.0), 1.0, 50), "b": poincare_scene(p(F=0.5), 3.0, 50)},
        fig4=shock_scene(p(F=0.5), 3.0, (80.0, 87.0), (81.0, 85.0), 200),
        fig5={f"{k:g}": phase_scene(p(F=0.5, K=k), 1.0, 60, 200) for k in (0.1, 1.0, 10.0)},
        checks=checks_scene(cases, 300),
    )


def test_the_register_loads_and_names_known_checks():
    claims = load_claims(REGISTER)
    assert len(claims) >= 30
    assert all(c["check"] in CHECKS for c in claims)


def test_every_claim_gets_a_row_with_the_exact_columns(evidence):
    rows = evaluate(load_claims(REGISTER), evidence)
    assert len(rows) == len(load_claims(REGISTER))
    for row in rows:
        assert list(row) == COLUMNS
        assert row["status"] in STATUSES
        assert row["replicated_value"]


def test_csv_round_trip(tmp_path, evidence):
    rows = evaluate(load_claims(REGISTER), evidence)
    path = tmp_path / "claims.csv"
    write_claims_csv(rows, path)
    assert path.read_text().splitlines()[0] == ",".join(COLUMNS)
    assert read_claims_csv(path) == rows


def test_csv_with_other_columns_is_rejected(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="columns"):
        read_claims_csv(path)


@pytest.mark.parametrize(
    "mutate, message",
    [
        (lambda c: c[0].pop("tolerance"), "lacks 'tolerance'"),
        (lambda c: c.append(dict(c[0])), "appears twice"),
        (lambda c: c[0].update(check="nonsense"), "unknown check"),
    ],
)
def test_a_malformed_register_is_rejected(tmp_path, mutate, message):
    data = yaml.safe_load(REGISTER.read_text())
    mutate(data["claims"])
    path = tmp_path / "claims.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(ValueError, match=message):
        load_claims(path)


def test_fmt_is_stable_and_short():
    assert fmt(6.295673629679129) == "6.29567363"
    assert fmt(float("nan")) == "nan"
    assert fmt("text") == "text"
