"""The replication as a ReScience C article, written by the run: ``metadata.yaml`` in the journal's fields, and
``article.typ`` from ``workflow/templates/article.typ``, typeset by Typst to ``article.pdf``, PDF/A-2b.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import yaml

from ..io.netcdf import read_csv, read_variables, replaced, write_text
from ..model.parameters import Parameters
from ..model.quantities import MODEL_KEYS
from ..paper import corrected, printed as pe
from ..paper.printed_axes import FIG3_PERIOD, limits_match, panel
from ..verdict.rule import EVIDENCE, STATUSES, fmt
from ..verdict.scores import joint_candidates, panel_candidates, read_scores, summary
from ..verdict.tally import ORDER, findings, headline
from .docs import fill
from .logs import logged
from .tables import LIMIT_COLUMNS, WORK_PRECISION_COLUMNS, read_claims

__all__ = ["RULE", "keywords", "metadata", "prefix", "string", "typ", "write_article"]

#: the rule that names the article a replication or a failed one, from the findings' statuses
RULE = ("the title reads [Re] when the paper's findings that are reproduced outnumber those that fail in part or in "
        "whole (not reproduced or partially reproduced), and [¬Re] otherwise; consistent, undetermined and untestable "
        "findings count on neither side")
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
    failed = counts["not_reproduced"] + counts["partially_reproduced"]
    return "[Re]" if counts["reproduced"] > failed else "[¬Re]"


def keywords(citation: Mapping) -> list[str]:
    return list(dict.fromkeys(["rescience c", "replication", *citation["keywords"], "python"]))


def metadata(citation: Mapping, title: str, abstract: str) -> dict:
    """The article's ``metadata.yaml`` in ReScience C's field names, from ``CITATION.cff`` (placeholders stay so)."""
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


def _value(paper: float, run: float, status: str = "—") -> dict:
    """One row of the table of values: the paper's and the run's, their relative difference, the status."""
    return {"paper": typ(fmt(paper, 12)), "run": typ(fmt(run, 12)), "diff": typ(fmt(abs(run - paper) / abs(paper), 2)),
            "status": typ(status.replace("_", " "))}


def _equations(rows: Mapping[str, Mapping], path: str) -> dict[str, dict]:
    """Eqs. (22e), (23) and (25) as printed and corrected, on the last cycle of ``path`` (a Fig. 3 case) against its
    simulated times; (22e) written out here, since the model's closed forms give that time only inside the period."""
    v = read_variables(path, ("event_time", "event_kind", "velocity_before_impact", "period", *MODEL_KEYS))
    p, v1, period = Parameters(**{k: float(v[k]) for k in MODEL_KEYS}), *(float(v[k][-1]) for k in (
        "velocity_before_impact", "period"))
    start = np.flatnonzero(v["event_kind"] == 1)[-2]  # the last complete cycle's impact at a1, then a2, a3, a4
    c, w = p.zone_offset, p.omega
    h3 = math.hypot(p.a3 + c, corrected.cycle_velocities(v1, p)["v4p"] / w)
    s, v1p = pe.symbols_of(p), (1 - p.b) * v1  # as read: signed positions, f, the velocity after the impact
    fixed = {"eq22e_step_time": (float(v["event_time"][start + 3] - v["event_time"][start + 2]),
                                 pe.zone_left_time_22e(corrected.cycle_velocities(v1, p)["v4p"], s),
                                 (math.acos((p.a4 + c) / h3) - math.acos((p.a3 + c) / h3)) / w),
             "eq23_period": (period, pe.period_23(v1, p), corrected.period(v1, p)),
             "eq25_force_perturbation": (period, p.natural_period + 2 * (pe.phase_jump_24(v1, v1p, s)
                                                                         + pe.zone_change_25(v1p, s)),
                                         corrected.period_from_perturbations(v1, p))}
    return {claim: {"printed": _value(printed, run, rows[claim]["status"]), "corrected": _value(right, run)}
            for claim, (run, printed, right) in fixed.items()}


def _axes(rows: Sequence[Mapping], limits: Sequence[Mapping]) -> str:
    """Each axis claim as Typst cells: the printed limits and the run's, how many of them agree, its status."""
    claim, judged = {r["claim_id"]: r for r in rows}, {}
    for row in limits:
        axis = panel(row["figure"], row["panel"]).axes[row["axis"]]
        shown = judged.setdefault(row["claim_id"], {"printed": [], "run": [], "agree": 0, "of": 0})
        shown["agree"] += limits_match(float(row["low"]), float(row["high"]), axis.low, axis.high, axis.step)
        shown["of"] += 2
        for kind, low, high in (("printed", axis.low, axis.high), ("run", float(row["low"]), float(row["high"]))):
            shown[kind].append(f"{axis.label}: [{fmt(low, 6)}, {fmt(high, 6)}]")
    return ",\n".join(f"[{typ(claim[c]['source'])}], [{typ('; '.join(shown['printed']))}], "
                      f"[{typ('; '.join(shown['run']))}], [{shown['agree']} of {shown['of']} limits], "
                      f"[{typ(claim[c]['status'].replace('_', ' '))}]" for c, shown in judged.items())


def _readings(scores: Sequence[Mapping]) -> tuple[str, dict[str, str]]:
    """Per printed panel (and Fig. 4's two together) as Typst cells: the best score, how many readings tie at it and
    only the words in which they differ; and the tie in words by panel."""
    candidates = panel_candidates(scores)
    if any(figure == "4" for figure, _ in candidates):
        candidates[("4", "both panels")] = joint_candidates(scores, "4")
    cells, ties = [], {}
    for (figure, name), c in sorted(candidates.items(), key=lambda item: item[0][0]):
        _, groups = c.tied()
        words = [re.split(r"; |, ", group[0]) for group in groups]  # a reading's words, field by field
        words = words if len({len(w) for w in words}) == 1 else [group[0].split("; ") for group in groups]
        differ = [" | ".join(dict.fromkeys(f)) for f in zip(*words) if len(set(f)) > 1] or groups[0][:1]
        ties[f"{figure} {name}"] = (f"{len(groups)} of {len(c.scores)} readings tie (undetermined)" if len(groups) > 1
                                    else f"one of {len(c.scores)} readings leads" if len(groups[0]) == 1
                                    else f"{len(groups[0])} identical of {len(c.scores)} readings lead")
        cells.append(f"[{typ(figure)} {typ(name)}], [{typ(summary(c)[0].replace(' with the default locator', ''))}], "
                     f"[{len(groups)} of {len(c.scores)}], [{typ('; '.join(differ))}]")
    return ",\n".join(cells), ties


def _register(rows: Sequence[Mapping]) -> str:
    """Every row of the claims table as Typst cells, the paper's words verbatim once for the rows that quote them."""
    cells = []
    for _, group in itertools.groupby(rows, key=lambda r: r["quote"] or id(r)):  # a row without words stands alone
        group = list(group)
        for i, r in enumerate(group):
            words = f"table.cell(rowspan: {len(group)})[{typ(r['quote'])}], " if i == 0 else ""
            source = r["source"] + (" (beyond the paper)" if r["origin"] == "beyond" else "")
            cells.append(f"[{typ(source)}], {words}[{typ(r['part'])}], [{typ(r['evidence'].replace('_', ' '))}], "
                         f"[{typ(r['status'].replace('_', ' '))}]")
    return ",\n".join(cells)


def write_article(inputs: Mapping[str, str | Sequence[str]], outputs: Mapping[str, str], log: str,
                  config: Mapping) -> str:
    """The job of rule ``render_article``: the ``metadata``, ``source``, ``bibliography`` and ``pdf`` of ``outputs``
    and the figures it includes; the title."""
    import typst

    with logged(log, "render_article") as logger:
        rows, folder = read_claims(inputs["claims"]), Path(outputs["source"]).parent
        by_id, found = {r["claim_id"]: r for r in rows}, findings(rows)
        counts = {s: sum(status == s for status, _ in found.values()) for s in ORDER}
        citation = yaml.safe_load(Path(inputs["citation"]).read_text(encoding="utf-8"))
        original = next(r for r in citation["references"] if r.get("doi"))
        checks = read_variables(inputs["checks"], ("group", "label", "period", "velocity", "multiplier",
                                                   "fixed_point_eq16"))
        paper = {checks["label"][i][-1]: i for i, group in enumerate(checks["group"]) if group == "paper"}
        exact = next(row for row in read_csv(inputs["benchmark"], WORK_PRECISION_COLUMNS) if row["method"] == "exact")
        number = {name: {case: typ(fmt(float(checks[name][i]), digits)) for case, i in paper.items()}
                  for name, digits in (("period", 12), ("velocity", 12), ("multiplier", 10))}
        values = {case: {"period": _value(FIG3_PERIOD, checks["period"][i],
                                          by_id[f"fig3_period_{case}"]["status"]),
                         "velocity": _value(checks["fixed_point_eq16"][i], checks["velocity"][i],
                                            by_id[f"eq19_fixed_point_case_{case}"]["status"]),
                         "multiplier": _value(pe.multiplier_21_of(config["model"]["b"]), checks["multiplier"][i],
                                              by_id["eq21_multiplier"]["status"])} for case, i in paper.items()}
        readings, ties = _readings(read_scores(inputs["readings"]))
        names = {"authors": [typ(a["name"]) for a in citation["authors"]], "rule": typ(RULE),
                 "author_literals": [string(a["name"]) for a in citation["authors"]],
                 "keyword_literals": [string(k) for k in keywords(citation)],
                 "statuses": {k.replace("_", " "): typ(v) for k, v in STATUSES.items()},
                 "evidence": {k.replace("_", " "): typ(v) for k, v in EVIDENCE.items()},
                 "config": config, "count": counts, "n_findings": len(found), "n_rows": len(rows), "ties": ties,
                 "replication": headline(rows).split(":")[0].lower(),  # full, partial or failed, by the tally
                 "number": {**number, "exact_error_velocity": typ(fmt(float(exact["error_velocity"]), 2))},
                 "verdict": {r["claim_id"]: typ(r["status"].replace("_", " ")) for r in rows},
                 "finding": {name: typ(status.replace("_", " ")) for name, (status, _) in found.items()},
                 "values": values, "equations": _equations(by_id, inputs["fig3"][0]),
                 "table": {"axes": _axes(rows, read_csv(inputs["limits"], LIMIT_COLUMNS)), "readings": readings,
                           "register": _register(rows)},
                 "figure": {Path(path).stem: f"figures/{Path(path).name}" for path in inputs["figures"]}}
        template = Path(inputs["template"]).read_text(encoding="utf-8")
        abstract = " ".join(fill(template.split("{#- abstract -#}")[1], inputs["template"], names).split())
        meta = metadata(citation, f"{prefix(counts)} {original['title']}", abstract.replace("\\", ""))
        names.update(meta={k: typ(v) if isinstance(v, str) else v for k, v in meta.items()},
                     literal={k: string(v) for k, v in meta.items() if isinstance(v, str)})
        source = fill(template, inputs["template"], names)
        for path in inputs["figures"]:
            write_text(Path(path).read_text(encoding="utf-8"), folder / "figures" / Path(path).name)
        write_text(Path(inputs["bibliography"]).read_text(encoding="utf-8"), outputs["bibliography"])
        write_text(yaml.safe_dump(meta, sort_keys=False, allow_unicode=True, width=100), outputs["metadata"])
        write_text(source, outputs["source"])
        with replaced(outputs["pdf"]) as tmp:
            typst.compile(str(outputs["source"]), output=str(tmp), root=str(folder), pdf_standards="a-2b",
                          ignore_system_fonts=True)  # its date the run's: publish compares the sources
        logger.info("the article: %s", meta["title"])
    return meta["title"]
