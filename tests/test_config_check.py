from pathlib import Path

import pytest
import yaml

from escapement.config_check import config_error

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow/schemas/config.schema.yaml"


@pytest.fixture
def config():
    return yaml.safe_load((ROOT / "config/config.yaml").read_text())


def test_the_shipped_configuration_is_valid(config):
    assert config_error(config, SCHEMA) is None


@pytest.mark.parametrize(
    "edit, message",
    [
        (lambda c: c["model"].update(M=0.0), "model.M = 0.0 is invalid: M must be a number > 0 (mass, kg)"),
        (lambda c: c["model"].update(K=-1.0), "model.K = -1.0 is invalid: K must be a number > 0"),
        (lambda c: c["model"].update(b=2.0), "model.b = 2.0 is invalid: b must be a number in the open interval (0, 2)"),
        (lambda c: c["fig4"].update(F=-1.0), "fig4.F = -1.0 is invalid: F must be a number >= 0 (force, N)"),
        (lambda c: c["model"].update(a1="left"), "model.a1 = 'left' is invalid: a1 must be a number"),
        (lambda c: c["fig3"].update(n_cycles=2.5), "fig3.n_cycles = 2.5 is invalid: n_cycles must be an integer >= 1"),
        (lambda c: c["model"].pop("K"), "model: the key 'K' is missing: it must be given"),
        (lambda c: c.update(extra=1), "unknown key 'extra'"),
        (lambda c: c["fig4"].update(velocity_window=[80.0]), "fig4.velocity_window = [80.0] is invalid"),
    ],
)
def test_each_problem_is_one_clear_line(config, edit, message):
    edit(config)
    problem = config_error(config, SCHEMA)
    assert problem is not None and message in problem
    assert "\n" not in problem
