"""From a scene's configuration (the paper's symbols as keys) to model parameters.

A scene's mapping holds the model keys (M, K, F, b, a1, a2, optional a3, a4) and
the initial displacement x0; the workflow merges the common ``model`` block with
the scene's own keys before it gets here.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..model.parameters import ParameterError, Parameters, check_initial_state

__all__ = ["MODEL_KEYS", "parameters_from", "initial_state_from"]

MODEL_KEYS = ("M", "K", "F", "b", "a1", "a2", "a3", "a4")
REQUIRED = ("M", "K", "F", "b", "a1", "a2")


def parameters_from(scene: Mapping) -> Parameters:
    """Build validated parameters; a missing key raises a :class:`ParameterError` naming it."""
    for key in REQUIRED:
        if key not in scene:
            raise ParameterError(key, None, "given (it is missing from the configuration)")
    return Parameters(**{k: scene[k] for k in MODEL_KEYS if scene.get(k) is not None})


def initial_state_from(scene: Mapping) -> tuple[float, float]:
    if "x0" not in scene:
        raise ParameterError("x0", None, "given (it is missing from the configuration)")
    return check_initial_state(scene["x0"], scene.get("v0", 0.0))
