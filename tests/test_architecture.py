"""The layering of the package (docs/architecture.md): no module imports a layer above its own,
models never import the runtime, and there are no import cycles between modules.

Every ``import`` statement counts, including those inside functions (a deferred import is still
a dependency), except those under ``if TYPE_CHECKING:`` (annotations only).
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest

import bearingsim

PACKAGE = Path(bearingsim.__file__).parent

LAYERS: dict[str, int] = {
    "symbolic": 0, "units": 1, "files": 1, "errors": 1, "validation": 2, "checks": 2, "vectors": 1,
    "plotting": 1, "registry": 2,
    "catalog": 3, "physics": 4,
    "language": 3,
    "components": 5,
    "assemblies": 6,
    "assembler": 4,
    "simulation": 5,
    "studies": 7, "fmu": 7,
    "scenes": 8, "reference": 8,
    "cli": 9,
}
"""Layer of every top-level module or subpackage of bearingsim (a module may import only its own
layer or lower ones)."""

MODELS = ("physics", "components", "assemblies", "catalog", "language")
RUNTIME = ("assembler", "simulation", "studies", "fmu", "scenes", "cli")


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path) -> set[str]:
    """bearingsim modules imported by a file (``from x import y`` counts y when it is a module)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):  # drop the annotation-only imports
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) \
                and node.test.id == "TYPE_CHECKING":
            node.body = []
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("bearingsim"))
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            if node.module.startswith("bearingsim"):
                found.add(node.module)
                for alias in node.names:
                    candidate = f"{node.module}.{alias.name}"
                    if (PACKAGE.parent / candidate.replace(".", "/")).with_suffix(".py").exists() \
                            or (PACKAGE.parent / candidate.replace(".", "/")).is_dir():
                        found.add(candidate)
    return found


def _graph() -> nx.DiGraph:
    g = nx.DiGraph()
    for path in PACKAGE.rglob("*.py"):
        src = _module_name(path)
        g.add_node(src)
        for dst in _imports(path):
            if dst != src and dst != "bearingsim":
                g.add_edge(src, dst)
    return g


def _area(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None


def test_every_area_has_a_layer():
    areas = {_area(m) for m in _graph().nodes} - {None, "__main__"}
    assert areas <= set(LAYERS), f"give these a layer in LAYERS: {sorted(areas - set(LAYERS))}"


def test_no_module_imports_a_higher_layer():
    bad = []
    for src, dst in _graph().edges:
        a, b = _area(src), _area(dst)
        if a is None or b is None or a == b:
            continue
        if LAYERS[b] > LAYERS[a]:
            bad.append(f"{src} -> {dst}")
    assert not bad, "imports of a higher layer:\n" + "\n".join(sorted(bad))


@pytest.mark.parametrize("model_area", MODELS)
def test_models_never_import_the_runtime(model_area):
    bad = [f"{s} -> {d}" for s, d in _graph().edges
           if _area(s) == model_area and _area(d) in RUNTIME]
    assert not bad, "\n".join(sorted(bad))


def test_physics_never_imports_components():
    bad = [f"{s} -> {d}" for s, d in _graph().edges
           if _area(s) == "physics" and _area(d) in ("components", "assemblies", "language")]
    assert not bad, "\n".join(sorted(bad))


def test_no_import_cycles():
    g = _graph()
    # a package's __init__ importing its own submodules is not a cycle of concerns
    g.remove_edges_from([(s, d) for s, d in list(g.edges) if d.startswith(s + ".")])
    cycles = [c for c in nx.simple_cycles(g) if len(c) > 1]
    assert not cycles, "import cycles:\n" + "\n".join(" -> ".join(c) for c in cycles[:10])
