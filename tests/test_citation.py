"""The citation metadata agree: CITATION.cff, .zenodo.json, codemeta.json and pyproject.toml."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
CFF = yaml.safe_load((ROOT / "CITATION.cff").read_text())
ZENODO = json.loads((ROOT / ".zenodo.json").read_text())
CODEMETA = json.loads((ROOT / "codemeta.json").read_text())
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
PAPER_DOI = "10.3233/SAV-130800"


def _words(text: str) -> str:
    return " ".join(text.split())


def test_title_abstract_and_version_agree():
    assert _words(ZENODO["title"]) == _words(CFF["title"]) == _words(CODEMETA["name"])
    assert _words(ZENODO["description"]) == _words(CFF["abstract"]) == _words(CODEMETA["description"])
    assert ZENODO["version"] == CFF["version"] == CODEMETA["version"] == PROJECT["version"]
    # a release date goes with a release (a tag and its archive); until then none of the three claims one
    assert ZENODO.get("publication_date") == CFF.get("date-released") == CODEMETA.get("datePublished")


def test_authors_keywords_and_licences_agree():
    names = [a["name"] for a in CFF["authors"]]
    assert [c["name"] for c in ZENODO["creators"]] == names == [a["name"] for a in CODEMETA["author"]]
    assert [a["name"] for a in PROJECT["authors"]] == names
    assert ZENODO["keywords"] == CFF["keywords"] == CODEMETA["keywords"]
    assert CFF["license"] == ["MIT", "CC-BY-4.0"]
    # the deposit takes one licence, the software's; the text's and the figures' CC BY 4.0 is named in its notes
    assert ZENODO["license"] == PROJECT["license"] == CFF["license"][0] == "MIT"
    assert all(f"{name} for the" in ZENODO["notes"] for name in CFF["license"])
    assert CODEMETA["license"] == [f"https://spdx.org/licenses/{name}" for name in CFF["license"]]
    assert (ROOT / "LICENSE").exists() and "creativecommons.org/licenses/by/4.0" in (
        ROOT / "LICENSE-CC-BY-4.0.md"
    ).read_text()


def test_each_cites_the_replicated_paper():
    (paper,) = CFF["references"]
    assert paper["doi"] == PAPER_DOI
    # a replication is derived from the original (its model, equations and figures), not a supplement to it
    assert ZENODO["related_identifiers"] == [{"identifier": PAPER_DOI, "relation": "isDerivedFrom", "scheme": "doi",
                                              "resource_type": "publication-article"}]
    reference = CODEMETA["referencePublication"]
    assert reference["identifier"] == f"https://doi.org/{PAPER_DOI}"
    assert reference["name"] == paper["title"]
    assert [a["familyName"] for a in reference["author"]] == [a["family-names"] for a in paper["authors"]]
