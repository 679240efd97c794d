"""What a run promises and what makes it: every file the workflow's default target holds, the one line that
answers a target no configuration makes, and the digest of the code every job runs (the package, the workflow's
scripts, the benchmarks and the versions of the declared dependencies), a param of every rule, so that any edit of a
source file reruns every job.
"""

from __future__ import annotations

import difflib
import hashlib
import re
from collections.abc import Iterable, Mapping
from importlib import metadata
from pathlib import Path

from ..scenes.settings import KINDS, REPLICATION

__all__ = ["EXTRA_FIGURES", "FIGURE_NAMES", "FILES", "code_digest", "data_files", "file_digest", "figure_files",
           "not_a_target", "stale_files", "study_targets", "targets"]

#: the data files of each kind in its study's folder: a pattern per scene (its label) or the kind's one file
FILES = {"fig3": "poincare_map/case_{}.nc", "fig5": "phase_diagrams/K_{}.nc"}
#: the replication's data beyond its scenes: the claims' runs, the long run, the readings, the tables
REPLICATION_DATA = ("checks.nc", "long_run.nc", "long_run_timing.csv", "readings.csv", "work_precision.csv",
                    "claims.csv", "panel_limits.csv", "stress.csv")
#: the documents the replication renders (docs/): the pages, the measured times, the report's landing text and items
DOCUMENTS = ("README.md", "REPLICATION.md", "timings.md", "landing.html", "verdict.html", "replication.html")
EXTRA_FIGURES = ("long_run", "work_precision")
#: the article's files (article/) and the figures it shows, in the order it shows them
ARTICLE = ("article.pdf", "metadata.yaml", "article.typ", "article.bib")
ARTICLE_FIGURES = ("poincare_map", "shock_detail", "phase_diagrams", "escapement_error", "work_precision", "long_run")
#: the name of every figure a rule draws (a figure of another name is not a target of any configuration)
FIGURE_NAMES = (*(kind.name for kind in KINDS.values()), *EXTRA_FIGURES, "work_precision_full")


def data_files(study: str, block: str, labels: Iterable[str]) -> dict[str, str]:
    """The data files of the kind ``block`` in ``study``, by scene label (``""`` for a kind of one file)."""
    if block in FILES:
        return {label: f"results/{study}/{FILES[block].format(label)}" for label in labels}
    return {"": f"results/{study}/{KINDS[block].name}.nc"}


def figure_files(study: str, blocks: Iterable[str]) -> list[str]:
    names = [KINDS[block].name for block in blocks] + (list(EXTRA_FIGURES) if study == REPLICATION else [])
    return [f"results/{study}/figures/{name}.png" for name in names]


def study_targets(study: str, scenes: Mapping[str, Mapping[str, object]]) -> list[str]:
    """Every file a study promises: each kind's data and figure, and the replication's own data and documents."""
    found = [path for block, labelled in scenes.items() for path in data_files(study, block, labelled).values()]
    found += [png.removesuffix(".png") + ext for png in figure_files(study, scenes) for ext in (".png", ".pdf", ".svg")]
    if "stability_map" in scenes:
        found.append(f"results/{study}/stability_map_timing.csv")
    if study == REPLICATION:
        found += [f"results/{REPLICATION}/{name}" for name in REPLICATION_DATA]
        found += [f"results/replication/docs/{name}" for name in DOCUMENTS]
        found += [f"results/replication/article/{name}" for name in ARTICLE]
    return found


def stale_files(study: str, scenes: Mapping[str, Mapping[str, object]]) -> list[Path]:
    """The files of a kind's name in ``results/<study>/`` (data, figures, timing) this configuration no longer makes."""
    keep, root = set(study_targets(study, scenes)), Path("results", study)
    patterns = [*(FILES.get(block, f"{kind.name}.nc").format("*") for block, kind in KINDS.items()),
                *(f"figures/{kind.name}.{ext}" for kind in KINDS.values() for ext in ("png", "pdf", "svg")),
                "stability_map_timing.csv"]
    return sorted({path for pattern in patterns for path in root.glob(pattern) if path.as_posix() not in keep})


def targets(studies: Mapping[str, Mapping[str, Mapping[str, object]]]) -> list[str]:
    """The default target: every file of every study (Snakemake reruns a job for a missing target, not for a
    missing output beside it)."""
    return [path for study, scenes in studies.items() for path in study_targets(study, scenes)]


def not_a_target(path: str, studies: Mapping[str, Mapping[str, Mapping[str, object]]]) -> str:
    """One line for a target this configuration does not make: what it makes instead, and the closest name."""
    parts = Path(path).parts
    study = parts[1] if len(parts) > 2 and parts[0] == "results" else None
    if study is not None and study not in studies:
        return (f"{path} is not made by this configuration: it runs the studies {', '.join(studies)} (a study of "
                f"your own is named by `name` and runs only with a configuration that differs from the paper's)")
    study = study or REPLICATION
    drawn = [Path(p).stem for p in figure_files(study, studies[study])]
    tracked = {f"fig{kind.figure[5:]}": kind.name for kind in KINDS.values() if kind.figure}
    stem, hint = Path(path).stem, ""
    if stem in tracked:
        hint = f" (the paper's {stem.replace('fig', 'Fig. ')} is drawn as {tracked[stem]}.png; figures/{stem}.png " \
               f"is its tracked copy, updated by the publish target)"
    elif stem in FIGURE_NAMES and stem not in drawn:
        hint = f" (the study '{study}' does not draw {stem}: what its configuration changes does not reach it)"
    elif close := difflib.get_close_matches(stem, drawn, n=1, cutoff=0.6):
        hint = f" (did you mean {close[0]}{Path(path).suffix}?)"
    return (f"{path} is not made by this configuration{hint}; the study '{study}' draws {', '.join(drawn)} (each as "
            f".png, .pdf and .svg) in results/{study}/figures/, each from its data in results/{study}/")


def code_digest(root: str | Path, package: str | Path | None = None) -> str:
    """The digest the module's docstring describes, of ``package`` (by default the one loaded) and of ``root``'s."""
    digest = hashlib.sha256()
    package = Path(package) if package is not None else Path(__file__).resolve().parents[1]
    for folder, base in ((package, package.parent), (Path(root, "workflow/scripts"), Path(root)),
                         (Path(root, "benchmarks"), Path(root))):
        for file in sorted(folder.rglob("*")):
            if file.is_file() and "__pycache__" not in file.parts:
                digest.update(file.relative_to(base).as_posix().encode() + b"\0" + file.read_bytes())
    for requirement in metadata.requires("escapement") or ():
        if "extra ==" not in requirement:
            name = re.match(r"[A-Za-z0-9._-]+", requirement)[0]
            digest.update(f"{name}=={metadata.version(name)}".encode())
    return digest.hexdigest()[:16]


def file_digest(paths: Iterable[str | Path]) -> str:
    """The digest of the files ``paths`` (their names and contents): a param of the rules that read them as text, so
    that an edit reruns the job whatever the file's modification time."""
    digest = hashlib.sha256()
    for path in paths:
        digest.update(Path(path).as_posix().encode() + b"\0" + Path(path).read_bytes() + b"\0")
    return digest.hexdigest()[:16]
