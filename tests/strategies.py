"""Hypothesis strategies for valid model parameters and initial states."""

from __future__ import annotations

from hypothesis import strategies as st

from escapement import Parameters
from escapement.model.parameters import SMALLEST


def _zero_or_normal(x: float) -> bool:
    """0, or of a magnitude the model accepts (see escapement.model.parameters)."""
    return x == 0.0 or abs(x) >= SMALLEST


@st.composite
def parameters(draw, symmetric: bool | None = None) -> Parameters:
    """Valid parameters over a wide but well-conditioned range (SI units)."""
    M = draw(st.floats(0.2, 5.0))
    K = draw(st.floats(0.2, 5.0))
    F = draw(st.floats(0.0, 3.0).filter(_zero_or_normal))
    b = draw(st.floats(0.02, 0.95))
    a1 = -draw(st.floats(0.02, 0.5))
    a2 = a1 + draw(st.floats(0.01, 0.6))
    sym = draw(st.booleans()) if symmetric is None else symmetric
    if sym:
        return Parameters(M=M, K=K, F=F, b=b, a1=a1, a2=a2)
    a3 = draw(st.floats(0.02, 0.5))
    a4 = a3 - draw(st.floats(0.01, 0.6))
    return Parameters(M=M, K=K, F=F, b=b, a1=a1, a2=a2, a3=a3, a4=a4)


initial_displacement = st.floats(-3.0, 3.0).filter(_zero_or_normal)
initial_velocity = st.floats(-2.0, 2.0).filter(_zero_or_normal)
