"""The last job: copy the figures and documents that git tracks from ``results/`` to their place in
the repository, only where what they show changed.

The jobs before it write only under ``results/``, so an interrupted or failed run never touches a
tracked file; this job replaces a tracked file atomically, and leaves it byte-identical (only its
modification time renewed, for Snakemake) when the new one shows the same thing:

- a PNG figure is compared as an image, with matplotlib's own comparison
  (``matplotlib.testing.compare.compare_images``, the one pytest-mpl uses), and copied only if the
  RMS difference of its pixels exceeds :data:`FIGURE_RMS_TOLERANCE`;
- a PDF figure goes with the PNG drawn from the same figure in the same job (same folder and stem):
  copied when that PNG is, kept when it is kept. Rasterising a PDF needs Ghostscript, which not every
  machine has, and a rule that depended on it would decide differently from machine to machine;
- a document (Markdown) is copied only if its text differs outside its numbers, or if a number it
  prints differs by more than :data:`DOCUMENT_DIGIT_TOLERANCE` units of its last printed digit
  (``1.30e-14`` and ``1.3e-14`` print the same number; a sign is text).

Measured on the long-run figure when it drew every cycle's error (the finest curves the project drew):
curves moved by 1e-6 (relative, some 1e10 times float64 rounding) give an RMS of 0.002, by 1e-4 0.9, by
1 per cent 4.1; one character of the legend changed gives 1.6.

Rounding that differs from one CPU, BLAS kernel or C library to another moves a computed value by
about 1e-16 (relative), which moves no curve by a visible fraction of a pixel and changes no printed
digit; only a curve or number that shows rounding itself (an error near the spacing of float64) can
change beyond the tolerance, or one that an adaptive integrator's steps amplify (the long-run figure draws
those as levels, see :mod:`escapement.plotting.study_figures`). CI applies the same rule to the files
``git status`` shows as modified (``python -m escapement.pipeline.publish --check PATH...``, see
:func:`check`) after runs with NumPy's baseline SIMD dispatch and with an older OpenBLAS core type.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path, PurePosixPath

from matplotlib.testing.compare import compare_images
from matplotlib.testing.exceptions import ImageComparisonFailure
from PIL import UnidentifiedImageError

from ..io.atomic import atomic_path
from .logs import logged

__all__ = [
    "DOCUMENT_DIGIT_TOLERANCE",
    "FIGURE_RMS_TOLERANCE",
    "Comparison",
    "check",
    "compare_documents",
    "compare_figures",
    "compare_tracked",
    "main",
    "mark_stale",
    "publish",
]

#: RMS pixel difference (of 255) within which a figure shows the same thing: on the long-run figure,
#: curves moved by 1e-6 (relative) measure 0.002 and one character of the legend changed 1.6.
FIGURE_RMS_TOLERANCE = 0.1

#: units of a number's last printed digit by which it may differ: none, as a value moved by less than
#: half a unit prints the same and a digit printed differently says another number.
DOCUMENT_DIGIT_TOLERANCE = Decimal(0)

#: a printed number: digits, an optional fraction and an optional exponent (a sign before it is text)
_NUMBER = re.compile(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")

#: the rule by which each kind of tracked file is compared
_KINDS = {".png": "figure", ".pdf": "pdf", ".md": "document"}


@dataclass(frozen=True)
class Comparison:
    """How a new version of a tracked file compares with the one in place.

    ``difference`` is what was measured (the RMS pixel difference of a figure, the largest difference
    of a printed number in units of its last digit), ``None`` where nothing could be measured (no file
    in place, images of different sizes, text that differs outside its numbers)."""

    path: str
    rule: str
    difference: float | None
    within: bool
    detail: str

    def describe(self) -> str:
        verdict = "within the tolerance" if self.within else "beyond the tolerance"
        return f"{self.path}: {self.rule}, {self.detail}: {verdict}"


def compare_figures(old: str | os.PathLike, new: str | os.PathLike, path: str = "") -> Comparison:
    """Compare two PNG files as images (``compare_images``), against :data:`FIGURE_RMS_TOLERANCE`."""
    rule = f"image RMS against {FIGURE_RMS_TOLERANCE:g}"
    path = path or str(old)
    if Path(old).read_bytes() == Path(new).read_bytes():
        return Comparison(path, rule, 0.0, True, "bytes identical, RMS 0")
    # compare_images writes an image of the difference beside the new file: both go to a temporary folder
    with tempfile.TemporaryDirectory() as folder:
        expected, actual = Path(folder, "committed.png"), Path(folder, "new.png")
        shutil.copyfile(old, expected)
        shutil.copyfile(new, actual)
        try:
            result = compare_images(str(expected), str(actual), tol=0, in_decorator=True)
        except ImageComparisonFailure as error:  # raised for images of different sizes
            return Comparison(path, rule, None, False, str(error).replace("\n", " "))
        except UnidentifiedImageError as error:
            return Comparison(path, rule, None, False, f"not readable as an image ({error})")
    rms = 0.0 if result is None else float(result["rms"])
    return Comparison(path, rule, rms, rms <= FIGURE_RMS_TOLERANCE, f"RMS {rms:.4f}")


def _numbers(text: str) -> tuple[list[str], list[str]]:
    """The text between the printed numbers, and the numbers."""
    return _NUMBER.split(text), _NUMBER.findall(text)


def _last_digit(number: Decimal) -> Decimal:
    """The value of one unit of the last printed digit of ``number`` (0.01 for 1.25, 1e-15 for 1.0e-14)."""
    return Decimal(1).scaleb(number.as_tuple().exponent)


def compare_documents(old: str, new: str, path: str = "") -> Comparison:
    """Compare two texts: equal outside their numbers, each number equal to the other at its printed
    digits (within :data:`DOCUMENT_DIGIT_TOLERANCE` units of the coarser of the two last digits)."""
    rule = f"numbers at their printed digits (tolerance {DOCUMENT_DIGIT_TOLERANCE} in the last digit)"
    if old == new:
        return Comparison(path, rule, 0.0, True, "text identical")
    (old_text, old_numbers), (new_text, new_numbers) = _numbers(old), _numbers(new)
    if old_text != new_text:
        lines = list(zip(old.splitlines(), new.splitlines()))
        line = next((i for i, (a, b) in enumerate(lines, 1) if a != b), len(lines) + 1)
        return Comparison(path, rule, None, False, f"the text differs outside its numbers (from line {line})")
    worst, differing = Decimal(0), []
    for a, b in zip(old_numbers, new_numbers, strict=True):
        x, y = Decimal(a), Decimal(b)
        units = abs(x - y) / max(_last_digit(x), _last_digit(y))
        worst = max(worst, units)
        if units > DOCUMENT_DIGIT_TOLERANCE:
            differing.append(f"{a} -> {b}")
    detail = (f"{len(old_numbers)} numbers, {len(differing)} printed differently, largest difference {worst:g} "
              "unit(s) of the last printed digit") + (f" (first {differing[0]})" if differing else "")
    return Comparison(path, rule, float(worst), not differing, detail)


def _kind(path: str, argument: str) -> str:
    suffix = PurePosixPath(path).suffix.lower()
    if suffix in _KINDS:
        return _KINDS[suffix]
    raise ValueError(f"{argument}: {path!r} has no comparison rule: a tracked file must end in .png, .pdf or .md")


def compare_tracked(names: Sequence[str], old: Sequence[str | os.PathLike | None],
                    new: Sequence[str | os.PathLike], argument: str = "targets") -> list[Comparison]:
    """Compare each tracked file ``names[i]`` as it is (``old[i]``, ``None`` if there is none) with its
    new version ``new[i]``, by the rule of its kind; a PDF is decided by the PNG of the same folder and
    stem among ``names``. ``argument`` names ``names`` in a refusal."""
    kinds = [_kind(name, argument) for name in names]
    for name, kind in zip(names, kinds, strict=True):
        png = str(PurePosixPath(name).with_suffix(".png"))
        if kind == "pdf" and png not in names:
            raise ValueError(f"{argument}: {name!r} has no PNG of the same figure among them ({png!r}): a PDF is "
                             "decided by the PNG drawn from the same figure")
    decided: dict[str, Comparison] = {}
    for name, kind, before, after in zip(names, kinds, old, new, strict=True):
        if before is None or not Path(before).is_file():
            decided[name] = Comparison(name, "new file", None, False, "no version in place to compare with")
        elif kind == "figure":
            decided[name] = compare_figures(before, after, name)
        elif kind == "document":
            texts = (Path(before).read_text(encoding="utf-8"), Path(after).read_text(encoding="utf-8"))
            decided[name] = compare_documents(*texts, path=name)
    for name, kind, before, after in zip(names, kinds, old, new, strict=True):
        if kind != "pdf" or name in decided:
            continue
        png = str(PurePosixPath(name).with_suffix(".png"))
        by = decided[png]
        same = Path(before).read_bytes() == Path(after).read_bytes()
        decided[name] = Comparison(name, f"goes with {png}", by.difference, by.within,
                                   f"{by.detail}; PDF bytes {'identical' if same else 'differ'}")
    return [decided[name] for name in names]


def publish(sources: Sequence[str], targets: Sequence[str], log: str) -> None:
    """Copy each of ``sources`` to the matching ``targets`` where it differs beyond the tolerance of its
    kind (or where a figure's PNG does, for its PDF); log per file what was compared and the difference."""
    with logged(log, "publish") as logger:
        logger.info("tolerances: figures RMS %g (of 255), documents %s unit(s) of a number's last printed digit",
                    FIGURE_RMS_TOLERANCE, DOCUMENT_DIGIT_TOLERANCE)
        for comparison, source, target in zip(compare_tracked(targets, targets, sources), sources, targets,
                                              strict=True):
            path = Path(target)
            if comparison.within or (path.is_file() and path.read_bytes() == Path(source).read_bytes()):
                os.utime(path)  # newer than its source, for Snakemake; its content stays as committed
                logger.info("%s: unchanged (%s; %s)", target, comparison.rule, comparison.detail)
                continue
            with atomic_path(path) as tmp:
                shutil.copyfile(source, tmp)
            logger.info("%s: updated from %s (%s; %s)", target, source, comparison.rule, comparison.detail)


def _committed(path: str, revision: str, folder: Path) -> Path | None:
    """``path`` as committed at ``revision``, written under ``folder``; ``None`` if it is not committed."""
    shown = subprocess.run(["git", "show", f"{revision}:./{path}"], capture_output=True, check=False)
    if shown.returncode != 0:
        return None
    copy = folder / path
    copy.parent.mkdir(parents=True, exist_ok=True)
    copy.write_bytes(shown.stdout)
    return copy


def check(paths: Sequence[str], revision: str = "HEAD") -> list[Comparison]:
    """Compare each of ``paths`` (relative to the working directory, inside a git work tree) with its
    version committed at ``revision``, by the rule :func:`publish` applies; a PDF is decided by its PNG,
    which need not be among ``paths``."""
    names = list(dict.fromkeys(paths))
    for name in list(names):
        png = str(PurePosixPath(name).with_suffix(".png"))
        if _kind(name, "paths") == "pdf" and png not in names:
            names.append(png)
    for name in names:
        if not Path(name).is_file():
            raise ValueError(f"paths: {name!r} is not a file: each path must name a tracked file as it is now")
    with tempfile.TemporaryDirectory() as folder:
        committed = [_committed(name, revision, Path(folder)) for name in names]
        comparisons = compare_tracked(names, committed, names, argument="paths")
    return [c for c in comparisons if c.path in paths]


def main(argv: Sequence[str] | None = None) -> int:
    """``--check PATH...``: 0 if every path shows what its committed version shows, within the tolerances."""
    parser = argparse.ArgumentParser(prog="python -m escapement.pipeline.publish", description=main.__doc__)
    parser.add_argument("--check", nargs="+", metavar="PATH", required=True,
                        help="tracked files to compare with their committed version")
    parser.add_argument("--revision", default="HEAD", help="the commit to compare with (default: HEAD)")
    args = parser.parse_args(argv)
    comparisons = check(args.check, args.revision)
    for comparison in comparisons:
        print(comparison.describe())
    beyond = [c.path for c in comparisons if not c.within]
    if beyond:
        print(f"{len(beyond)} of {len(comparisons)} file(s) differ from {args.revision} beyond the tolerance: "
              + ", ".join(beyond), file=sys.stderr)
        return 1
    return 0


def mark_stale(targets: Sequence[str]) -> None:
    """Date the tracked files back to the epoch, so that the next run publishes them again.

    Called when a run fails: Snakemake restores a tracked file that a failed job was updating with
    a new modification time, which would otherwise make it look newer than what it is copied from.
    The content is untouched, so git sees no change."""
    for target in targets:
        if Path(target).is_file():
            os.utime(target, (0, 0))


if __name__ == "__main__":
    sys.exit(main())
