import numpy as np

from escapement.io.dataset import cycle_variables, dataset, event_variables, impact_variables, sample_variables
from escapement.io.provenance import DOI
from escapement.model.parameters import Parameters
from escapement.solvers.exact import solve_exact


def test_every_variable_has_units_and_a_long_name(case_b):
    run = solve_exact(case_b, 3.0, n_cycles=5)
    variables = {**cycle_variables(run), **impact_variables(run), **sample_variables(run, np.linspace(0, 5, 11), True)}
    variables.update(event_variables(run))
    for name, da in variables.items():
        assert "long_name" in da.attrs, name
        assert "units" in da.attrs or "flag_values" in da.attrs, name


def test_attributes_carry_parameters_outcome_and_provenance(case_a):
    run = solve_exact(case_a, 1.0, n_cycles=3)
    ds = dataset(run, cycle_variables(run), title="t", scene="fig3")
    assert ds.attrs["Conventions"] == "CF-1.11"
    assert DOI in ds.attrs["references"]
    assert ds.attrs["source"].startswith("escapement ")
    assert "git commit" in ds.attrs["source"]
    for key, value in case_a.as_dict().items():
        assert ds.attrs[key] == value
    assert ds.attrs["outcome"] == "completed" and ds.attrs["x0"] == 1.0


def test_impulse_and_dissipated_energy_follow_the_impact_law():
    p = Parameters(M=2.0, K=1.0, F=0.5, b=0.2, a1=-0.1, a2=0.05)
    run = solve_exact(p, 3.0, n_cycles=3)
    imp = impact_variables(run)
    vb = imp["velocity_before"].values
    assert np.allclose(imp["impulse"].values, -2.0 * 0.2 * vb, rtol=1e-14)
    assert np.allclose(imp["energy_dissipated"].values, 0.5 * 2.0 * vb**2 * (1 - 0.8**2), rtol=1e-14)
    assert np.all(np.isin(imp["impact_position"].values, [-0.1, 0.1]))
