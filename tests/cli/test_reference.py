"""docs/reference.md is generated from the declarations: it says exactly what the code declares."""
from __future__ import annotations

from pathlib import Path

from pycram_cli.cli.reference import render
from pycram_cli.designators import DESIGNATORS
from pycram_cli.reasoning import QUERIES


DOCS = Path(__file__).resolve().parents[2] / "docs" / "reference.md"


def test_the_committed_reference_is_what_the_declarations_say():
    assert DOCS.read_text() == render(), "regenerate with: python -m pycram_cli.cli.reference --write docs/reference.md"


def test_every_designator_slot_and_query_parameter_is_in_it():
    text = render()
    for spec in DESIGNATORS.values():
        assert f"### `{spec.name}`" in text
        assert all(f"| `{slot.name}` |" in text for slot in spec.slots)
    for query in QUERIES.values():
        assert f"pycram query {query.usage()}" in text
