"""The article rebuilds from its folder alone: a copy of the tracked article/ (or, before it is published, of the run's)
compiles with Typst into an article of as many pages as the PDF beside its source."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
#: what a source that compiles on its own says of itself (workflow/templates/article.typ)
ALONE = "It compiles from its folder alone"


def test_the_article_compiles_from_a_copy_of_its_folder_alone(tmp_path):
    typst = pytest.importorskip("typst")
    folder = next((REPO / f for f in ("article", "results/replication/article")
                   if (REPO / f / "article.typ").is_file() and ALONE in (REPO / f / "article.typ").read_text("utf-8")),
                  None)
    if folder is None:
        pytest.skip("no article written to compile on its own: run snakemake --cores 2 publish")
    copy = Path(shutil.copytree(folder, tmp_path / "article"))
    pdf = typst.compile(str(copy / "article.typ"), root=str(copy), ignore_system_fonts=True)
    pages = [int(re.search(rb"/Type\s*/Pages\b.*?/Count (\d+)", data, re.S)[1]) for data in (
        pdf, (copy / "article.pdf").read_bytes())]
    assert pages[0] == pages[1] > 4
