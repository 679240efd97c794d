import pytest

from escapement import ParameterError
from escapement.scene_config import initial_state_from, parameters_from

SCENE = {"M": 1.0, "K": 1.0, "F": 0.5, "b": 0.1, "a1": -0.1, "a2": 0.05, "x0": 3.0}


def test_a_complete_scene_gives_parameters_and_initial_state():
    p = parameters_from(SCENE)
    assert (p.a3, p.a4) == (0.1, -0.05)
    assert initial_state_from(SCENE) == (3.0, 0.0)


@pytest.mark.parametrize("key", ["M", "K", "F", "b", "a1", "a2"])
def test_a_missing_model_key_is_named(key):
    with pytest.raises(ParameterError, match=f"^{key} = None is invalid: {key} must be given"):
        parameters_from({k: v for k, v in SCENE.items() if k != key})


def test_a_missing_x0_is_named():
    with pytest.raises(ParameterError, match="^x0 = None"):
        initial_state_from({k: v for k, v in SCENE.items() if k != "x0"})
