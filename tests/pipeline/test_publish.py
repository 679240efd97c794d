"""Publishing the tracked files: copied only where what they show changed, by the rule CI checks too.

A figure is compared as an image (matplotlib's ``compare_images``) against an RMS tolerance, its PDF
goes with its PNG, and a document is compared with its numbers read at their printed digits.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

from escapement.paper.checks import fmt
from escapement.pipeline.publish import (
    DOCUMENT_DIGIT_TOLERANCE,
    FIGURE_RMS_TOLERANCE,
    check,
    compare_documents,
    compare_figures,
    main,
    mark_stale,
    publish,
)
from escapement.plotting import save_figure

CYCLES = np.arange(1, 201)


def draw(folder: Path, name: str, scale: float = 1.0, label: str = "DOP853 rtol 1e-12") -> tuple[Path, Path]:
    """A figure like the long-run one (two error curves with markers on log axes, a legend), its
    second curve multiplied by ``scale``; saved as ``name``.png and .pdf in ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.loglog(CYCLES, 1e-16 * CYCLES, marker=".", ms=3, label="exact solver")
    ax.loglog(CYCLES, scale * 3e-12 * CYCLES**1.5, marker=".", ms=3, label=label)
    ax.set_xlabel("Number of cycles")
    ax.legend()
    png, pdf = folder / f"{name}.png", folder / f"{name}.pdf"
    save_figure(fig, png, pdf)
    return png, pdf


@pytest.fixture(scope="module")
def drawings(tmp_path_factory) -> dict[str, tuple[Path, Path]]:
    """The committed drawing and its variants: rounding-level, sub-pixel, a few per cent, a label."""
    folder = tmp_path_factory.mktemp("drawings")
    return {
        "committed": draw(folder, "committed"),
        "rounding": draw(folder, "rounding", scale=1 + 1e-15),
        "subpixel": draw(folder, "subpixel", scale=1 + 3e-5),
        "per_cent": draw(folder, "per_cent", scale=1.03),
        "label": draw(folder, "label", label="DOP853 rtol 1e-13"),
    }


def tracked_copy(drawings, folder: Path) -> tuple[Path, Path]:
    """The committed drawing as the tracked figures/fig.png and .pdf under ``folder``."""
    (folder / "figures").mkdir(parents=True)
    png, pdf = folder / "figures/fig.png", folder / "figures/fig.pdf"
    shutil.copyfile(drawings["committed"][0], png)
    shutil.copyfile(drawings["committed"][1], pdf)
    os.utime(png, (1, 1))
    return png, pdf


def publish_drawing(drawings, variant: str, folder: Path) -> tuple[bool, bool, str]:
    """Publish ``variant`` over the committed drawing: whether the PNG and the PDF were replaced, and the log."""
    png, pdf = tracked_copy(drawings, folder)
    log, readme = folder / "publish.log", folder / "README.md"
    readme.write_text("text")  # a document after the figure, whose name the PDF must not take
    publish([*map(str, drawings[variant]), str(readme)], [str(png), str(pdf), str(readme)], str(log))
    committed = drawings["committed"]
    replaced = (png.read_bytes() != committed[0].read_bytes(), pdf.read_bytes() != committed[1].read_bytes())
    if replaced[0]:
        assert png.read_bytes() == drawings[variant][0].read_bytes()
    if replaced[1]:
        assert pdf.read_bytes() == drawings[variant][1].read_bytes()
    assert png.stat().st_mtime > 1  # newer than its source either way, for Snakemake
    return *replaced, log.read_text()


@pytest.mark.parametrize("variant", ["rounding", "subpixel"])
def test_a_figure_that_differs_by_rounding_is_left_in_place(drawings, variant, tmp_path):
    png_replaced, pdf_replaced, log = publish_drawing(drawings, variant, tmp_path)
    assert not png_replaced and not pdf_replaced
    assert f"{tmp_path / 'figures/fig.png'}: unchanged (image RMS against {FIGURE_RMS_TOLERANCE:g}; " in log
    assert f"{tmp_path / 'figures/fig.pdf'}: unchanged (goes with {tmp_path / 'figures/fig.png'}; " in log


def test_a_sub_pixel_difference_is_measured_and_within_the_tolerance(drawings):
    """A curve moved by 3e-5 (relative), a fraction of a pixel, changes some antialiased pixels and the
    PDF's bytes: neither is news."""
    committed, moved = drawings["committed"], drawings["subpixel"]
    assert committed[0].read_bytes() != moved[0].read_bytes()
    assert committed[1].read_bytes() != moved[1].read_bytes()
    comparison = compare_figures(committed[0], moved[0])
    assert 0 < comparison.difference <= FIGURE_RMS_TOLERANCE and comparison.within


@pytest.mark.parametrize("variant", ["per_cent", "label"])
def test_a_figure_that_differs_visibly_is_published_with_its_pdf(drawings, variant, tmp_path):
    png_replaced, pdf_replaced, log = publish_drawing(drawings, variant, tmp_path)
    assert png_replaced and pdf_replaced
    comparison = compare_figures(drawings["committed"][0], drawings[variant][0])
    assert comparison.difference > FIGURE_RMS_TOLERANCE and not comparison.within
    assert f"RMS {comparison.difference:.4f}" in log
    assert f"fig.pdf: updated from {drawings[variant][1]} (goes with {tmp_path / 'figures/fig.png'}" in log


def test_figures_of_another_size_or_unreadable_are_published(drawings, tmp_path):
    fig, ax = plt.subplots(figsize=(4.0, 3.5))
    small = tmp_path / "other.png"
    save_figure(fig, small, tmp_path / "other.pdf")
    comparison = compare_figures(drawings["committed"][0], small)
    assert not comparison.within and comparison.difference is None and "size" in comparison.detail
    broken = tmp_path / "broken.png"
    broken.write_bytes(b"not an image")
    assert not compare_figures(drawings["committed"][0], broken).within


def test_a_pdf_is_decided_by_its_png_and_refused_without_one(drawings, tmp_path):
    with pytest.raises(ValueError, match=r"targets: '.*fig\.pdf' has no PNG of the same figure among them"):
        publish([str(drawings["per_cent"][1])], [str(tmp_path / "fig.pdf")], str(tmp_path / "log"))
    refusal = r"targets: '.*fig\.svg' has no comparison rule: a tracked file must end in \.png, \.pdf or \.md"
    with pytest.raises(ValueError, match=refusal):
        publish([str(drawings["per_cent"][0])], [str(tmp_path / "fig.svg")], str(tmp_path / "log"))


def document(velocity_error: float, time_error: float) -> str:
    """A document with two numbers printed as the generated documents print them (``fmt``, 2 digits)."""
    return (f"DOP853 at rtol 1e-12 reaches {fmt(velocity_error, 2)} (velocity)\n"
            f"and {fmt(time_error, 2)} (impact time) over 1 000 000 cycles.\n")


def publish_document(old: str, new: str, folder: Path) -> tuple[bool, str]:
    source, target = folder / "results/README.md", folder / "README.md"
    source.parent.mkdir()
    source.write_text(new)
    target.write_text(old)
    publish([str(source)], [str(target)], str(folder / "publish.log"))
    assert target.read_text() in (old, new)
    return target.read_text() == new and new != old, (folder / "publish.log").read_text()


def test_a_document_whose_number_moved_in_its_17th_digit_is_left(tmp_path):
    value = 1.3456789012345678e-14
    moved = np.nextafter(value, 1.0)
    assert moved != value and fmt(moved, 2) == fmt(value, 2)
    replaced, log = publish_document(document(value, 2.5e-16), document(moved, 2.5e-16), tmp_path)
    assert not replaced and "README.md: unchanged" in log


def test_a_number_printed_with_other_digits_but_the_same_value_is_left(tmp_path):
    old, new = document(1.3e-14, 2.5e-16), document(1.3e-14, 2.5e-16).replace("1.3e-14", "1.30e-14")
    assert old != new
    replaced, log = publish_document(old, new, tmp_path)
    assert not replaced and "7 numbers, 0 printed differently" in log


@pytest.mark.parametrize("new", [document(1.7e-14, 2.5e-16), document(1.3e-14, 2.6e-16),
                                 document(1.3e-14, 2.5e-16).replace("1.3e-14", "1.27e-14"),
                                 document(1.3e-14, 2.5e-16).replace("impact time", "period")])
def test_a_document_that_prints_another_number_or_text_is_published(tmp_path, new):
    replaced, log = publish_document(document(1.3e-14, 2.5e-16), new, tmp_path)
    assert replaced and "README.md: updated from" in log


def test_numbers_are_compared_in_units_of_their_last_printed_digit():
    assert DOCUMENT_DIGIT_TOLERANCE == 0
    comparison = compare_documents("a 1.3e-14 b 0.25", "a 1.3e-14 b 0.28", "x.md")
    assert comparison.difference == 3 and "first 0.25 -> 0.28" in comparison.detail
    assert compare_documents("1e6 and 1.0e+6 and 10", "1.0e6 and 1e6 and 10.00", "x.md").within
    assert not compare_documents("-1e-16", "1e-16", "x.md").within  # a sign is text
    assert not compare_documents("F = 1 N\n", "F = 1 N\nmore\n", "x.md").within


def test_the_unchanged_file_keeps_its_bytes_and_inode(tmp_path):
    source, target = tmp_path / "new.md", tmp_path / "README.md"
    source.write_text("text 1.5")
    target.write_text("text 1.5")
    os.utime(target, (1, 1))
    inode = target.stat().st_ino
    publish([str(source)], [str(target)], str(tmp_path / "publish.log"))
    assert target.stat().st_ino == inode and target.stat().st_mtime > 1


def test_a_missing_target_is_created(tmp_path):
    source = tmp_path / "s.md"
    source.write_text("x")
    publish([str(source)], [str(tmp_path / "sub/t.md")], str(tmp_path / "log"))
    assert (tmp_path / "sub/t.md").read_text() == "x"
    assert "no version in place to compare with" in (tmp_path / "log").read_text()


def test_mark_stale_dates_files_back_without_touching_their_content(tmp_path):
    path = tmp_path / "README.md"
    path.write_text("readme")
    mark_stale([str(path), str(tmp_path / "absent.md")])
    assert path.stat().st_mtime == 0 and path.read_text() == "readme"


def git(repo: Path, *args: str) -> None:
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@example.org", *args], cwd=repo, check=True,
                   capture_output=True)


VARIANTS = ["rounding", "subpixel", "per_cent", "label"]
NUMBERS = {"same": document(1.3e-14, 2.5e-16).replace("1.3e-14", "1.30e-14"), "other": document(1.7e-14, 2.5e-16)}


@pytest.fixture
def repository(drawings, tmp_path, monkeypatch) -> Path:
    """A git work tree with committed figures (one per variant) and documents, at the committed versions."""
    repo = tmp_path / "repo"
    (repo / "figures").mkdir(parents=True)
    for variant in VARIANTS:
        shutil.copyfile(drawings["committed"][0], repo / f"figures/{variant}.png")
        shutil.copyfile(drawings["committed"][1], repo / f"figures/{variant}.pdf")
    for name in NUMBERS:
        (repo / f"{name}.md").write_text(document(1.3e-14, 2.5e-16))
    git(repo, "init", "--quiet")
    git(repo, "add", ".")
    git(repo, "commit", "--quiet", "-m", "committed")
    monkeypatch.chdir(repo)
    return repo


def test_the_ci_check_agrees_with_publish(drawings, repository, tmp_path, capsys):
    sources, targets = [], []
    for variant in VARIANTS:
        for i, ext in enumerate(("png", "pdf")):
            sources.append(str(drawings[variant][i]))
            targets.append(f"figures/{variant}.{ext}")
    for name, text in NUMBERS.items():
        (tmp_path / f"{name}.md").write_text(text)
        sources.append(str(tmp_path / f"{name}.md"))
        targets.append(f"{name}.md")
    before = {target: Path(target).read_bytes() for target in targets}
    publish(sources, targets, str(tmp_path / "publish.log"))
    published = {target for target in targets if Path(target).read_bytes() != before[target]}
    assert published == {"figures/per_cent.png", "figures/per_cent.pdf", "figures/label.png", "figures/label.pdf",
                         "other.md"}
    # the files publish kept, written over with what it was given, as a run that bypassed it would leave them
    for source, target in zip(sources, targets, strict=True):
        shutil.copyfile(source, target)
    comparisons = check(targets)
    assert [c.path for c in comparisons] == targets
    assert {c.path for c in comparisons if not c.within} == published
    assert main(["--check", "figures/subpixel.pdf", "same.md"]) == 0  # the PDF decided by its PNG
    assert main(["--check", *targets]) == 1
    out, err = capsys.readouterr()
    assert "figures/label.png: image RMS against" in out and "beyond the tolerance" in out
    assert "5 of 10 file(s) differ from HEAD beyond the tolerance" in err


def test_the_ci_check_refuses_a_path_that_is_not_a_file(repository):
    with pytest.raises(ValueError, match=r"paths: 'figures/absent\.png' is not a file: each path must name"):
        check(["figures/absent.png"])
