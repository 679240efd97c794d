"""The tracked figures and documents, and the one step that updates them (``snakemake --cores 2 publish``): copied
from ``results/replication/`` where what they show changed; ``python -m escapement.pipeline.publish --check`` says
whether every tracked file shows what the run shows. Both compare by :func:`compare`: a PNG with matplotlib's
``compare_images`` within an RMS of :data:`FIGURE_RMS_TOLERANCE` (curves moved by 1e-6 give 0.002, by 1e-4 0.9, one
character of a legend 1.6; CPUs' rounding, about 1e-16, moves no pixel), a PDF by its source (rasterising one needs
Ghostscript), a document by its text and its numbers at their printed digits (``1.30e-14`` is ``1.3e-14``).
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import tempfile
from collections.abc import Mapping, Sequence
from decimal import Decimal
from pathlib import Path
from xml.etree import ElementTree

from ..io.netcdf import replaced
from .outputs import ARTICLE, ARTICLE_FIGURES

__all__ = ["FIGURE_RMS_TOLERANCE", "PUBLISHED", "WALL_TIMED", "check", "compare", "damage", "main", "publish"]

#: RMS pixel difference (of 255) within which a figure shows the same thing
FIGURE_RMS_TOLERANCE = 0.1
#: the tracked files, each with the file of results/ it is copied from (not the work-precision figure: wall times)
PUBLISHED = {
    **{f"figures/{tracked}.{ext}": f"results/replication/figures/{drawn}.{ext}"
       for tracked, drawn in (("fig3", "poincare_map"), ("fig4", "shock_detail"), ("fig5", "phase_diagrams"),
                              ("long_run", "long_run"), ("stability_map", "stability_map"),
                              ("escapement_error", "escapement_error"), ("existence_map", "existence_map"))
       for ext in ("png", "pdf")},
    "README.md": "results/replication/docs/README.md",
    "REPLICATION.md": "results/replication/docs/REPLICATION.md",
    **{f"article/{name}": f"results/replication/article/{name}" for name in ARTICLE},
    # the figures the article includes, so that article/ compiles on its own
    **{f"article/figures/{name}.svg": f"results/replication/article/figures/{name}.svg"
       for name in ARTICLE_FIGURES},
}
#: tracked files drawn from wall times, which differ from run to run and machine to machine: kept while whole
WALL_TIMED = frozenset({"article/figures/work_precision.svg"})
#: a printed number: digits, an optional fraction and an optional exponent (a sign before it is text)
_NUMBER = re.compile(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
#: how the detail of :func:`compare` begins for a tracked file that is not whole
DAMAGED = "the tracked file was damaged: "
#: what a PDF's ``startxref`` offset must point at: its cross-reference table or stream (an object)
_XREF = re.compile(rb"xref|\d+\s+\d+\s+obj")


def _pdf(data: bytes) -> str | None:
    """What makes ``data`` not a whole PDF, or None; hand-written as no PDF library is among the dependencies,
    and its header, end marker and cross-reference offset are what a cut-off copy loses."""
    found = re.search(rb"startxref\s+(\d+)\s+%%EOF\s*\Z", data[-1024:])
    if not data.startswith(b"%PDF-"):
        return "no %PDF- at its start"
    if not data.rstrip().endswith(b"%%EOF"):
        return "no %%EOF at its end"
    if not found:
        return "no startxref offset before its %%EOF"
    if not _XREF.match(data, int(found[1])):
        return f"its startxref offset {int(found[1])} points at neither xref nor an object"
    return None


def damage(path: Path) -> str | None:
    """What makes ``path`` not a whole file of its kind, or None: a PNG must decode and end with IEND, a PDF pass
    :func:`_pdf`, an SVG parse as XML, any other file decode as UTF-8."""
    data = path.read_bytes()
    if path.suffix == ".png":
        from PIL import Image

        try:
            with Image.open(path, formats=["PNG"]) as image:
                image.load()
        except OSError as error:
            return f"not a whole PNG ({error})"
        return None if data.endswith(b"IEND\xaeB`\x82") else "not a whole PNG (no IEND chunk at its end)"
    if path.suffix == ".pdf":
        return None if (flaw := _pdf(data)) is None else f"not a whole PDF ({flaw})"
    try:
        ElementTree.fromstring(data) if path.suffix == ".svg" else data.decode("utf-8")
    except (ElementTree.ParseError, UnicodeDecodeError) as error:
        return f"not {'a whole SVG' if path.suffix == '.svg' else 'UTF-8 text'} ({error})"
    return None


def _figure(old: Path, new: Path) -> tuple[bool, str]:
    from matplotlib.testing.compare import compare_images
    from matplotlib.testing.exceptions import ImageComparisonFailure

    with tempfile.TemporaryDirectory() as folder:  # compare_images writes its difference image beside the files
        expected, actual = shutil.copy(old, Path(folder, "old.png")), shutil.copy(new, Path(folder, "new.png"))
        try:
            result = compare_images(expected, actual, tol=0, in_decorator=True)
        except ImageComparisonFailure as error:  # images of different sizes
            return False, str(error).replace("\n", " ")
    rms = 0.0 if result is None else float(result["rms"])
    return rms <= FIGURE_RMS_TOLERANCE, f"RMS {rms:.4f} against {FIGURE_RMS_TOLERANCE:g}"


def _document(old: str, new: str) -> tuple[bool, str]:
    if old == new:
        return True, "text identical"
    if _NUMBER.split(old) != _NUMBER.split(new):
        line = next((i for i, (a, b) in enumerate(zip(old.splitlines(), new.splitlines()), 1) if a != b),
                    min(len(old.splitlines()), len(new.splitlines())) + 1)
        return False, f"the text differs outside its numbers (from line {line})"
    differing = [f"{a} -> {b}" for a, b in zip(_NUMBER.findall(old), _NUMBER.findall(new)) if Decimal(a) != Decimal(b)]
    return not differing, f"{len(differing)} numbers printed differently" + (f" (first {differing[0]})"
                                                                               if differing else "")


def compare(tracked: str | Path, drawn: str | Path) -> tuple[bool, str]:
    """Whether the tracked file shows what the drawn one shows, and the difference in words; a PDF is judged by its
    PNG (the article's by its Typst source); a damaged tracked file differs, a damaged drawn one is refused."""
    tracked, drawn = Path(tracked), Path(drawn)
    if (flaw := damage(drawn)) is not None:
        raise OSError(f"{drawn}: {flaw}; draw it again with snakemake --cores 2 --forcerun {drawn}")
    if not tracked.is_file():
        return False, "no tracked file to compare with"
    if tracked.read_bytes() == drawn.read_bytes():
        return True, "bytes identical"
    if (flaw := damage(tracked)) is not None:
        return False, DAMAGED + flaw
    if tracked.suffix == ".pdf":
        source = ".typ" if tracked.stem == "article" else ".png"
        same, detail = compare(tracked.with_suffix(source), drawn.with_suffix(source))
        return same, detail.replace(DAMAGED, f"judged by its {source}, which is damaged: ")
    if tracked.suffix == ".png":
        return _figure(tracked, drawn)
    return _document(tracked.read_text(encoding="utf-8"), drawn.read_text(encoding="utf-8"))


def publish(published: Mapping[str, str], log: str) -> None:
    """Copy each drawn file of ``published`` (tracked path: drawn path) over its tracked one where they differ or the
    tracked one is damaged, saying per file what was compared and the difference."""
    from .logs import logged

    with logged(log, "publish") as logger:
        decided = check(published)  # all compared first: a PDF goes by its PNG as tracked
        lines = []
        for (tracked, same, detail), drawn in zip(decided, published.values()):
            if not same:
                with replaced(tracked) as partial:
                    shutil.copyfile(drawn, partial)
            lines.append(f"{tracked}: kept ({detail})" if same else f"{tracked}: updated from {drawn} ({detail})")
            logger.info("%s", lines[-1])
        updated = sum(not same for _, same, _ in decided)
        print("\n".join([*lines, f"publish: {updated} of {len(decided)} tracked files updated"]), file=sys.stderr)


def check(published: Mapping[str, str] = PUBLISHED) -> list[tuple[str, bool, str]]:
    """Each tracked file against the file drawn by the last run: ``(path, same, detail)``."""
    missing = [drawn for drawn in published.values() if not Path(drawn).is_file()]
    if missing:
        raise FileNotFoundError(f"run the workflow first: {', '.join(missing)} not found")
    return [(tracked, True, "drawn from wall times: kept while whole")
            if tracked in WALL_TIMED and Path(tracked).is_file() and damage(Path(tracked)) is None
            else (tracked, *compare(tracked, drawn)) for tracked, drawn in published.items()]


def main(argv: Sequence[str] | None = None) -> int:
    """``--check``: 0 if every tracked file shows what the last run drew, within the tolerances; else 1."""
    parser = argparse.ArgumentParser(prog="python -m escapement.pipeline.publish", description=main.__doc__)
    parser.add_argument("--check", action="store_true", required=True,
                        help="compare each tracked figure and document with the one the last run drew")
    parser.parse_args(argv)
    try:
        results = check(PUBLISHED)
    except OSError as error:  # a file of the run missing or damaged, or one the machine refuses to read
        print(error, file=sys.stderr)
        return 1
    for path, same, detail in results:
        if detail.startswith(DAMAGED):
            print(f"{path}: {detail.removeprefix(DAMAGED)}; run snakemake --cores 2 publish", file=sys.stderr)
        else:
            print(f"{path}: {'same' if same else 'DIFFERS'} ({detail})")
    differing = [path for path, same, detail in results if not same and not detail.startswith(DAMAGED)]
    if differing:
        print(f"{len(differing)} tracked file(s) differ from the run beyond the tolerance: {', '.join(differing)}; "
              "run `snakemake --cores 2 publish` and commit them if the code changed what they show", file=sys.stderr)
    return 0 if all(same for _, same, _ in results) else 1


if __name__ == "__main__":
    sys.exit(main())
