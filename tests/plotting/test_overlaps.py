"""No legend or label covers data, and no two labels overlap, on every figure drawn from real datasets.

Each figure is drawn from small datasets computed here by the scene functions (a few cycles) and
measured on its canvas: the display boxes of the legends and texts (annotations, notes, titles, axis
labels, the suptitle) against the display positions of the data (the vertices of every line and
points every pixel along its segments, a ring around each marker, the segments of line collections,
the offsets of scatter collections, each arrow that is not a label's leader) and the areas of meshes
and patches, all clipped to their axes.
"""

from __future__ import annotations

import itertools

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.collections import LineCollection, PathCollection, PolyCollection, QuadMesh
from matplotlib.figure import Figure
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

from escapement import Parameters
from escapement.pipeline.simulate import (
    escapement_error_scene,
    existence_scene,
    long_run_scene,
    phase_scene,
    poincare_scene,
    shock_scene,
    stability_chunk_scene,
)
from escapement.plotting import (
    escapement_error,
    existence_map,
    fig3,
    fig4,
    fig5,
    long_run,
    stability_map,
    work_precision,
)
from escapement.studies.benchmark import METHODS
from escapement.studies.benchmark import work_precision as work_precision_rows


def paper_parameters(F: float, K: float = 1.0) -> Parameters:
    """Sec. 4: M = 1 kg, b = 0.1, a1 = -0.1 m, a2 = 0.05 m, symmetric geometry."""
    return Parameters(M=1.0, K=K, F=F, b=0.1, a1=-0.1, a2=0.05)


#: a box and what it covers must share more than this (pixels, each way) to count as overlapping
TOLERANCE = 0.5


def _along(xy: np.ndarray, step: float = 1.0) -> np.ndarray:
    """The vertices of a polyline in display coordinates and points every ``step`` pixels between
    them; a NaN vertex breaks the line, as it does on the canvas."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    a, b = xy[:-1], xy[1:]
    ok = np.isfinite(a).all(axis=1) & np.isfinite(b).all(axis=1)
    a, b = a[ok], b[ok]
    n = np.maximum(1, np.ceil(np.hypot(*(b - a).T) / step)).astype(int)
    s = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)  # 0, 1/k, ..., (k-1)/k per segment
    start = np.repeat(a, n, axis=0)
    points = start + s[:, None] * (np.repeat(b, n, axis=0) - start)
    return np.vstack([points, xy[np.isfinite(xy).all(axis=1)]])


def _ring(xy: np.ndarray, radius: float) -> np.ndarray:
    """Points on a circle of ``radius`` pixels around each point: where a marker is drawn."""
    angles = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    offsets = radius * np.column_stack([np.cos(angles), np.sin(angles)])
    return (xy[:, None, :] + offsets[None, :, :]).reshape(-1, 2)


def _inside(points: np.ndarray, box: Bbox) -> np.ndarray:
    return points[(points[:, 0] > box.x0) & (points[:, 0] < box.x1) & (points[:, 1] > box.y0) & (points[:, 1] < box.y1)]


def _overlap(a: Bbox, b: Bbox) -> bool:
    return (min(a.x1, b.x1) - max(a.x0, b.x0) > TOLERANCE) and (min(a.y1, b.y1) - max(a.y0, b.y0) > TOLERANCE)


def data_of(fig: Figure, renderer) -> tuple[list[tuple[str, np.ndarray]], list[tuple[str, Bbox]]]:
    """The data drawn in every axes: (name, display points) and (name, display area), clipped to the axes."""
    points, areas = [], []
    px_per_pt = fig.dpi / 72
    for i, ax in enumerate(fig.axes):
        clip = ax.bbox
        here = []
        for line in ax.lines:
            if not line.get_visible():
                continue
            xy = line.get_transform().transform(line.get_xydata())
            if line.get_linestyle() not in ("None", "", " "):
                here.append((f"axes {i} line {line.get_label()!r}", _along(xy)))
            if line.get_marker() not in (None, "None", "", " "):
                finite = xy[np.isfinite(xy).all(axis=1)]
                here.append((f"axes {i} markers {line.get_label()!r}",
                             np.vstack([finite, _ring(finite, line.get_markersize() / 2 * px_per_pt)])))
        for coll in ax.collections:
            if isinstance(coll, LineCollection):
                segs = [_along(coll.get_transform().transform(s)) for s in coll.get_segments() if len(s)]
                if segs:
                    here.append((f"axes {i} segments {coll.get_label()!r}", np.vstack(segs)))
            elif isinstance(coll, PathCollection) and len(coll.get_offsets()):
                here.append((f"axes {i} offsets {coll.get_label()!r}",
                             coll.get_offset_transform().transform(coll.get_offsets())))
            elif isinstance(coll, QuadMesh | PolyCollection):
                areas.append((f"axes {i} mesh", Bbox.intersection(coll.get_window_extent(renderer), clip)))
        for patch in ax.patches:
            areas.append((f"axes {i} patch {patch.get_label()!r}",
                          Bbox.intersection(patch.get_window_extent(renderer), clip)))
        for text in ax.texts:  # an arrow without text is data (an impulse); with text, a label's leader
            if isinstance(text, Annotation) and not text.get_text() and text.arrow_patch is not None:
                areas.append((f"axes {i} arrow", Bbox.intersection(text.arrow_patch.get_window_extent(renderer), clip)))
        for name, xy in here:
            xy = xy[np.isfinite(xy).all(axis=1)]
            kept = xy[(xy[:, 0] >= clip.x0) & (xy[:, 0] <= clip.x1) & (xy[:, 1] >= clip.y0) & (xy[:, 1] <= clip.y1)]
            points.append((name, kept))
    return points, [(name, box) for name, box in areas if box is not None]


def _text_box(text: Text, renderer) -> Bbox:
    box = Text.get_window_extent(text, renderer)  # the text alone, not an annotation's arrow
    patch = text.get_bbox_patch()
    return Bbox.union([box, patch.get_window_extent(renderer)]) if patch is not None else box


def labels_of(fig: Figure, renderer) -> list[tuple[str, Bbox]]:
    """Every legend and every non-empty text of the figure and its axes, with its display box."""
    labels = [(f"figure legend {k}", legend.get_window_extent(renderer)) for k, legend in enumerate(fig.legends)]
    texts = [("suptitle" if t is fig._suptitle else "figure text", t) for t in fig.texts]
    for i, ax in enumerate(fig.axes):
        if ax.get_legend() is not None:
            labels.append((f"axes {i} legend", ax.get_legend().get_window_extent(renderer)))
        texts += [(f"axes {i} text", t) for t in ax.texts]
        texts += [(f"axes {i} title", t) for t in (ax.title, ax._left_title, ax._right_title)]
        texts += [(f"axes {i} axis label", t) for t in (ax.xaxis.label, ax.yaxis.label)]
    for name, text in texts:
        if text.get_visible() and text.get_text().strip():
            labels.append((f"{name} {text.get_text()[:30]!r}", _text_box(text, renderer)))
    return labels


def collisions(fig: Figure) -> list[str]:
    """What covers what on the drawn figure: a label over data, two labels over each other, a label
    outside the figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    points, areas = data_of(fig, renderer)
    labels = labels_of(fig, renderer)
    found = []
    for name, box in labels:
        for data, xy in points:
            covered = _inside(xy, box.padded(-TOLERANCE))
            if len(covered):
                found.append(f"{name} covers {len(covered)} point(s) of {data}, e.g. {covered[0].round(1)}")
        found += [f"{name} covers {data}" for data, area in areas if _overlap(box, area)]
        if not fig.bbox.padded(TOLERANCE).contains(box.x0, box.y0) or not fig.bbox.padded(TOLERANCE).contains(
            box.x1, box.y1
        ):
            found.append(f"{name} reaches outside the figure")
    for (a, box_a), (b, box_b) in itertools.combinations(labels, 2):
        if _overlap(box_a, box_b):
            found.append(f"{a} overlaps {b}")
    return found


# ---- the check itself finds what it is for


def test_the_check_finds_a_legend_over_data_and_overlapping_labels():
    fig, ax = plt.subplots()
    x = np.linspace(0, 1, 50)
    ax.plot(x, np.ones_like(x), label="flat line at the top")
    ax.set_ylim(0, 1.05)
    ax.legend(loc="upper center")  # on the line
    ax.text(0.5, 0.5, "one label", transform=ax.transAxes, ha="center")
    ax.text(0.5, 0.5, "another label", transform=ax.transAxes, ha="center")
    found = collisions(fig)
    plt.close(fig)
    assert any("legend" in f and "covers" in f and "flat line" in f for f in found)
    assert any("'one label'" in f and "overlaps" in f and "'another label'" in f for f in found)


def test_the_check_finds_a_segment_crossing_a_label_between_its_vertices():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], "-", label="diagonal")  # two vertices, both far from the label
    ax.text(0.5, 0.5, "crossed", transform=ax.transAxes, ha="center", va="center")
    found = collisions(fig)
    plt.close(fig)
    assert any("'crossed'" in f and "diagonal" in f for f in found)


def test_the_check_finds_a_label_over_a_mesh_and_a_label_outside_the_figure():
    fig, ax = plt.subplots()
    ax.pcolormesh(np.arange(4.0), np.arange(3.0), np.ones((2, 3)))
    ax.text(0.5, 0.5, "on the mesh", transform=ax.transAxes)
    ax.text(1.0, 1.0, "off the edge of the figure", transform=fig.transFigure)
    found = collisions(fig)
    plt.close(fig)
    assert any("'on the mesh'" in f and "mesh" in f for f in found)
    assert any("'off the edge" in f and "outside the figure" in f for f in found)


# ---- every figure of the project, from real datasets


def _fig3():
    return fig3({"a": poincare_scene(paper_parameters(F=1.0), 1.0, 12),
                 "b": poincare_scene(paper_parameters(F=0.5), 3.0, 12)})


def _fig4():
    return fig4(shock_scene(paper_parameters(F=0.5), 3.0, (80.0, 87.0), (81.0, 85.0), 50))


def _fig4_one_impact():  # the adopted reading: K = 0.1 N/m from -3 m, one impact and its impulse arrow
    return fig4(shock_scene(paper_parameters(F=0.5, K=0.1), -3.0, (80.0, 87.0), (81.0, 85.0), 50))


def _escapement_error():
    zones = {"paper": [-0.1, 0.05], "before": [-0.2, -0.05], "after": [0.05, 0.2]}
    return escapement_error(escapement_error_scene(paper_parameters(F=1.0), [0.1, 0.5, 2.0], zones))


def _fig5():
    return fig5({f"{K:g}": phase_scene(paper_parameters(F=0.5, K=K), 1.0, 8, 60) for K in (0.1, 1.0, 10.0)})


def _fig5_stopped():  # a run that stops: its outcome is written in the panel
    return fig5({"1": phase_scene(paper_parameters(F=1.0), 0.05, 3, 50),
                 "10": phase_scene(paper_parameters(F=0.5, K=10.0), 1.0, 4, 50)})


def _work_precision():
    settings = {method: [] for method in METHODS}
    settings.update({"RK45": [1e-3, 1e-9], "DOP853": [1e-3, 1e-9], "LSODA": [1e-6], "Radau": [1e-3],
                     "CVODE-Adams": [1e-6], "CVODE-BDF": [1e-6], "naive-RK4": [0.1, 0.01]})
    return work_precision(work_precision_rows(paper_parameters(F=1.0), 1.0, 5, settings, 0.001, 1), "a")


def _long_run():
    return long_run(long_run_scene(paper_parameters(F=1.0), 1.0, 300, "DOP853", 1e-12, 10)[0])


def _stability_map():
    model = {"M": 1.0, "K": 1.0, "a1": -0.1, "a2": 0.05}
    b = (np.arange(10) + 0.5) * 0.2  # cell centres of (0, 2): beyond b = 1 no cycle
    return stability_map(stability_chunk_scene(model, b, np.linspace(0.01, 2.0, 6), speed_sample=2)[0])


def _existence_map():
    model = {"M": 1.0, "K": 1.0, "b": 0.1, "a1": -0.1, "a2": 0.05}
    block = {"a3": {"start": 0.0, "stop": 0.25, "n": 12}, "F": {"start": 0.0, "stop": 0.014, "n": 8}, "x0": -1.0,
             "n_cycles": 60, "tolerance": 1e-9}
    return existence_map(existence_scene(model, block))


FIGURES = {"fig3": _fig3, "fig4": _fig4, "fig4 one impact": _fig4_one_impact, "escapement_error": _escapement_error,
           "fig5": _fig5, "fig5 stopped": _fig5_stopped,
           "work_precision": _work_precision, "long_run": _long_run, "stability_map": _stability_map,
           "existence_map": _existence_map}


@pytest.mark.parametrize("name", list(FIGURES))
def test_no_label_covers_data_or_another_label(name):
    fig = FIGURES[name]()
    try:
        found = collisions(fig)
    finally:
        plt.close(fig)
    assert not found, "\n".join(found)
