"""The recorded axes of Figs. 3-5 against the tick labels of the paper's text, parsed here on their own: every
number on the lines of a figure's block is one tick label of one recorded axis of that figure, and the other way
round. Where the paper's text file is at hand (its path in ``ESCAPEMENT_PAPER_TEXT``), the recorded lines are
compared with it verbatim."""

from __future__ import annotations

import os
import re
from collections import Counter
from decimal import Decimal
from pathlib import Path

import pytest

from escapement.paper.printed_axes import PANELS, TICK_LINES, Axis, panel, panels_of

NUMBER = re.compile(r"^-?\d+(\.\d+)?$")
#: the lines of the paper's text each figure's tick labels stand on (first, last), read off the text
BLOCKS = {"3": (263, 423), "4": (425, 477), "5": (479, 547)}
#: page numbers of the paper (1001-1010) stand alone between the labels of Fig. 5
PAGE_NUMBERS = {str(n) for n in range(1001, 1011)}


def numbers(line: str) -> list[str]:
    return [token for token in line.split() if NUMBER.match(token) and token not in PAGE_NUMBERS]


@pytest.mark.parametrize("figure", ["3", "4", "5"])
def test_every_tick_label_of_a_figure_belongs_to_exactly_one_recorded_axis(figure):
    recorded = Counter(t for p in panels_of(figure) for axis in (p.x, p.y) for t in axis.ticks)
    first, last = BLOCKS[figure]
    assert recorded == Counter(token for n, line in TICK_LINES.items() if first <= n <= last for token in numbers(line))


@pytest.mark.parametrize("p", PANELS, ids=lambda p: f"fig{p.figure}-{p.name}")
def test_each_axis_cites_lines_that_show_its_labels(p):
    for axis in (p.x, p.y):
        shown = {token for n in axis.lines for token in numbers(TICK_LINES[n])}
        assert set(axis.ticks) <= shown, (axis.label, set(axis.ticks) - shown)
        for n in axis.lines:
            assert set(numbers(TICK_LINES[n])) & set(axis.ticks), (axis.label, n)
        first, last = BLOCKS[p.figure]
        assert all(first <= n <= last for n in axis.lines)


# (figure, panel): (x low, x high, x step), (y low, y high, y step), as read off the labels
EXPECTED = {
    ("3", "a/velocity"): ((0, 50, 10), (0.95, 1.3, 0.05)), ("3", "a/period"): ((0, 50, 10), (6.283, 6.2846, 0.0002)),
    ("3", "a/amplitude"): ((0, 60, 10), (1.0, 1.4, 0.05)), ("3", "b/velocity"): ((0, 50, 10), (0.5, 3.0, 0.5)),
    ("3", "b/period"): ((0, 50, 10), (6.2826, 6.2834, 0.0001)), ("3", "b/amplitude"): ((0, 60, 10), (0.5, 3.0, 0.5)),
    ("4", "velocity"): ((80, 87, 1), (-0.1, 0.9, 0.1)), ("4", "acceleration"): ((81, 85, 1), (-0.1, 0.9, 0.1)),
    ("5", "a"): ((-5, 5, 5), (-1.5, 1.5, 0.5)), ("5", "b"): ((-1, 1, 0.5), (-1, 1, 0.2)),
    ("5", "c"): ((-1, 1, 0.5), (-3, 4, 1)),
}


def test_every_panel_is_recorded_once_with_its_limits_and_steps_and_only_fig4_s_time_axes_are_not_scored():
    assert sorted((p.figure, p.name) for p in PANELS) == sorted(EXPECTED)
    for key, expected in EXPECTED.items():
        p = panel(*key)
        for axis, (low, high, step) in zip((p.x, p.y), expected):
            assert (axis.low, axis.high) == (low, high) and axis.step == pytest.approx(step, rel=1e-12), key
    unscored = {(p.figure, p.name, name) for p in PANELS for name, a in p.axes.items() if not a.scored}
    assert unscored == {("4", "velocity", "x"), ("4", "acceleration", "x")}


@pytest.mark.parametrize("ticks", [("0", "0.5", "1.5"), ("1", "0.5", "0")], ids=["uneven", "downwards"])
def test_uneven_tick_labels_are_refused(ticks):
    with pytest.raises(ValueError, match="evenly spaced"):
        Axis("y", ticks, (1,))


def test_period_labels_split_into_two_evenly_spaced_axes_in_one_way_only():
    """Eighteen period labels of Fig. 3: one axis by 0.0002, one by 0.0001, each contiguous."""
    labels = Counter(t for n, line in TICK_LINES.items() if 263 <= n <= 423 for t in numbers(line)
                     if t.startswith("6.28"))
    assert sum(labels.values()) == 18
    values = sorted(Decimal(t) for t in labels.elements())
    splits = []
    for a_low in sorted(set(values)):
        for b_low in sorted(set(values)):
            a = [a_low + Decimal("0.0002") * i for i in range(9)]
            b = [b_low + Decimal("0.0001") * i for i in range(9)]
            if sorted(a + b) == values:
                splits.append((a[0], a[-1], b[0], b[-1]))
    assert splits == [(Decimal("6.2830"), Decimal("6.2846"), Decimal("6.2826"), Decimal("6.2834"))]


def test_the_recorded_lines_are_the_paper_s_verbatim_and_no_line_of_a_figure_block_with_a_number_is_left_out():
    path = os.environ.get("ESCAPEMENT_PAPER_TEXT")
    if not path:
        pytest.skip("ESCAPEMENT_PAPER_TEXT does not name the paper's text file")
    text = Path(path).read_text(encoding="utf-8").splitlines()
    for n, line in TICK_LINES.items():
        assert text[n - 1].strip() == line, n
    for figure, (first, last) in BLOCKS.items():
        found = {n for n in range(first, last + 1) if numbers(text[n - 1]) and not text[n - 1].startswith("(")}
        recorded = {n for n in TICK_LINES if first <= n <= last and numbers(TICK_LINES[n])}
        assert found == recorded, figure
