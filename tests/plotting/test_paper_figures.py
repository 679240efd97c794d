import hashlib

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.figure import Figure

from escapement import Parameters
from escapement.pipeline.simulate import phase_scene, poincare_scene, shock_scene
from escapement.plotting import fig3, fig4, fig5, stability_map, work_precision
from escapement.plotting.style import save_figure


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_figures_are_byte_identical_across_saves(tmp_path, case_a, case_b):
    cases = {"a": poincare_scene(case_a, 1.0, 10), "b": poincare_scene(case_b, 3.0, 10)}
    digests = []
    for i in range(2):
        png, pdf = tmp_path / f"f{i}.png", tmp_path / f"f{i}.pdf"
        save_figure(fig3(cases), png, pdf)
        digests.append((_digest(png), _digest(pdf)))
    assert digests[0] == digests[1]
    assert b"CreationDate" not in (tmp_path / "f0.pdf").read_bytes()


def test_fig4_and_fig5_draw_from_datasets(case_b):
    assert isinstance(fig4(shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 50)), Figure)
    assert isinstance(fig5({"1": phase_scene(case_b, 3.0, 3, 50)}), Figure)


def test_fig4_breaks_the_velocity_line_at_each_impact(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 50)
    line = fig4(ds).axes[0].lines[0]
    assert np.isnan(line.get_ydata()).sum() == ds.sizes["impact"]


def test_an_outcome_other_than_completed_is_written_on_the_figure(case_a):
    figure = fig5({"1": phase_scene(case_a, 0.05, 3, 50)})
    texts = [t.get_text() for t in figure.axes[0].texts]
    assert any(text.startswith("stopped:") for text in texts)


def _all_text(figure) -> str:
    texts = [t.get_text() for t in figure.texts]
    for ax in figure.axes:
        texts += [ax.get_title()] + [t.get_text() for t in ax.texts]
    for legend in figure.legends:
        texts += [t.get_text() for t in legend.get_texts()]
    return "\n".join(texts).replace("\u00a0", " ").replace("\n", " ")


def test_fig4_labels_every_impact_of_the_velocity_panel_with_its_impulse_and_energy(case_b):
    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 50)
    figure = fig4(ds)
    labels = [t.get_text() for t in figure.axes[0].texts if t.get_text().startswith("impulse")]
    v_lo, v_hi = ds["velocity_window"].values
    inside = (ds["impact_time"] >= v_lo) & (ds["impact_time"] <= v_hi)
    assert len(labels) == int(inside.sum()) >= 3
    for j, e in zip(ds["impulse"].values[inside], ds["energy_dissipated"].values[inside]):
        assert any(f"{abs(j):.4f} N s" in text and f"{e:.4f} J" in text for text in labels)


def test_each_paper_figure_states_the_readings_it_assumes(case_a, case_b):
    cases = {"a": poincare_scene(case_a, 1.0, 5), "b": poincare_scene(case_b, 3.0, 5)}
    text = _all_text(fig3(cases))
    assert "Fig. 3" in text and "released from rest at x(0) = 1 m" in text and "x(0) = 3 m" in text
    assert cases["a"][cases["a"].attrs["amplitude_variable"]].attrs["long_name"] in text  # the amplitude's definition
    text = _all_text(fig4(shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 20)))
    assert "Fig. 4" in text and all(s in text for s in ("F = 0.5 N", "K = 1 N/m", "x(0) = 3 m"))
    figure = fig5({"0.1": phase_scene(Parameters(M=1.0, K=0.1, F=0.7, b=0.1, a1=-0.1, a2=0.05), 2.0, 3, 20),
                   "1": phase_scene(case_b, 1.0, 3, 20)})
    titles = [ax.get_title().replace("\u00a0", " ") for ax in figure.axes]
    assert "F = 0.7 N" in titles[0] and "x(0) = 2 m" in titles[0]
    assert "F = 0.5 N" in titles[1] and "x(0) = 1 m" in titles[1]
    assert "Fig. 5" in _all_text(figure)


def test_a_reading_stored_in_the_dataset_is_drawn_as_it_is(case_b):
    ds = phase_scene(case_b, 1.0, 3, 20)
    ds.attrs["reading"] = "F and x(0) chosen to match the printed axes"
    assert "F and x(0) chosen to match the printed axes" in _all_text(fig5({"1": ds}))


def test_the_fixed_point_line_is_drawn_over_the_points_in_its_own_colour(case_a):
    ax = fig3({"a": poincare_scene(case_a, 1.0, 20)}).axes[0]
    data, guide = ax.lines[0], ax.lines[1]
    assert guide.get_label().startswith("fixed point of Eq. (19)")
    assert guide.get_zorder() > data.get_zorder() and guide.get_color() != data.get_color()


def _stability(b=(0.5, 0.9, 1.1, 1.5), F=(0.5, 1.0, 2.0)):
    from escapement.pipeline.simulate import stability_chunk_scene

    return stability_chunk_scene({"M": 1.0, "K": 1.0, "a1": -0.1, "a2": 0.05}, list(b), list(F), speed_sample=2)[0]


def test_the_stability_map_marks_no_cycle_apart_from_the_colour_scale():
    ds = _stability()
    figure = stability_map(ds)
    no_cycle = ~np.isfinite(ds["multiplier"].values.T)
    assert no_cycle.any() and not no_cycle.all()
    for ax in figure.axes[:2]:  # the two maps (their colour bars come after)
        (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
        assert mesh.get_rasterized()  # the cells as an image in the PDF
        drawn = np.ma.getmaskarray(mesh.get_array()).reshape(no_cycle.shape) | ~np.isfinite(
            np.ma.getdata(mesh.get_array()).reshape(no_cycle.shape))
        assert np.array_equal(drawn, no_cycle)  # no colour where there is no cycle
        (patch,) = ax.patches
        assert patch.get_hatch() and patch.get_label().startswith("no cycle")
        x0, x1 = patch.get_path().get_extents().intervalx
        assert x0 == (0.9 + 1.1) / 2 and x1 == 1.5 + (1.5 - 1.1) / 2  # the cells' edges, midway between centres
    assert any(t.get_text().startswith("no cycle") for t in figure.legends[0].get_texts())


def test_the_work_precision_legend_spells_out_the_closed_form_map(case_a):
    rows = [{"method": m, "wall_s": w, "error_velocity": 1e-10, "error_time": 1e-12}
            for m, w in (("exact", 1e-3), ("map16", 1e-5), ("DOP853", 1e-2))]
    entries = [t.get_text() for t in work_precision(rows, "a").legends[0].get_texts()]
    assert "map (16) + corrected period (23)" in entries and "map16" not in entries


@pytest.mark.parametrize("name", ["fig4", "stability_map"])
def test_labelled_and_rasterised_figures_are_byte_identical_across_saves(tmp_path, case_b, name):
    def draw():
        if name == "fig4":
            return fig4(shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 20))
        return stability_map(_stability())

    digests = []
    for i in range(2):
        png, pdf = tmp_path / f"f{i}.png", tmp_path / f"f{i}.pdf"
        save_figure(draw(), png, pdf)
        digests.append((_digest(png), _digest(pdf)))
    assert digests[0] == digests[1]


def test_a_drawn_fig5_panel_has_the_axes_its_claim_scores():
    """K = 0.1 N/m, F = 1 N from -1 m: the panel (a) of the paper prints -5 to 5 m and -1.5 to 1.5 m/s."""
    from escapement.paper.printed_axes import panel
    from escapement.pipeline.readings import scene_axes

    panels = {"0.1": phase_scene(Parameters(M=1.0, K=0.1, F=1.0, b=0.1, a1=-0.1, a2=0.05), -1.0, 60, 100)}
    claimed = scene_axes({}, None, panels)
    assert claimed == {("5", "a"): {"x": (-5.0, 5.0), "y": (-1.5, 1.5)}}  # the printed limits
    ax = fig5(panels, claimed, "caption").axes[0]
    assert (ax.get_xlim(), ax.get_ylim()) == ((-5.0, 5.0), (-1.5, 1.5))
    assert np.diff(ax.get_yticks()) == pytest.approx(panel("5", "a").y.step)
    assert np.diff(ax.get_xticks()) == pytest.approx(5.0)


def test_a_drawn_fig4_keeps_the_claimed_value_axes_after_its_labels_are_placed(case_b):
    from escapement.pipeline.readings import scene_axes

    ds = shock_scene(case_b, 3.0, (80.0, 87.0), (81.0, 85.0), 50)
    claimed = scene_axes({}, ds, {})
    figure = fig4(ds, claimed)
    for ax, name in zip(figure.axes[:2], ("velocity", "acceleration")):
        assert ax.get_ylim() == claimed[("4", name)]["y"]
        low, high = claimed[("4", name)]["y"]
        assert round(low / 0.1, 9).is_integer() and round(high / 0.1, 9).is_integer()  # on the printed ticks
