import hashlib

import numpy as np
from matplotlib.figure import Figure

from escapement.io.scenes import phase_scene, poincare_scene, shock_scene
from escapement.plotting.paper_figures import fig3, fig4, fig5
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
