"""Every figure: no text over another or outside the figure, none inside an axes (where it could cover data), a title
of at most two lines, none under 7 pt where the article prints it; and the same figure saves to the same bytes."""

from __future__ import annotations

import hashlib
import itertools
import re
from pathlib import Path as FilePath

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.patches import PathPatch
from matplotlib.path import Path
from matplotlib.text import Text

from escapement.plotting import (escapement_error, existence_map, long_run, phase_diagrams, poincare_map, save_figure,
                                 shock_detail, stability_map, work_precision)
from escapement.plotting.stylesheet import style

#: two boxes must share more than this (pixels, each way) to count as overlapping
TOLERANCE = 0.5
TITLE = "A figure of the escapement model (a paper, Fig. 9)\nM = 1 kg, b = 0.1, a\u2081 = \u22120.1 m, a\u2082 = 0.05 m"

#: what a study changed, long enough to take several lines above the legend
CHANGES = ("M = 2 kg (paper: 1 kg), b = 0.3 (paper: 0.1), a1 = -0.12 m (paper: -0.1 m), a2 = 0.07 m (paper: 0.05 m), "
           "a3 = 0.12 m (paper: 0.1 m), a4 = -0.03 m (paper: -0.05 m); case c added (F = 0.75 N, x0 = -2 m)")


def _study(ds):
    ds.attrs["study_changes"] = CHANGES
    return ds


#: each figure at its most crowded: the most panels, a run that stopped, and (where a figure shows it) a study's
#: changes above the legend; the maps with the title they compose themselves
FIGURES = {
    "poincare_map": lambda d: poincare_map({"a": _study(d.poincare()), "b": _study(d.poincare(F=0.5, x0=-3.0)),
                                            "c": _study(d.poincare(outcome="stopped", x0=0.05))}, TITLE),
    "shock_detail": lambda d: shock_detail(_study(d.shock(impacts=(82.0, 84.4, 86.0))), TITLE),
    "phase_diagrams": lambda d: phase_diagrams({f"{K:g}": _study(d.phase(K=K)) for K in (0.1, 1.0, 10.0)}, TITLE),
    "one phase diagram": lambda d: phase_diagrams({"mine": _study(d.phase(outcome="stopped"))}, TITLE),
    "long_run": lambda d: long_run(d.long_run([1e-13] * 9, [1e-12] * 9)),
    "stability_map": lambda d: stability_map(_study(d.stability())),
    "existence_map": lambda d: existence_map(_study(d.existence())),
    "escapement_error": lambda d: escapement_error(_study(d.escapement_error())),
    "work_precision": lambda d: work_precision(d.work_precision()),
}


#: the figures the article includes, the Poincaré map with the paper's two cases
ARTICLE = {**{name: FIGURES[name] for name in ("shock_detail", "phase_diagrams", "escapement_error", "work_precision",
                                               "long_run")},
           "poincare_map": lambda d: poincare_map({"a": d.poincare(), "b": d.poincare(F=0.5, x0=-3.0)}, TITLE)}
TEMPLATE = FilePath(__file__).parents[2] / "workflow" / "templates" / "article.typ"


def collisions(fig) -> list[str]:
    """Texts and legends over each other or outside the figure, and texts inside an axes."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    texts = [("title", fig._suptitle)] + [(f"axes {i} {kind}", text) for i, ax in enumerate(fig.axes)
                                          for kind, text in (("title", ax.title), ("x label", ax.xaxis.label),
                                                             ("y label", ax.yaxis.label))]
    boxes = [(f"{name} {text.get_text()[:30]!r}", text.get_window_extent(renderer)) for name, text in texts
             if text.get_visible() and text.get_text().strip()]
    boxes += [(f"legend {k}", legend.get_window_extent(renderer)) for k, legend in enumerate(fig.legends)]
    found = [f"{a} overlaps {b}" for (a, p), (b, q) in itertools.combinations(boxes, 2)
             if min(p.x1, q.x1) - max(p.x0, q.x0) > TOLERANCE and min(p.y1, q.y1) - max(p.y0, q.y0) > TOLERANCE]
    found += [f"{name} reaches outside the figure" for name, box in boxes
              if not (fig.bbox.padded(TOLERANCE).contains(box.x0, box.y0)
                      and fig.bbox.padded(TOLERANCE).contains(box.x1, box.y1))]
    found += [f"axes {i} holds the text {t.get_text()[:30]!r}" for i, ax in enumerate(fig.axes) for t in ax.texts
              if t.get_text().strip()]
    return found


@pytest.mark.parametrize("name", list(FIGURES))
def test_no_text_covers_another_or_data_and_the_title_has_at_most_two_lines(datasets, name):
    fig = FIGURES[name](datasets)
    found = collisions(fig)
    assert fig.get_suptitle().count("\n") <= 1
    assert not found, "\n".join(found)


@pytest.mark.parametrize("name", list(ARTICLE))
def test_no_text_of_a_figure_the_article_includes_prints_under_7_pt(datasets, name):
    """The article prints each figure as wide as its text column: A4's 21 cm less the margins of its page setup.
    Every text counts, tick labels too, though they get their words only when drawn (each copies the first's size)."""
    setup = re.search(r'paper: "a4", margin: \(left: ([\d.]+)cm, right: ([\d.]+)cm', TEMPLATE.read_text())
    left, right = setup.groups()
    fig = ARTICLE[name](datasets)
    sizes = [t.get_fontsize() for t in fig.findobj(Text) if t.get_visible()]
    sizes += [0.7 * axis.get_major_ticks()[0].label1.get_fontsize() for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)
              if axis.get_scale() == "log"]  # the exponent of 10^n, which mathtext shrinks by 0.7
    assert min(sizes) * (21.0 - float(left) - float(right)) / 2.54 / fig.get_figwidth() >= 7.0


def test_a_figure_saves_to_the_same_bytes_every_time(tmp_path):
    """No date, software stamp or random id in the files: a small figure with what the stability map draws (a
    rasterised mesh with a blank cell, a hatched patch, text, a legend), drawn twice, saves to the same bytes."""
    def figure():
        with style():
            fig, ax = plt.subplots(figsize=(2.0, 1.6), layout="constrained")
            ax.pcolormesh([0.0, 1.0], [0.0, 1.0], [[0.2, np.nan], [0.5, 0.7]], shading="nearest", rasterized=True)
            ax.add_patch(PathPatch(Path([(0, 0), (1, 0), (1, 1), (0, 0)]), hatch="////", label="no cycle"))
            ax.set_title("\u03bc\u2082 measured")
            fig.legend(loc="outside lower center")
        return fig

    digests = []
    for i in range(2):
        png, pdf, svg = tmp_path / f"f{i}.png", tmp_path / f"f{i}.pdf", tmp_path / f"f{i}.svg"
        save_figure(figure(), png, pdf, svg)
        digests.append([hashlib.sha256(p.read_bytes()).hexdigest() for p in (png, pdf, svg)])
    assert digests[0] == digests[1]
    assert b"CreationDate" not in (tmp_path / "f0.pdf").read_bytes()
    assert b"<dc:date>" not in (tmp_path / "f0.svg").read_bytes()
