"""One chunk of the stability map: arrays on the (b, F) grid, the other parameters as constants."""

import numpy as np

from escapement.experiments.stability import stability_chunk
from escapement.model.status import Status
from escapement.paper.poincare import stability_grid
from escapement.paper.printed import multiplier_21_of

MODEL = {"M": 1.0, "K": 1.0, "a1": -0.1, "a2": 0.05}


def test_a_chunk_holds_the_grid_of_its_axes():
    b, F = [0.3, 0.6, 1.2], [0.5, 1.0]
    chunk = stability_chunk(MODEL, b, F, speed_sample=2)
    for name in ("multiplier", "multiplier_eq21", "fixed_point", "period", "status"):
        assert getattr(chunk, name).shape == (3, 2), name
    grid = stability_grid(MODEL, np.repeat(b, 2), np.tile(F, 3))
    np.testing.assert_array_equal(chunk.multiplier.ravel(), grid["multiplier"])
    assert chunk.multiplier_eq21[:, 0].tolist() == [multiplier_21_of(x) for x in b]
    assert chunk.constants == {"M": 1.0, "K": 1.0, "a1": -0.1, "a2": 0.05, "a3": 0.1, "a4": -0.05}
    assert (chunk.status[:2] == Status.COMPLETED.code).all()
    assert set(chunk.timings) == {"ensemble_seconds_per_trajectory", "scalar_seconds_per_trajectory"}
