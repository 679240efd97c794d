"""What a study of the user's own changes from the paper's scenes, and which of its kinds run.

A user's block is laid over the paper's key by key at every level (:func:`merged`: mappings merged, other values,
lists too, replaced), so that ``fig3: {cases: {c: ...}}`` adds a case to the paper's two. A kind runs as the
user's study only if its scenes then differ from the paper's: the comparison takes each scene's effective settings
(built by :mod:`escapement.pipeline.config`), the flat mapping of the model's keys and the block's (the block's
win), without the model's keys the kind's data do not depend on (its axes, its zones, the existence map's mass:
``Kind.ignores`` of :mod:`escapement.scenes.settings`), with the symmetric defaults ``a3 = -a1``, ``a4 = -a2``
filled in and nested axes and zones as dotted keys (``F.n``, ``zones.paper``).

:func:`describe` says in one line what differs in a kind (the scenes' ``changes``, their datasets'
``study_changes``, the line its figure shows); :func:`notes` says, one line a kind, why a kind the user's changes
do not reach does not run (or which of the model's changes do not reach a kind that runs), and in one line when
no kind runs.
"""

from __future__ import annotations

import copy
import string
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from ..model.quantities import INITIAL_STATE, PARAMETERS, SYMMETRIC_DEFAULTS
from ..scenes.settings import KINDS

__all__ = ["KindPlan", "changed_model_keys", "describe", "filled", "leaves", "merged", "notes", "number",
           "worded"]

#: the keys of a scene's mapping that place it, not settings of its run
PLACING = ("study", "label", "changes")
#: the quantities a change names with their units
QUANTITIES = {**PARAMETERS, **INITIAL_STATE}


def merged(base: Mapping, over: Mapping) -> dict:
    """``over`` laid over ``base`` key by key at every level, by Snakemake's own rule for configuration sources
    (``snakemake.utils.update_config``: mappings merged, any other value, a list too, replaced); neither changed."""
    from snakemake.utils import update_config

    out = copy.deepcopy(dict(base))
    update_config(out, copy.deepcopy(dict(over)))
    return out


def filled(values: Mapping, leave_out: Iterable[str] = ()) -> dict:
    """``values`` with the symmetric defaults ``a3 = -a1``, ``a4 = -a2`` where the key is absent (and not one
    of ``leave_out``): the geometry the model runs."""
    out = dict(values)
    for key, mirror in SYMMETRIC_DEFAULTS.items():
        if key not in out and key not in leave_out and isinstance(out.get(mirror), int | float):
            out[key] = -out[mirror]
    return out


def leaves(values: Mapping, prefix: str = "") -> dict:
    """The values of a scene's mapping by dotted key (a nested axis or zone as ``F.n``, ``zones.paper``), without
    the keys that place the scene (:data:`PLACING`)."""
    out = {}
    for key, value in values.items():
        if not prefix and key in PLACING:
            continue
        if isinstance(value, Mapping):
            out.update(leaves(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = value
    return out


def changed_model_keys(model: Mapping, paper: Mapping, given: Iterable[str]) -> list[str]:
    """The keys of ``given`` (the user's model block) whose value, the symmetric defaults filled in, differs from
    the paper's model."""
    mine, theirs = filled(model), filled(paper)
    return [key for key in given if mine.get(key) != theirs.get(key)]


def number(value: object) -> str:
    """A value as the configuration would give it: a float by its shortest form that reads back to it (``2`` for
    2.0, ``0.12``), a list item by item."""
    if isinstance(value, bool) or not isinstance(value, int | float | list | tuple):
        return str(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(number(v) for v in value) + "]"
    short = format(value, "g")
    return short if float(short) == value else repr(float(value))


def _unit(key: str) -> str:
    head, _, leaf = key.partition(".")
    if head == "zones":
        return " m"
    q = QUANTITIES.get(head)
    if q is None or q.dimensionless or leaf not in ("", "start", "stop"):
        return ""
    return f" {q.unit_label}"


def worded(key: str, value: object) -> str:
    """``K = 2 N/m``: a dotted key of a scene, its value and the value's units where it has some."""
    return f"{key} = {number(value)}{_unit(key)}"


class _Absent:
    def __repr__(self) -> str:
        return "absent"


ABSENT = _Absent()


def _pairs(block: str, mine: Mapping[str, dict], theirs: Mapping[str, dict]):
    """Each scene of the user's kind beside the paper's scene it replaces, Fig. 5's panels by their place, the
    others by their label: (name, the user's label, the user's scene, the paper's), None for a scene one lacks."""
    if block == "fig5":
        labels, a, b = list(mine), list(mine.values()), list(theirs.values())
        for i in range(max(len(a), len(b))):
            letter = string.ascii_lowercase[i] if i < 26 else str(i + 1)
            yield (f"panel ({letter})", labels[i] if i < len(a) else None, a[i] if i < len(a) else None,
                   b[i] if i < len(b) else None)
        return
    for label in dict.fromkeys([*mine, *theirs]):
        yield KINDS[block].label.format(label) if label else "", label, mine.get(label), theirs.get(label)


def _difference(mine: Mapping, theirs: Mapping) -> dict[str, tuple]:
    return {key: (mine.get(key, ABSENT), theirs.get(key, ABSENT)) for key in dict.fromkeys([*mine, *theirs])
            if mine.get(key, ABSENT) != theirs.get(key, ABSENT)}


def _item(key: str, values: tuple) -> str:
    value, paper = values
    if value is ABSENT:
        return f"{key} left out (paper: {number(paper)}{_unit(key)})"
    if paper is ABSENT:
        return f"{worded(key, value)} (not in the paper)"
    return f"{worded(key, value)} (paper: {number(paper)}{_unit(key)})"


def describe(block: str, mine: Mapping[str, dict], theirs: Mapping[str, dict],
             own: Mapping[str, Sequence[str]] | None = None) -> str:
    """What differs between the user's scenes of ``block`` and the paper's (each a scene's effective settings by
    its label, as :func:`leaves` gives them), in one line; empty if nothing does. A difference every scene shares
    is named once; a scene the paper lacks is named with the keys ``own`` gives for its label (those it sets)."""
    pairs = list(_pairs(block, mine, theirs))
    matched = [_difference(a, b) for _, _, a, b in pairs if a is not None and b is not None]
    shared = dict(matched[0]) if len(pairs) > 1 and matched else {}
    for difference in matched[1:]:
        shared = {k: v for k, v in shared.items() if difference.get(k) == v}
    items = [", ".join(_item(key, values) for key, values in shared.items())] if shared else []
    for name, label, a, b in pairs:
        if a is None:
            items.append(f"the paper's {name}" + (f" ({worded('K', b['K'])})" if block == "fig5" else "")
                         + " left out")
        elif b is None:
            keys = [k for k in (own or {}).get(label, ()) if k in a]
            items.append(f"{name} added" + (f" ({', '.join(worded(k, a[k]) for k in keys)})" if keys else ""))
        else:
            rest = [_item(key, values) for key, values in _difference(a, b).items() if key not in shared]
            if rest:
                items.append(f"{name}: " + ", ".join(rest) if name else ", ".join(rest))
    return "; ".join(items)


@dataclass(frozen=True)
class KindPlan:
    """What became of one kind in the user's study: what differs from the paper's (empty: it does not run), the
    user's model keys that do not reach it, whether the user gave its block, and the block's own keys the user
    changed (dotted, with their values)."""

    block: str
    changes: str
    missed: tuple[str, ...]
    given: bool
    block_changes: tuple[tuple[str, object], ...]


def _model_keys(model: Mapping, keys: Iterable[str]) -> str:
    return ", ".join(f"model.{k} = {number(model[k])}" for k in keys)


def _missed(plan: KindPlan, block: Mapping) -> list[tuple[str, list[str]]]:
    """Why the user's model keys ``plan.missed`` do not reach the kind, each reason with its keys: the keys the kind
    ignores (an axis, the zones), and those its block (or every case of Fig. 3, every panel of Fig. 5) sets
    itself."""
    kind = KINDS[plan.block]
    ignored = [k for k in plan.missed if k in kind.ignored]
    found = [(reason, [k for k in ignored if kind.why([k]) == reason])
             for reason in dict.fromkeys(kind.why([k]) for k in ignored)]
    own = [k for k in plan.missed if k not in kind.ignored]
    if own:
        setter = "its block"
        if plan.block == "fig3" and not all(k in block for k in own):
            setter = "every case"
        elif plan.block == "fig5" and all(k in ("K", "F", "x0") for k in own):
            setter = "every panel"
        found.append((f"{setter} sets its own {' and '.join(own)}", own))
    return found


def _reasons(plan: KindPlan, model: Mapping, block: Mapping) -> list[str]:
    """Why a kind the user's changes touch does not run: :func:`_missed`, with the model's values, and the block's
    own keys that leave its scenes the paper's."""
    reasons = [f"{reason} ({_model_keys(model, keys)})" for reason, keys in _missed(plan, block)]
    if plan.block_changes:
        changed = ", ".join(f"{plan.block}.{k} = {number(v)}" for k, v in plan.block_changes)
        reasons.append(f"{changed} {'gives' if len(plan.block_changes) == 1 else 'give'} the paper's scenes")
    elif plan.given:
        reasons.append(f"your {plan.block} block holds the paper's values")
    return reasons


def notes(study: str, plans: Sequence[KindPlan], model: Mapping, blocks: Mapping[str, Mapping],
          given: Sequence[str]) -> list[str]:
    """One line for each kind the user's changes touch (the model changed, or its block given) that does not run,
    saying why, and one for each kind that some of the model's changes do not reach; one line in all when no kind
    runs though the user gave blocks (``given``, their names). ``model`` and ``blocks`` are the user's, laid over
    the paper's."""
    tag = f"your study '{study}'"
    if not any(plan.changes for plan in plans):
        if not given:
            return []
        moved = dict.fromkeys(key for plan in plans for key in plan.missed)
        changed = [f"model.{k} = {number(model[k])}" for k in moved]
        changed += [f"{plan.block}.{k} = {number(v)}" for plan in plans for k, v in plan.block_changes]
        if not changed:
            return [f"{tag} does not run: the blocks you give ({', '.join(given)}) hold the paper's values"]
        why = [f"{plan.block}: {'; '.join(reason for reason, _ in _missed(plan, blocks[plan.block]))}"
               for plan in plans if plan.missed]
        return [f"{tag} does not run: nothing you changed ({', '.join(changed)}) reaches a scene"
                + (f" ({' | '.join(why)})" if why else ": every kind's scenes stay the paper's")]
    lines = []
    for plan in plans:
        block = blocks[plan.block]
        if plan.changes and plan.missed:
            lines.append(f"{tag}: {_model_keys(model, plan.missed)} {'does' if len(plan.missed) == 1 else 'do'} "
                         f"not reach {plan.block}: " + "; ".join(reason for reason, _ in _missed(plan, block)))
        elif not plan.changes and (plan.missed or plan.given):
            lines.append(f"{tag}: {plan.block} does not run: " + "; ".join(_reasons(plan, model, block)))
    return lines
