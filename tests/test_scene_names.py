"""Each scene of the paper is named once: whatever calls something by a scene's name runs that scene.

The scenes are defined in ``config/paper.yaml`` only (Fig. 3's cases, Fig. 4, Fig. 5's panels). Wherever the
project's text names one of them (the code and its docstrings, the command line's help, the configuration's
comments, the rules, the templates and the documents rendered from them), a force, spring constant or release
stated with the name, in the forms the project writes them (``F = 1 N``, ``K = 0.1 N/m``, ``x0 = -1 m``,
``x(0) = 3 m``, ``released (from rest) at -1 m``, ``from +1 m``), up to the end of its clause, must be that
scene's; the blocks that run a scene under its name (the benchmark, the long run, the command line's defaults)
must run exactly it. The reader is a pattern, not a parser. The texts are read from the files as they are (a
clone or an archive alike): no test reads the repository's history.
"""

from __future__ import annotations

import re
from pathlib import Path

import yaml

from escapement.cli import DEFAULTS, main
from escapement.pipeline.plan import replication_scenes, study_scenes

ROOT = Path(__file__).resolve().parents[1]
CONFIG = yaml.safe_load((ROOT / "config/paper.yaml").read_text())

NUMBER = r"([+\-−]?\d+(?:\.\d+)?)"
#: what a text may state with a scene's name, each read as the value of one key of the scene
STATED = {
    "F": re.compile(rf"\bF\s*=\s*{NUMBER}\s*N\b(?!\s*/)"),
    "K": re.compile(rf"\bK\s*=\s*{NUMBER}\s*N/m"),
    "x0": re.compile(rf"\bx(?:0|\(0\))\s*=\s*{NUMBER}\s*m\b"
                     rf"|\breleas\w*(?: (?:from )?(?:at )?rest)?(?: at| from)? {NUMBER}\s*m\b|\bfrom {NUMBER}\s*m\b"),
}
#: where a statement about a scene ends: a sentence, a clause, a line, or the name of another scene
END = re.compile(r"(?<!Fig)(?<!Eq)(?<!Sec)(?<!e\.g)(?<!i\.e)\.\s|;|\n|\|")


def scenes() -> dict[str, tuple[re.Pattern, dict[str, float]]]:
    """Each scene's name as the project writes it, and its force, spring constant and release."""
    model, found = CONFIG["model"], {}
    for case, keys in CONFIG["fig3"]["cases"].items():
        name = rf"Fig\. ?3,? ?(?:case )?\({case}\)"
        found[f"Fig. 3 ({case})"] = (re.compile(name), {"F": keys["F"], "K": keys.get("K", model["K"]),
                                                         "x0": keys["x0"]})
    fig4 = CONFIG["fig4"]
    found["Fig. 4"] = (re.compile(r"Fig\. 4\b(?! \()"), {"F": fig4["F"], "K": fig4.get("K", model["K"]),
                                                          "x0": fig4["x0"]})
    fig5 = CONFIG["fig5"]
    for i, k in enumerate(fig5["K"]):
        letter = "abc"[i]
        per_panel = {key: fig5[key][i] if isinstance(fig5[key], list) else fig5[key] for key in ("F", "x0")}
        found[f"Fig. 5 ({letter})"] = (re.compile(rf"Fig\. ?5,? ?(?:panel )?\({letter}\)"), {"K": k, **per_panel})
    return found


SCENES = scenes()
ANY_SCENE = re.compile("|".join(f"(?:{pattern.pattern})" for pattern, _ in SCENES.values()))


def statements(text: str) -> list[tuple[str, str, float, int]]:
    """Every (scene, key, stated value, offset) that ``text`` states with a scene's name."""
    found = []
    for name, (pattern, _) in SCENES.items():
        for match in pattern.finditer(text):
            rest = text[match.end():match.end() + 200]
            stop = min([m.start() for m in (END.search(rest), ANY_SCENE.search(rest)) if m] + [len(rest)])
            for key, stated in STATED.items():
                for value in stated.finditer(rest[:stop]):
                    number = next(g for g in value.groups() if g is not None).replace("−", "-")
                    found.append((name, key, float(number), match.start()))
    return found


def tracked_texts() -> list[Path]:
    """The project's texts: its code, configuration, rules, templates and documents."""
    parts = ("src", "benchmarks", "config", "workflow", "README.md", "REPLICATION.md", "CITATION.cff",
             "codemeta.json", ".zenodo.json")
    found = [path for part in parts for path in ((ROOT / part).rglob("*") if (ROOT / part).is_dir() else
                                                 [ROOT / part])]
    return sorted(p for p in found if p.is_file() and "__pycache__" not in p.parts
                  and p.suffix in {".py", ".md", ".yaml", ".smk", ".rst", ".cff", ".json"})


def test_every_text_that_names_a_scene_states_that_scene():
    texts = {path.relative_to(ROOT).as_posix(): path.read_text(encoding="utf-8") for path in tracked_texts()}
    assert "workflow/templates/README.md" in texts and "src/escapement/cli.py" in texts
    wrong, stated = [], 0
    for where, text in texts.items():
        for name, key, value, offset in statements(text):
            stated += 1
            expected = SCENES[name][1][key]
            if value != expected:
                line = text.count("\n", 0, offset) + 1
                wrong.append(f"{where}:{line}: {name} with {key} = {value:g}, but the scene has {key} = {expected:g}")
    assert not wrong, "\n".join(wrong)
    assert stated >= 10  # the reader finds the statements the documents make (16 when this was written)


def test_the_command_line_help_names_its_defaults_as_the_scene_they_are(capsys):
    assert main(["solve", "--help"]) == 0
    text = capsys.readouterr().out
    said = statements(text)
    assert ("Fig. 3 (a)", "x0", -1.0) in [s[:3] for s in said]
    assert not [s for s in said if s[2] != SCENES[s[0]][1][s[1]]]


def test_the_blocks_that_run_fig3_a_by_name_run_exactly_it():
    """The benchmark, the long run and the command line run Fig. 3 (a) as the fig3 block defines it."""
    scene = study_scenes("replication", CONFIG)["fig3"]["a"].settings
    runs = replication_scenes(CONFIG)
    keys = ("M", "K", "F", "b", "a1", "a2", "x0")
    for block in (runs["benchmark"], runs["long_run"], DEFAULTS):
        assert {k: block[k] for k in keys} == {k: scene[k] for k in keys}
