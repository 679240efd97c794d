"""The replication as a ReScience C article, written by the run: ``metadata.yaml`` in the journal's own fields and
``article.typ`` from the template ``workflow/templates/article.typ``, typeset by Typst (a compiler in a wheel, no
TeX) to ``article.pdf``, PDF/A-2b with its fonts embedded.

The PDF is built from the metadata: its title, authors, keywords and abstract are the file's. Every number of the
text comes from the claims table, the checks dataset and the facts of the documents, formatted once here; the
template holds none. The title's prefix follows one stated rule from the verdict's headline (:data:`RULE`).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import jinja2
import yaml

from ..io.netcdf import read_netcdf, replaced, write_text
from ..verdict.evidence import fmt
from ..verdict.tally import ORDER, findings
from .outputs import ARTICLE_FIGURES

__all__ = ["RULE", "metadata", "prefix", "string", "typ", "write_article"]

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
        "keywords": ", ".join(dict.fromkeys(["rescience c", "replication", *citation["keywords"], "python"])),
        "code": [{"url": citation.get("repository-code", "")}, {"doi": citation.get("doi", "")}, {"swh": ""}],
        "data": [{"url": ""}, {"doi": ""}],
        "replication": [{"cite": cite}, {"bib": "mao2013"}, {"url": f"https://doi.org/{original['doi']}"},
                        {"doi": original["doi"]}],
        "abstract": abstract,
        "bibliography": "article.bib",
        "type": "Replication",
        "domain": "Nonlinear dynamics",
        "language": "Python",
        # filled in after acceptance, by the editor: left empty, as the journal's template has them
        "review": [{"url": ""}],
        "contributors": [{"name": "", "orcid": "", "role": role} for role in ("editor", "reviewer", "reviewer")],
        "dates": [{"received": ""}, {"accepted": ""}, {"published": ""}],
        "article": [{"number": ""}, {"doi": ""}, {"url": ""}],
        "journal": [{"name": "ReScience C"}, {"issn": "2430-3658"}, {"volume": ""}, {"issue": ""}],
    }


def _counts(rows: Sequence[Mapping]) -> tuple[dict[str, int], int, int]:
    """The number of findings of each status, of findings, and of the rows that check them."""
    found = findings(rows)
    return ({s: sum(status == s for status, _ in found.values()) for s in ORDER}, len(found),
            sum(len(parts) for _, parts in found.values()))


def _numbers(rows: Sequence[Mapping], checks, facts: Mapping[str, str]) -> dict[str, str]:
    """The numbers the text cites, each formatted once: the limit cycles of the paper's two cases (the checks
    dataset's group ``paper``), the printed period, and the facts of the documents."""
    paper = checks["group"].values == "paper"
    cases = dict(zip(checks["label"].values[paper], zip(*(checks[k].values[paper] for k in
                                                          ("period", "velocity", "multiplier")))))
    (ta, va, ma), (tb, vb, mb) = cases["fig3a"], cases["fig3b"]
    claim = {r["claim_id"]: r for r in rows}
    return {"period_a": fmt(ta, 12), "period_b": fmt(tb, 12), "velocity_a": fmt(va, 12), "velocity_b": fmt(vb, 12),
            "multiplier_a": fmt(ma, 10), "multiplier_b": fmt(mb, 10),
            "printed_period": claim["fig3_period_a"]["paper_value"], **facts}


def _short(text: str, most: int = 110) -> str:
    """The first clause of ``text`` (up to its first "; "), cut at a word to ``most`` characters."""
    first = text.split("; ")[0]
    return first if len(first) <= most else first[:most].rsplit(" ", 1)[0] + " …"


def _cell(markdown: str) -> str:
    """A cell of the documents' Markdown tables (bold, ``<br>`` breaks) as Typst markup."""
    return " #linebreak() ".join(typ(part) for part in markdown.replace("**", "").split("<br>"))


def _tables(rows: Sequence[Mapping], readings: Sequence[Mapping]) -> dict[str, str]:
    """The tables of the article as Typst cells: the candidate readings of each printed panel that its axes support
    best (``readings``, :func:`escapement.verdict.scores.best_readings_table`), the printed axes beside the run's
    (the limits the adopted reading gives, autoscaled as printed), and the findings by section, each with what the
    run found."""
    axes = [r for r in rows if r["source"].startswith("Fig.") and r["origin"] == "paper"]
    found = findings(rows)
    return {
        "readings": ",\n".join(f"[{typ(r['figure'])} {typ(r['panel'])}], [{_cell(r['limits reproduced'])}], "
                               f"[{_cell(r['best-supported readings'])}]" for r in readings),
        "axes": ",\n".join(f"[{typ(r['source'])}], [{typ(r['paper_value'])}], "
                           f"[{typ(re.split(r' [(][0-9]+ of [0-9]+ printed limits[)]', r['replicated_value'])[0])}], "
                           f"[{typ(r['status'].replace('_', ' '))}]"
                           for r in axes),
        "findings": ",\n".join(f"[{typ(parts[0]['source'])}], [{typ(parts[0]['statement'])}], "
                               f"[{typ(_short(parts[0]['replicated_value']))}], [{typ(status.replace('_', ' '))}]"
                               for status, parts in found.values()),
    }


def write_article(rows: Sequence[Mapping], facts: Mapping[str, str], readings: Sequence[Mapping],
                  inputs: Mapping[str, str], outputs: Mapping[str, str]) -> str:
    """Write ``metadata.yaml``, ``article.typ``, ``article.bib`` and ``article.pdf`` (the keys ``metadata``,
    ``source``, ``bibliography`` and ``pdf`` of ``outputs``) from the claims table's ``rows``, the documents'
    ``facts``, the best-supported ``readings`` of each printed panel and the files of ``inputs``: the checks
    dataset, ``CITATION.cff``, the template, the bibliography and the figures (``figure_<name>``, the SVG the
    plotting jobs drew, which the source names by their path). Returns the title."""
    import typst

    figures = {name: inputs[f"figure_{name}"] for name in ARTICLE_FIGURES}
    counts, n_findings, n_rows = _counts(rows)
    citation = yaml.safe_load(Path(inputs["citation"]).read_text(encoding="utf-8"))
    original = next(r for r in citation["references"] if r.get("doi"))
    title = f"{prefix(counts)} {original['title']}"
    abstract = (
        f"We replicate J. Mao, Y. Fu and P. Li, \"{original['title']}\" ({original['journal']}, "
        f"{original['year']}), with an exact event-driven solver of its piecewise-linear model and a register of "
        f"the paper's claims, each checked under every reading its words admit. Of the {n_findings} sentences "
        f"the register quotes, {counts['reproduced']} are reproduced, {counts['consistent']} consistent, "
        f"{counts['partially_reproduced']} partially reproduced, {counts['not_reproduced']} not reproduced, "
        f"{counts['undetermined']} undetermined and {counts['untestable']} untestable.")
    meta = metadata(citation, title, abstract)
    names = {"meta": {k: typ(v) if isinstance(v, str) else v for k, v in meta.items()},
             "literal": {k: string(v) for k, v in meta.items() if isinstance(v, str)},
             "author_literals": [string(a["name"]) for a in meta["authors"]],
             "count": {k: str(v) for k, v in counts.items()}, "n_findings": str(n_findings), "n_rows": str(n_rows),
             "rule": typ(RULE), "number": {k: typ(v) for k, v in _numbers(rows, read_netcdf(inputs["checks"]),
                                                                         facts).items()},
             "verdict": {r["claim_id"]: typ(r["status"].replace("_", " ")) for r in rows},
             "table": _tables(rows, readings), "authors": [typ(a["name"]) for a in meta["authors"]],
             # the figures as the plotting jobs drew them, by their path from the source
             "figure": {name: string(os.path.relpath(path, Path(outputs["source"]).parent))
                        for name, path in figures.items()}}
    environment = jinja2.Environment(undefined=jinja2.StrictUndefined, keep_trailing_newline=True,
                                     autoescape=False)
    source = environment.from_string(Path(inputs["template"]).read_text(encoding="utf-8")).render(names)
    root = Path(os.path.commonpath([Path(p).resolve() for p in (outputs["source"], *figures.values())]))
    write_text(Path(inputs["bibliography"]).read_text(encoding="utf-8"), outputs["bibliography"])
    write_text(yaml.safe_dump(meta, sort_keys=False, allow_unicode=True, width=100), outputs["metadata"])
    write_text(source, outputs["source"])
    with replaced(outputs["pdf"]) as tmp:
        typst.compile(str(outputs["source"]), output=str(tmp), root=str(root), pdf_standards="a-2b",
                      ignore_system_fonts=True)  # its date the run's: publish compares the sources
    return title
