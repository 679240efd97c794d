"""Publishing the tracked files: copied only where what they show changed, by the one rule CI's check applies.

A figure is compared as an image (matplotlib's ``compare_images``) against an RMS tolerance, its PDF goes with
its PNG, and a document is compared with its numbers read at their printed digits. A file cut short is never kept
or called the same, and a publish interrupted mid-copy leaves every tracked file whole.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

from escapement.pipeline import publish as module
from escapement.pipeline.publish import PUBLISHED, check, compare, damage, main, publish
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


def pdf(text: str) -> bytes:
    """The smallest whole PDF by the published rule: its header, a comment, an empty cross-reference table, its
    offset and the end marker."""
    head = f"%PDF-1.4\n% {text}\n".encode()
    return head + f"xref\nstartxref\n{len(head)}\n%%EOF\n".encode()


def cut(path: Path, fraction: float = 0.5) -> Path:
    """``path`` cut to ``fraction`` of its bytes, as a copy killed midway leaves it."""
    data = path.read_bytes()
    path.write_bytes(data[:int(len(data) * fraction)])
    return path


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


def test_a_figure_drawn_from_wall_times_is_kept_while_whole_and_replaced_when_damaged(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tracked := Path("article/figures/work_precision.svg")).parent.mkdir(parents=True)
    tracked.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 1"/></svg>')
    drawn = tmp_path / "drawn.svg"
    drawn.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 2"/></svg>')
    assert [r[1] for r in check({str(tracked): str(drawn)})] == [True]
    tracked.write_text("<svg")
    assert [r[1] for r in check({str(tracked): str(drawn)})] == [False]


def test_every_tracked_file_is_published_from_the_replication_s_results():
    figures = ("fig3", "fig4", "fig5", "long_run", "stability_map", "escapement_error", "existence_map")
    expected = {"README.md", "REPLICATION.md"} | {f"figures/{f}.{e}" for f in figures for e in ("png", "pdf")}
    article = {f"article/{name}" for name in ("article.pdf", "metadata.yaml", "article.typ", "article.bib")}
    article |= {f"article/figures/{name}.svg" for name in ("poincare_map", "shock_detail", "phase_diagrams",
                                                           "escapement_error", "work_precision", "long_run")}
    assert set(PUBLISHED) == expected | article
    assert all(path.startswith("results/replication/") for path in PUBLISHED.values())


def test_the_article_s_pdf_is_judged_by_its_typst_source(tmp_path):
    """The article's PDF carries the run's date, so publish judges it by its source: the same source keeps the
    PDF whatever its bytes; a source whose text changed updates it."""
    for side in ("tracked", "drawn"):
        (tmp_path / side).mkdir()
        (tmp_path / side / "article.pdf").write_bytes(pdf(side))
        (tmp_path / side / "article.typ").write_text("= Results\nThe period is 6.2957 s.\n")
    assert compare(tmp_path / "tracked/article.pdf", tmp_path / "drawn/article.pdf") == (True, "bytes identical")
    (tmp_path / "drawn/article.typ").write_text("= Results\nThe period is 6.3 s.\n")
    same, detail = compare(tmp_path / "tracked/article.pdf", tmp_path / "drawn/article.pdf")
    assert not same and "numbers printed differently" in detail


@pytest.mark.parametrize("name, data, flaw", [
    ("whole.pdf", pdf("whole"), None),
    ("header.pdf", pdf("whole")[1:], "not a whole PDF (no %PDF- at its start)"),
    ("offset.pdf", pdf("whole").replace(b"startxref\n", b""), "not a whole PDF (no startxref offset before its %%EOF)"),
    ("elsewhere.pdf", pdf("whole").replace(b"startxref\n17", b"startxref\n3"),
     "not a whole PDF (its startxref offset 3 points at neither xref nor an object)"),
    ("notes.md", "période".encode()[:2], "not UTF-8 text ('utf-8' codec can't decode byte 0xc3 in position 1: "
                                           "unexpected end of data)"),
])
def test_a_file_is_judged_whole_by_its_kind(tmp_path, name, data, flaw):
    (tmp_path / name).write_bytes(data)
    assert damage(tmp_path / name) == flaw


def test_a_png_without_its_iend_chunk_is_not_whole(drawings, tmp_path):
    (tmp_path / "fig.png").write_bytes(drawings["tracked"].read_bytes()[:-12])  # the 12 bytes of the IEND chunk
    assert damage(tmp_path / "fig.png") == "not a whole PNG (no IEND chunk at its end)"


def test_the_check_fails_on_each_tracked_file_cut_short_in_one_line_naming_it(drawings, tmp_path, monkeypatch,
                                                                               capsys):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    monkeypatch.setattr(module, "PUBLISHED", {f"figures/fig.{ext}": str(drawings["tracked"].with_suffix(f".{ext}"))
                                              for ext in ("png", "pdf", "svg")})
    for ext in ("png", "pdf", "svg"):
        cut(Path(f"figures/fig.{ext}"))
    assert main(["--check"]) == 1
    said = capsys.readouterr()
    assert said.out == ""
    patterns = [r"figures/fig\.png: not a whole PNG \(image file is truncated.*\)",
                r"figures/fig\.pdf: not a whole PDF \(no %%EOF at its end\)",
                r"figures/fig\.svg: not a whole SVG \((no element found|unclosed token): line \d+, column \d+\)"]
    lines = said.err.splitlines()
    assert len(lines) == 3 and all(re.fullmatch(f"{pattern}; run snakemake --cores 2 publish", line)
                                   for pattern, line in zip(patterns, lines)), lines


def test_publish_replaces_a_damaged_tracked_pdf_whose_png_is_unchanged(drawings, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    drawn = drawings["tracked"].with_suffix(".pdf")
    cut(Path("figures/fig.pdf"), 0.4)
    publish({"figures/fig.png": str(drawings["tracked"]), "figures/fig.pdf": str(drawn)}, "publish.log")
    assert Path("figures/fig.pdf").read_bytes() == drawn.read_bytes()
    log = Path("publish.log").read_text()
    assert "figures/fig.png: kept (bytes identical)" in log
    assert (f"figures/fig.pdf: updated from {drawn} (the tracked file was damaged: not a whole PDF (no %%EOF at its "
            "end))") in log


def test_a_publish_interrupted_mid_copy_leaves_every_tracked_file_whole(drawings, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    before = Path("figures/fig.pdf").read_bytes()
    copyfile = shutil.copyfile

    def interrupted(source, target, **kwargs):  # half the bytes written, then Ctrl-C; other copies as they are
        if not str(target).endswith(".partial"):
            return copyfile(source, target, **kwargs)
        Path(target).write_bytes(Path(source).read_bytes()[:len(Path(source).read_bytes()) // 2])
        raise KeyboardInterrupt

    monkeypatch.setattr(shutil, "copyfile", interrupted)
    with pytest.raises(KeyboardInterrupt):
        publish({"figures/fig.pdf": str(drawings["per_cent"].with_suffix(".pdf")),
                 "figures/fig.png": str(drawings["per_cent"])}, "publish.log")
    assert Path("figures/fig.pdf").read_bytes() == before
    assert sorted(p.name for p in Path("figures").iterdir()) == ["fig.pdf", "fig.png", "fig.svg"]


def test_a_damaged_file_of_the_run_is_refused_in_one_line_and_nothing_is_copied(drawings, tmp_path, monkeypatch,
                                                                                capsys):
    monkeypatch.chdir(tmp_path)
    shutil.copytree(drawings["tracked"].parent, "figures")
    shutil.copytree(drawings["per_cent"].parent, "results")
    before = {p: p.read_bytes() for p in Path("figures").iterdir()}
    cut(Path("results/fig.png"))
    published = {"figures/fig.pdf": "results/fig.pdf", "figures/fig.png": "results/fig.png"}
    refusal = (r"results/fig\.png: not a whole PNG \(image file is truncated.*\); draw it again with "
               r"snakemake --cores 2 --forcerun results/fig\.png")
    with pytest.raises(SystemExit) as failed:
        publish(published, "publish.log")
    assert re.fullmatch(f"publish failed: {refusal}", str(failed.value.code))
    assert {p: p.read_bytes() for p in Path("figures").iterdir()} == before
    monkeypatch.setattr(module, "PUBLISHED", published)
    assert main(["--check"]) == 1
    assert re.fullmatch(f"{refusal}\n", capsys.readouterr().err)
