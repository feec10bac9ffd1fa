"""Component documentation by one template (bearingsim.language.reference), checked over every
Component subclass of bearingsim.components and bearingsim.assemblies."""

from __future__ import annotations

from pathlib import Path

import pytest

from bearingsim.language.declarations import Flow, Potential
from bearingsim.language.reference import (
    component_reference,
    constructor_arguments,
    documented_arguments,
)
from bearingsim.reference import (
    component_classes,
    example_components,
    is_base_class,
    reference_text,
)

CLASSES = component_classes()
EXAMPLES = example_components()
DOCS = Path(__file__).resolve().parents[2] / "docs" / "components.md"


def test_the_walk_finds_the_components():
    names = {c.__name__ for c in CLASSES}
    assert {"Inertia", "RaceContact", "Ball", "MiddleRing", "PMSM", "DuplexPair",
            "DeepGrooveBallBearing", "BallRow", "PalmgrenBearing"} <= names
    assert len(CLASSES) >= 45


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_docstring_summary_and_every_constructor_argument(cls):
    doc = (cls.__doc__ or "").strip()
    assert doc, f"{cls.__name__} has no docstring"
    missing = [a for a in constructor_arguments(cls) if a not in documented_arguments(cls)]
    assert not missing, f"{cls.__name__}: document {missing} in its numpydoc Parameters section"


@pytest.mark.parametrize("cls", [c for c in CLASSES if not is_base_class(c)],
                         ids=lambda c: c.__name__)
def test_every_declaration_has_a_unit_and_a_description(cls):
    assert cls in EXAMPLES, f"add an example of {cls.__name__} to bearingsim.reference"
    component = EXAMPLES[cls]
    for name, decl in component.declarations.items():
        assert decl.unit, f"{cls.__name__}.{name} has no unit"
        assert decl.description.strip(), f"{cls.__name__}.{name} has no description"
    text = component_reference(component)
    for name in component.declarations:
        assert f"| `{name}` |" in text
    for name, connector in component.connectors.items():
        assert f"| `{name}` | {type(connector).__name__} |" in text
        for field, decl in connector.fields.items():
            kind = "flow" if isinstance(decl, Flow) else "potential"
            assert isinstance(decl, (Flow, Potential))
            assert f"`{field}` [" in text and f"({kind})" in text


def test_the_template_renders_parameters_with_unit_value_and_range():
    from bearingsim.components.rotational import SpringDamper

    text = component_reference(SpringDamper(c=250.0, d=0.5))
    assert "| `c` | N.m/rad | 250 | (0, inf] | spring constant |" in text
    assert "| `d` | N.m.s/rad | 0.5 | [0, inf] | damping constant |" in text
    assert "| `flange_a` | Flange | `phi` [rad] (potential), `tau` [N.m] (flow) |" in text


def test_docs_components_md_is_current():
    assert DOCS.read_text(encoding="utf-8") == reference_text(), (
        "docs/components.md is stale: run python -m bearingsim.reference docs/components.md")
