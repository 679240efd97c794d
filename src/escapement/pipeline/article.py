"""The replication as a ReScience C article, written by the run: ``metadata.yaml`` in the journal's fields, and
``article.typ`` from ``workflow/templates/article.typ``, typeset by Typst (no TeX) to ``article.pdf``, PDF/A-2b.
Its numbers are read from datasets and typed columns and formatted once here; the claims table gives the statuses.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import yaml

from ..io.netcdf import read_csv, read_variables, replaced, write_text
from ..paper.printed_axes import panel
from ..verdict.rule import fmt
from ..verdict.scores import joint_candidates, panel_candidates, read_scores, summary
from ..verdict.tally import ORDER, findings
from .docs import fill
from .logs import logged
from .tables import LIMIT_COLUMNS, WORK_PRECISION_COLUMNS, read_claims

__all__ = ["RULE", "keywords", "metadata", "prefix", "string", "typ", "write_article"]

#: the rule that names the article a replication or a failed one, from the findings' statuses
RULE = ("the title reads [Re] when the paper's findings that hold (reproduced or consistent) outnumber those that "
        "fail in part or in whole (not reproduced or partially reproduced), and [¬Re] otherwise")
#: Typst's markup characters, each escaped by a backslash in text from the run
_MARKUP = re.compile(r"([\\#*_$@<>\[\]`~=+/\-\"'])")


def typ(text: object) -> str:
    """``text`` as Typst markup that shows it as it is: every markup character escaped, lines joined."""
    return _MARKUP.sub(r"\\\1", str(text).replace("\n", " "))


def string(text: object) -> str:
    """``text`` inside a Typst string literal: backslashes and quotes escaped."""
    return str(text).replace("\\", "\\\\").replace('"', '\\"')


def prefix(counts: Mapping[str, int]) -> str:
    """``[Re]`` or ``[¬Re]`` by :data:`RULE`, from the number of findings of each status."""
    held = counts["reproduced"] + counts["consistent"]
    failed = counts["not_reproduced"] + counts["partially_reproduced"]
    return "[Re]" if held > failed else "[¬Re]"


def keywords(citation: Mapping) -> list[str]:
    return list(dict.fromkeys(["rescience c", "replication", *citation["keywords"], "python"]))


def metadata(citation: Mapping, title: str, abstract: str) -> dict:
    """The article's ``metadata.yaml`` in ReScience C's field names: the authors as ``CITATION.cff`` names them
    (placeholders stay placeholders), its code url and doi, and the original's citation."""
    original = next(r for r in citation["references"] if r.get("doi"))
    names = ", ".join(f"{a['given-names'][0]}. {a['family-names']}" for a in original["authors"])
    cite = (f"{names}, \"{original['title']}\", {original['journal']} {original['volume']} ({original['year']}) "
            f"{original['start']}-{original['end']}")
    return {
        "title": title,
        "authors": [{"name": a.get("name") or f"{a['given-names']} {a['family-names']}", "orcid": a.get("orcid", ""),
                     "email": a.get("email", ""), "affiliations": "1,*"} for a in citation["authors"]],
        "affiliations": [{"code": 1, "name": citation["authors"][0].get("affiliation", ""), "address": ""}],
        "keywords": ", ".join(keywords(citation)),
        "code": [{"url": citation.get("repository-code", "")}, {"doi": citation.get("doi", "")}, {"swh": ""}],
        "data": [{"url": ""}, {"doi": ""}],
        "replication": [{"cite": cite}, {"bib": "mao2013"}, {"url": f"https://doi.org/{original['doi']}"},
                        {"doi": original["doi"]}], "abstract": abstract,
        "bibliography": "article.bib", "type": "Replication", "domain": "Nonlinear dynamics", "language": "Python",
        # filled in after acceptance, by the editor: left empty, as the journal's template has them
        "review": [{"url": ""}],
        "contributors": [{"name": "", "orcid": "", "role": role} for role in ("editor", "reviewer", "reviewer")],
        "dates": [{"received": ""}, {"accepted": ""}, {"published": ""}],
        "article": [{"number": ""}, {"doi": ""}, {"url": ""}],
        "journal": [{"name": "ReScience C"}, {"issn": "2430-3658"}, {"volume": ""}, {"issue": ""}],
    }


def _axes(rows: Sequence[Mapping], limits: Sequence[Mapping]) -> str:
    """Each axis claim as Typst cells: the printed limits and the run's it judged (each scored axis), its status."""
    claim, judged = {r["claim_id"]: r for r in rows}, {}
    for row in limits:
        axis = panel(row["figure"], row["panel"]).axes[row["axis"]]
        for kind, low, high in (("printed", axis.low, axis.high), ("run", float(row["low"]), float(row["high"]))):
            judged.setdefault(row["claim_id"], {}).setdefault(kind, []).append(
                f"{axis.label}: [{fmt(low, 6)}, {fmt(high, 6)}]")
    return ",\n".join(f"[{typ(claim[c]['source'])}], [{typ('; '.join(shown['printed']))}], "
                      f"[{typ('; '.join(shown['run']))}], [{typ(claim[c]['status'].replace('_', ' '))}]"
                      for c, shown in judged.items())


def _readings(scores: Sequence[Mapping]) -> str:
    """Per printed panel (and Fig. 4's two together) as Typst cells: the best score, the readings tied at it."""
    candidates = panel_candidates(scores)
    if any(figure == "4" for figure, _ in candidates):
        candidates[("4", "both panels")] = joint_candidates(scores, "4")
    cells = []
    for (figure, name), c in sorted(candidates.items(), key=lambda item: item[0][0]):
        _, groups = c.tied()
        lead = (f"undetermined: {len(groups)} readings tie, plotting different values" if len(groups) > 1 else
                "one reading" if len(groups[0]) == 1 else f"{len(groups[0])} equivalent readings (identical values)")
        cells.append(f"[{typ(figure)} {typ(name)}], [{typ(summary(c)[0])}], [{typ(lead)} of {len(c.scores)}:"
                     + "".join(f" #linebreak() {typ(' = '.join(group))}" for group in groups) + "]")
    return ",\n".join(cells)


def write_article(inputs: Mapping[str, str | Sequence[str]], outputs: Mapping[str, str], log: str,
                  config: Mapping) -> str:
    """The job of rule ``render_article``: the ``metadata``, ``source``, ``bibliography`` and ``pdf`` of ``outputs``
    from the rule's ``inputs`` and the replication's ``config``. Returns the title."""
    import typst

    with logged(log, "render_article") as logger:
        rows, figures = read_claims(inputs["claims"]), {Path(path).stem: path for path in inputs["figures"]}
        found = findings(rows)
        counts = {s: sum(status == s for status, _ in found.values()) for s in ORDER}
        citation = yaml.safe_load(Path(inputs["citation"]).read_text(encoding="utf-8"))
        original = next(r for r in citation["references"] if r.get("doi"))
        title = f"{prefix(counts)} {original['title']}"
        meta = metadata(citation, title, (
            f"We replicate J. Mao, Y. Fu and P. Li, \"{original['title']}\" ({original['journal']}, "
            f"{original['year']}), with an exact event-driven solver of its piecewise-linear model and a register of "
            f"the paper's claims, each checked under every reading its words admit. Of the {len(found)} sentences "
            f"the register quotes, {counts['reproduced']} are reproduced, {counts['consistent']} consistent, "
            f"{counts['partially_reproduced']} partially reproduced, {counts['not_reproduced']} not reproduced, "
            f"{counts['undetermined']} undetermined and {counts['untestable']} untestable."))
        checks = read_variables(inputs["checks"], ("group", "label", "period", "velocity", "multiplier"))
        paper = [i for i, group in enumerate(checks["group"]) if group == "paper"]  # the paper's two cases, by label
        exact = next(row for row in read_csv(inputs["benchmark"], WORK_PRECISION_COLUMNS) if row["method"] == "exact")
        number = {name: {checks["label"][i]: typ(fmt(float(checks[name][i]), digits)) for i in paper}
                  for name, digits in (("period", 12), ("velocity", 12), ("multiplier", 10))}
        names = {"meta": {k: typ(v) if isinstance(v, str) else v for k, v in meta.items()},
                 "literal": {k: string(v) for k, v in meta.items() if isinstance(v, str)},
                 "author_literals": [string(a["name"]) for a in meta["authors"]],
                 "keyword_literals": [string(k) for k in keywords(citation)],
                 "authors": [typ(a["name"]) for a in meta["authors"]], "rule": typ(RULE),
                 "config": config, "count": counts, "n_findings": len(found),
                 "n_rows": sum(len(parts) for _, parts in found.values()),
                 # the limit cycles, and the exact solver's error in the benchmark
                 "number": {**number, "exact_error_velocity": typ(fmt(float(exact["error_velocity"]), 2))},
                 "verdict": {r["claim_id"]: typ(r["status"].replace("_", " ")) for r in rows},
                 "table": {"axes": _axes(rows, read_csv(inputs["limits"], LIMIT_COLUMNS)),
                           "readings": _readings(read_scores(inputs["readings"])),
                           "findings": ",\n".join(f"[{typ(parts[0]['source'])}], [{typ(parts[0]['statement'])}], "
                                                  f"[{typ(status.replace('_', ' '))}]" for status, parts in
                                                  found.values())},
                 # the figures as the plotting jobs drew them, by their path from the source
                 "figure": {name: string(os.path.relpath(path, Path(outputs["source"]).parent))
                            for name, path in figures.items()}}
        source = fill(Path(inputs["template"]).read_text(encoding="utf-8"), inputs["template"], names)
        root = Path(os.path.commonpath([Path(p).resolve() for p in (outputs["source"], *figures.values())]))
        write_text(Path(inputs["bibliography"]).read_text(encoding="utf-8"), outputs["bibliography"])
        write_text(yaml.safe_dump(meta, sort_keys=False, allow_unicode=True, width=100), outputs["metadata"])
        write_text(source, outputs["source"])
        with replaced(outputs["pdf"]) as tmp:
            typst.compile(str(outputs["source"]), output=str(tmp), root=str(root), pdf_standards="a-2b",
                          ignore_system_fonts=True)  # its date the run's: publish compares the sources
        logger.info("the article: %s", title)
    return title
