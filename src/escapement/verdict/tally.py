"""The headline of the verdict: the paper's quoted words counted as findings, read from the claims table alone;
each quote is one finding however many rows (its parts) check it, and rows beyond the paper are none.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from .rule import EVIDENCE, ORIGINS, STATUSES, finding_status

__all__ = ["findings", "findings_table", "headline", "vocabulary_table"]

ORDER = ("reproduced", "consistent", "partially_reproduced", "not_reproduced", "undetermined", "untestable")


def findings(rows: Iterable[Mapping[str, str]]) -> dict[str, tuple[str, list[Mapping[str, str]]]]:
    """Each finding (a sentence of the paper) with its status and its rows, in the table's order."""
    grouped: dict[str, list[Mapping[str, str]]] = {}
    for row in rows:
        if row["status"] not in STATUSES:
            raise ValueError(f"claim '{row['claim_id']}' has status = {row['status']!r}, which the vocabulary does "
                             "not define")
        if row["origin"] == "paper":
            grouped.setdefault(row["finding"], []).append(row)
    return {name: (finding_status(r["status"] for r in parts), parts) for name, parts in grouped.items()}


def headline(rows: Iterable[Mapping[str, str]]) -> str:
    """The verdict's first line: the findings counted by status (failed when none is even partially reproduced)."""
    rows = list(rows)
    found = findings(rows)
    counts = {s: sum(status == s for status, _ in found.values()) for s in ORDER}
    beyond = len(rows) - sum(len(parts) for _, parts in found.values())
    word = ("Failed" if not counts["reproduced"] + counts["partially_reproduced"]
            else "Full" if counts["reproduced"] == len(found) else "Partial")
    return (f"{word} replication: {counts['reproduced']} of {len(found)} findings reproduced, "
            + ", ".join(f"{counts[s]} {s.replace('_', ' ')}" for s in ORDER[1:])
            + f" ({beyond} row{'' if beyond == 1 else 's'} beyond the paper, not counted).")


def findings_table(rows: Iterable[Mapping[str, str]]) -> list[dict[str, str]]:
    """One row per finding: its name, its quote, its status, and its rows each with its part and status."""
    return [{"finding": name, "quote": parts[0]["quote"], "verdict": status.replace("_", " "),
             "rows": ", ".join(f"`{r['claim_id']}`" + (f" ({r['part']}: {r['status'].replace('_', ' ')})"
                                                       if len(parts) > 1 else "") for r in parts)}
            for name, (status, parts) in sorted(findings(rows).items(), key=lambda kv: (ORDER.index(kv[1][0]), kv[0]))]


def vocabulary_table() -> list[dict[str, str]]:
    """The statuses, kinds of evidence and origins with their meanings, as the vocabulary defines them."""
    return ([{"word": f"status: {w.replace('_', ' ')}", "meaning": m} for w, m in STATUSES.items()]
            + [{"word": f"evidence: {w.replace('_', ' ')}", "meaning": m} for w, m in EVIDENCE.items()]
            + [{"word": f"origin: {w}", "meaning": m} for w, m in ORIGINS.items()])
