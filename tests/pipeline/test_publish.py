"""Publishing the tracked files: copied only where what they show changed, by the one rule CI's check applies.

A figure is compared as an image (matplotlib's ``compare_images``) against an RMS tolerance, its PDF goes with
its PNG, and a document is compared with its numbers read at their printed digits.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

from escapement.pipeline.publish import PUBLISHED, check, compare, publish
from escapement.plotting import save_figure

CYCLES = np.arange(1, 201)


def draw(folder: Path, name: str, scale: float = 1.0, label: str = "DOP853 rtol 1e-12") -> Path:
    """A figure like the long-run one (two error curves with markers on log axes, a legend), its second curve
    multiplied by ``scale``; saved as ``name``.png and .pdf in ``folder``; the PNG's path."""
    folder.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.loglog(CYCLES, 1e-16 * CYCLES, marker=".", ms=3, label="exact solver")
    ax.loglog(CYCLES, scale * 3e-12 * CYCLES**1.5, marker=".", ms=3, label=label)
    ax.legend()
    save_figure(fig, folder / f"{name}.png", folder / f"{name}.pdf", folder / f"{name}.svg")
    return folder / f"{name}.png"


@pytest.fixture(scope="module")
def drawings(tmp_path_factory) -> dict[str, Path]:
    """The tracked drawing (in figures/) and its variants drawn again: a sub-pixel change, a change of a few per
    cent, another label."""
    folder = tmp_path_factory.mktemp("drawings")
    found = {"tracked": draw(folder / "figures", "fig")}
    variants = {"subpixel": {"scale": 1 + 3e-5}, "per_cent": {"scale": 1.03}, "label": {"label": "DOP853 rtol 1e-13"}}
    found.update({name: draw(folder / name, "fig", **kwargs) for name, kwargs in variants.items()})
    return found


@pytest.mark.parametrize("variant, same", [("subpixel", True), ("per_cent", False), ("label", False)])
def test_a_figure_is_the_same_within_the_tolerance_and_its_pdf_goes_with_its_png(drawings, variant, same):
    assert compare(drawings["tracked"], drawings[variant])[0] is same
    tracked_pdf, drawn_pdf = drawings["tracked"].with_suffix(".pdf"), drawings[variant].with_suffix(".pdf")
    assert compare(tracked_pdf, drawn_pdf)[0] is same


@pytest.mark.parametrize("old, new, same", [
    ("error 1.30e-14 at cycle 50", "error 1.3e-14 at cycle 50", True),  # the same number printed otherwise
    ("error 1.3e-14 at cycle 50", "error 1.4e-14 at cycle 50", False),
    ("error 1.3e-14 at cycle 50", "error 1.3e-14 at cycle 51", False),
    ("the velocity converges", "the velocity diverges", False),
    ("a drift of -2e-10 s", "a drift of 2e-10 s", False),  # a sign is text
])
def test_a_document_is_the_same_where_its_text_and_its_numbers_at_their_printed_digits_are(tmp_path, old, new,
                                                                                           same):
    (tmp_path / "old.md").write_text(old)
    (tmp_path / "new.md").write_text(new)
    assert compare(tmp_path / "old.md", tmp_path / "new.md")[0] is same


def test_publish_copies_only_what_differs_and_a_pdf_with_its_png(drawings, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    Path("README.md").write_text("error 1.3e-14\n")
    Path("new.md").write_text("error 1.30e-14\n")
    before = {p: Path(p).read_bytes() for p in ("figures/fig.png", "figures/fig.pdf", "README.md")}
    published = {"figures/fig.png": str(drawings["per_cent"]), "figures/fig.pdf": str(drawings["per_cent"].with_suffix(
        ".pdf")), "README.md": "new.md"}
    publish(published, "publish.log")
    assert Path("figures/fig.png").read_bytes() == drawings["per_cent"].read_bytes()
    assert Path("figures/fig.pdf").read_bytes() == drawings["per_cent"].with_suffix(".pdf").read_bytes()
    assert Path("README.md").read_bytes() == before["README.md"]  # the same numbers: kept as it was
    assert "README.md: kept" in Path("publish.log").read_text()
    said = capsys.readouterr().err.splitlines()  # on the console too
    assert "README.md: kept (0 numbers printed differently)" in said
    assert said[-1] == "publish: 2 of 3 tracked files updated"


def test_the_check_says_which_tracked_file_differs_from_the_run(drawings, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    assert [r[1] for r in check({"figures/fig.png": str(drawings["subpixel"])})] == [True]
    assert [r[1] for r in check({"figures/fig.png": str(drawings["label"])})] == [False]
    with pytest.raises(FileNotFoundError, match="run the workflow first"):
        check({"figures/fig.png": "results/none.png"})


def test_every_tracked_file_is_published_from_the_replication_s_results():
    figures = ("fig3", "fig4", "fig5", "long_run", "stability_map", "escapement_error", "existence_map")
    expected = {"README.md", "REPLICATION.md"} | {f"figures/{f}.{e}" for f in figures for e in ("png", "pdf")}
    article = {f"article/{name}" for name in ("article.pdf", "metadata.yaml", "article.typ", "article.bib")}
    assert set(PUBLISHED) == expected | article
    assert all(path.startswith("results/replication/") for path in PUBLISHED.values())


def test_the_article_s_pdf_is_judged_by_its_typst_source(tmp_path):
    """The article's PDF carries the run's date, so publish judges it by its source: the same source keeps the
    PDF whatever its bytes; a source whose text changed updates it."""
    for side in ("tracked", "drawn"):
        (tmp_path / side).mkdir()
        (tmp_path / side / "article.pdf").write_bytes(f"%PDF {side}".encode())
        (tmp_path / side / "article.typ").write_text("= Results\nThe period is 6.2957 s.\n")
    assert compare(tmp_path / "tracked/article.pdf", tmp_path / "drawn/article.pdf") == (True, "text identical")
    (tmp_path / "drawn/article.typ").write_text("= Results\nThe period is 6.3 s.\n")
    same, detail = compare(tmp_path / "tracked/article.pdf", tmp_path / "drawn/article.pdf")
    assert not same and "numbers printed differently" in detail
