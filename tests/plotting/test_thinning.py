"""The thinning rule keeps every extreme and bounds what a figure draws, whatever the length of the run, and the
figure says how it was thinned."""

from __future__ import annotations

import re

import matplotlib.pyplot as plt
import numpy as np

from escapement.plotting import phase_diagrams
from escapement.plotting.stylesheet import style
from escapement.plotting.thinning import PER_COLUMN, bound, decimate

#: the most bytes the SVG of one axes under 2 in wide may take: one line of at most 4 samples a column of 1/600 in,
#: at 25 bytes a vertex, and 40 kB of ticks, labels and legend
SVG_BOUND = PER_COLUMN * 600 * 2 * 25 + 40_000


def test_each_column_keeps_its_first_last_smallest_and_largest_of_ten_million_samples():
    columns, n = 2_000, 10_000_000
    y = np.random.default_rng(1).random(n)
    kept = decimate(np.arange(n, dtype=np.int32) // (n // columns), y)
    assert kept.size <= PER_COLUMN * columns and np.all(np.diff(kept) > 0) and {0, n - 1} <= set(kept.tolist())
    starts = np.searchsorted(kept, np.arange(columns) * (n // columns))
    assert np.array_equal(np.minimum.reduceat(y[kept], starts), y.reshape(columns, -1).min(axis=1))
    assert np.array_equal(np.maximum.reduceat(y[kept], starts), y.reshape(columns, -1).max(axis=1))


def test_a_break_in_a_line_is_kept_and_the_samples_beside_it():
    """A break (NaN, a column of its own as a figure gives it) splits its column: the last sample before it kept."""
    y = np.array([0.0, 3.0, np.nan, -1.0, 5.0, 2.0, 1.0, 4.0])
    assert decimate(np.array([0, 0, -2, 0, 0, 0, 0, 0]), y).tolist() == [0, 1, 2, 3, 4, 7]


def test_a_figure_of_200000_noisy_samples_writes_a_bounded_svg_and_says_how_it_was_thinned(tmp_path):
    t = np.linspace(0.0, 100.0, 200_001)
    y = np.sin(t) + 0.01 * np.random.default_rng(2).standard_normal(t.size)
    with style():
        fig, ax = plt.subplots(figsize=(2.4, 1.8), layout="constrained")
        (line,) = ax.plot(t, y)
        bound(fig)
        fig.savefig(tmp_path / "f.svg")
    assert (tmp_path / "f.svg").stat().st_size < SVG_BOUND
    assert line.get_ydata().max() == y.max() and line.get_ydata().min() == y.min() and line.get_xdata()[-1] == 100.0
    title = fig.legends[-1].get_title().get_text().replace("\n", " ")
    assert re.fullmatch(r"Drawn from 1 of every \d+ samples \(200,001 as [\d,]+\), each 1/600-inch column's first, "
                        r"last, smallest and largest kept: every extreme", title), title


def test_a_phase_diagram_of_more_samples_than_the_vector_limit_is_drawn_as_a_raster(datasets):
    fig = phase_diagrams({"a": datasets.phase(n=80)}, "Long")  # 32,400 samples and 160 impacts' breaks
    with style():
        note = bound(fig)
    assert note == fig.legends[-1].get_title().get_text().split("\n")[-1]
    assert note == "32,560 vertices drawn as a raster of 150 dpi, every one rendered"
    assert fig.axes[0].lines[0].get_rasterized() and not fig.axes[0].lines[1].get_rasterized()
