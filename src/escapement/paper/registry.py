"""Every check of the claims register, in one list.

Each check is a function marked with :func:`escapement.paper.checks.check` in the module of its
topic; it is in the register when :data:`REGISTERED` below names it, and only then. The claims
engine (:mod:`escapement.paper.claims`) reads :data:`CHECKS`, which maps each check's name in
``workflow/claims.yaml`` to its :class:`~escapement.paper.checks.Check`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from .airy import airy_order, daily_rate_check
from .axis_claims import printed_axes
from .checks import (
    Check,
    asymmetric_dependence,
    fixed_point,
    map_eq16,
    multiplier_paper_cases,
    multipliergroup_runs,
    stability_over_b,
)
from .conventions import eq14_conventions
from .dynamics_checks import force_amplitude, period_shares, piecewise_linear, release_transient, trivial_multiplier
from .existence import existence_sign_change, grazing_uniqueness, release_boundary
from .model_claims import impact_matrix, impulse_sets, jump_set, state_matrix, untestable
from .figure_checks import fig5_dimensions, fig5_impact_visible, section_crossings, window_impact
from .period_checks import eq22_abcd, eq22e, eq23, eq24, eq25
from .register import derivative_eq20, initial_order, map_eq17, natural_period, printed_step, stable_velocity_scaling
from .section4_checks import (
    both_converge,
    compare_cases,
    converged_period,
    convergence_rates,
    fig5_amplitude_common_force,
    fig5_converge,
    fig5_recovery_common_force,
    fig5_velocity_common_force,
    period_difference,
    period_initial_condition,
    shock_readout,
)

__all__ = ["CHECKS", "REGISTERED", "by_name"]

#: every check of the register, by the paper's section
REGISTERED: tuple[Callable, ...] = (
    # Sec. 3.3: the model's definitions, Eqs. (3a)-(5)
    state_matrix,
    impact_matrix,
    jump_set,
    impulse_sets,
    # Sec. 3.1-3.4: the step equations, the Poincare map, its fixed point and multiplier
    piecewise_linear,
    printed_step,
    eq14_conventions,
    map_eq16,
    map_eq17,
    fixed_point,
    derivative_eq20,
    multiplier_paper_cases,
    trivial_multiplier,
    stability_over_b,
    multipliergroup_runs,
    asymmetric_dependence,
    # Sec. 3.4: the period formulas, Eqs. (22)-(25)
    eq22_abcd,
    eq22e,
    eq23,
    eq24,
    eq25,
    natural_period,
    period_shares,
    # existence of the limit cycle
    existence_sign_change,
    release_boundary,
    grazing_uniqueness,
    # Sec. 4: Figs. 3, 4 and 5
    both_converge,
    compare_cases,
    convergence_rates,
    converged_period,
    period_difference,
    period_initial_condition,
    release_transient,
    initial_order,
    stable_velocity_scaling,
    force_amplitude,
    shock_readout,
    window_impact,
    fig5_converge,
    fig5_amplitude_common_force,
    fig5_velocity_common_force,
    fig5_recovery_common_force,
    fig5_dimensions,
    fig5_impact_visible,
    section_crossings,
    printed_axes,
    # the clock: Airy's theorem and the daily rate
    airy_order,
    daily_rate_check,
    # Sec. 5: what the paper's evidence cannot test
    untestable,
)


def by_name(functions: Iterable[Callable]) -> dict[str, Check]:
    """The checks of ``functions`` by their names in the register.

    Parameters
    ----------
    functions : iterable of callable
        Functions marked with :func:`escapement.paper.checks.check`.

    Returns
    -------
    dict of str to Check
        Each function's :class:`~escapement.paper.checks.Check`, in the order given.

    Raises
    ------
    ValueError
        If a function is not marked as a check, or two carry the same name.
    """
    checks: dict[str, Check] = {}
    for function in functions:
        spec = getattr(function, "check", None)
        if not isinstance(spec, Check):
            raise ValueError(f"{function.__qualname__} is not marked as a check of the register")
        if spec.name in checks:
            raise ValueError(f"two checks are named '{spec.name}'")
        checks[spec.name] = spec
    return checks


#: the register's checks by name, as the claims engine looks them up
CHECKS: dict[str, Check] = by_name(REGISTERED)
