"""The scene figures draw any number of panels, the caller's title, each panel's own parameters, the given axes
exactly, and a legend of only what is drawn; the words on them (values with the quantities table's symbols and units,
releases, outcomes)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from escapement.model.quantities import quantity
from escapement.plotting import phase_diagrams, poincare_map, shock_detail
from escapement.plotting.captions import outcome, quantity_value, release


def _legend(fig) -> list[str]:
    return [t.get_text() for legend in fig.legends for t in legend.get_texts() if t.get_text().strip()]


def _plain(text: str) -> str:
    return text.replace("\u00a0", " ").replace("\u2212", "-")


def test_a_poincare_map_has_a_column_per_case_each_titled_by_its_case_and_its_own_force(datasets):
    forces = [0.2, 0.7, 1.5, 3.0]
    fig = poincare_map({f"{F}": datasets.poincare(F=F) for F in forces}, "A study of the force\nsecond line")
    assert len(fig.axes) == 3 * 4 and fig.get_suptitle() == "A study of the force\nsecond line"
    titles = [_plain(ax.get_title()) for ax in fig.axes[:4]]  # the first row
    assert all(title.startswith(f"({F}) F = {F:g} N") for F, title in zip(forces, titles))
    # a study of one case c, or of one spring constant, still says which it is: by its case, or its letter and K
    assert _plain(poincare_map({"c": datasets.poincare(F=0.75, x0=-2.0)}, "t").axes[0].get_title()).startswith(
        "(c) F = 0.75 N, K = 1 N/m")
    assert _plain(phase_diagrams({"5": datasets.phase(K=5.0)}, "t").axes[0].get_title()).startswith(
        "(a) F = 1 N, K = 5 N/m")


@pytest.mark.parametrize("figure, axes, words", [
    (lambda d, axes: poincare_map({"a": d.poincare()}, "one\ntwo\nthree"), None, "title = .* two lines"),
    (lambda d, axes: phase_diagrams({"0.1": d.phase(K=0.1)}, "t", axes), {("5", "a"): {"x": (-5, 5, 5)}}, "no panel"),
])
def test_a_title_of_more_than_two_lines_and_axes_of_a_panel_the_figure_lacks_are_refused(datasets, figure, axes,
                                                                                           words):
    with pytest.raises(ValueError, match=words):
        figure(datasets, axes)


def test_given_axes_are_drawn_exactly_the_others_autoscaled_and_the_natural_period_only_inside_them(datasets):
    inside = poincare_map({"a": datasets.poincare(period_offset=-0.004)}, "t")
    natural = 2 * math.pi  # M = K = 1
    assert any(line.get_ydata()[0] == natural for line in inside.axes[1].lines)
    assert any("2\u03c0/\u03c9" in entry for entry in _legend(inside))
    fig = poincare_map({"a": datasets.poincare()}, "t", {"a/velocity": {"y": (0.5, 3.0, 0.5), "x": (0.0, 50.0, 10.0)}})
    assert all(line.get_ydata()[0] != natural for line in fig.axes[1].lines)  # offset 0.0125 s: outside the axes
    assert not any("2\u03c0/\u03c9" in entry for entry in _legend(fig))
    velocity, period = fig.axes[0], fig.axes[1]
    assert velocity.get_ylim() == (0.5, 3.0) and velocity.get_xlim() == (0.0, 50.0)
    assert np.diff(velocity.get_yticks()) == pytest.approx(0.5)
    low, high = period.get_ylim()
    assert low < 2 * math.pi + 0.0125 < high < 2 * math.pi + 0.03  # around the data, not the given axes


def test_the_paper_s_period_is_drawn_on_its_period_axes_widened_to_it_with_minor_ticks_apart(datasets):
    """The period Sec. 4 prints, 6.2832 s, below the run's periods: the printed step's axis reaches down to it,
    labelled every few steps with at most 5 minor ticks to a label (not one at each of ~100 steps)."""
    fig = poincare_map({"a": datasets.poincare(50)}, "t", {"a/period": {"y": (6.2956, 6.3044, 0.0002)}})
    period = fig.axes[1]
    (line,) = [line for line in period.lines if line.get_label().endswith("6.2832 s")]
    assert line.get_ydata()[0] == 6.2832
    low, high = period.get_ylim()
    assert 6.281 < low < 6.2822 and high == 6.3044  # the line clear of the axis
    assert len(period.yaxis.get_minorticklocs()) <= 5 * len(period.yaxis.get_majorticklocs())


def test_a_run_that_did_not_complete_says_so_in_its_panel_title(datasets):
    fig = phase_diagrams({"ran": datasets.phase(), "stopped": datasets.phase(outcome="stopped", x0=0.05)}, "t")
    assert "stopped after 0 of 6 cycles" in fig.axes[1].get_title()
    assert "stopped" not in fig.axes[0].get_title()
    assert _legend(fig) == ["trajectory from release", "last cycle", "impacts (velocity jumps)"]


def test_phase_diagrams_state_each_panels_parameters_and_only_what_differs_besides_f_and_k(datasets):
    panels = {f"{K:g}": datasets.phase(K=K, M=M) for K, M in ((0.1, 1.0), (1.0, 2.0), (10.0, 1.0))}
    fig = phase_diagrams(panels, "Phase diagrams")
    titles = [_plain(ax.get_title()) for ax in fig.axes]
    assert titles[1].startswith("(b) F = 1 N, K = 1 N/m, M = 2 kg\nfrom rest at x(0) = -1 m")
    assert all("b = " not in title for title in titles)  # b is the same in every panel


def test_the_shock_detail_breaks_the_velocity_at_each_impact_and_lists_each_impact(datasets):
    ds = datasets.shock(impacts=(82.0, 84.4, 86.0))
    fig = shock_detail(ds, "Shock detail")
    velocity, acceleration = fig.axes
    assert np.isnan(velocity.lines[0].get_ydata()).sum() == 3
    arrows = [a for a in acceleration.texts if a.arrow_patch is not None]
    assert len(arrows) == 2  # the impacts inside the acceleration window, 81-85 s
    listed = [_plain(entry) for entry in _legend(fig) if entry.startswith("impact at")]
    assert len(listed) == 3
    for t, j in zip(ds["impact_time"].values, ds["impulse"].values):
        assert any(f"t = {t:g} s" in entry and f"impulse {j:.3g} N s" in entry for entry in listed)


def test_a_study_s_figure_names_what_its_datasets_say_it_changed_and_the_replication_s_nothing(datasets):
    """The changes come from the datasets (their study_changes), each parameter by its symbol, above the legend;
    the title keeps its two lines."""
    said = "a3 = 0.12 m (paper: 0.1 m), a4 = -0.03 m (paper: -0.05 m); case c added (F = 0.75 N, x0 = -2 m)"
    cases = {"a": datasets.poincare(), "b": datasets.poincare(F=0.5), "c": datasets.poincare(F=0.75, x0=-2.0)}
    for ds in cases.values():
        ds.attrs["study_changes"] = said
    shock = datasets.shock()
    shock.attrs["study_changes"] = "b = 0.3 (paper: 0.1)"
    figures = [poincare_map(cases, "Poincaré map, study 'asym'"), shock_detail(shock, "Shock detail, study 'b'"),
               phase_diagrams({"0.1": datasets.phase(K=0.1)}, "Phase diagrams")]
    first, second, replication = (" ".join(_plain(legend.get_title().get_text()) for legend in fig.legends).strip()
                                  .replace("\n", " ") for fig in figures)
    assert first == ("Changed from the paper's scenes: a\u2083 = 0.12 m (paper: 0.1 m), a\u2084 = -0.03 m (paper: "
                     "-0.05 m); case c added (F = 0.75 N, x(0) = -2 m)")
    assert second == "Changed from the paper's scenes: b = 0.3 (paper: 0.1)"
    assert replication == ""
    assert all(fig.get_suptitle().count("\n") <= 1 for fig in figures)


def test_values_releases_and_outcomes_in_words(datasets):
    # the symbol and units unbroken, with the minus of the ticks; a pure number has no units
    a1 = quantity("a1")
    assert quantity_value("a1", -0.1) == f"{a1.symbol}\u00a0=\u00a0\u22120.1\u00a0{a1.unit_label}"
    assert quantity_value("b", 0.1).endswith("0.1")
    # the initial velocity only when it is not zero
    assert release(xr.Dataset({"x0": 3.0})) == "from rest at x(0)\u00a0=\u00a03\u00a0m"
    assert release(xr.Dataset({"x0": 3.0, "v0": -0.5})).endswith("with v(0)\u00a0=\u00a0\u22120.5\u00a0m/s")
    # only a run that did not complete has an outcome
    assert outcome(datasets.poincare()) is None and outcome(xr.Dataset()) is None
    assert outcome(datasets.poincare(outcome="turned_back_in_zone")) == "turned back in zone after 0 of 20 cycles"
