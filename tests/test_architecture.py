"""The layering of the package (docs/architecture.md): no module imports a layer above its own,
models never import the runtime, and there are no import cycles between modules.

Every ``import`` statement counts: those inside functions (a deferred import is still a
dependency), those under ``if TYPE_CHECKING:`` (a type-only circle is still a circle of
concerns) and those of package ``__init__`` files. ``from package import name`` depends on the
submodule ``package.name`` when there is one, else on the package itself (its ``__init__``):
a submodule that takes a name from its own package's ``__init__`` while the ``__init__`` imports
the submodule is a cycle.
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest

import bearingsim

PACKAGE = Path(bearingsim.__file__).parent

LAYERS: dict[str, int] = {
    "symbolic": 0, "cache_paths": 0, "keeps": 0, "units": 1, "files": 1, "errors": 1,
    "cache_budget": 1, "series_csv": 1, "input_limits": 2,
    "validation": 2, "sweep_preloads": 2, "sweep_samplers": 0,
    "checks": 2, "physical_checks": 2, "vectors": 1, "entry_points": 1, "sweep_server": 1,
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


def _module_name(path: Path, package: Path = PACKAGE) -> str:
    rel = path.relative_to(package.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_module(name: str, package: Path) -> bool:
    """Whether the dotted ``name`` is a module or package under ``package``'s parent folder."""
    path = package.parent / name.replace(".", "/")
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _imports(path: Path, package: Path = PACKAGE) -> set[str]:
    """Modules of ``package`` that a file imports, wherever the import statement stands."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    here = _module_name(path, package)
    own_package = here if path.name == "__init__.py" else here.rpartition(".")[0]
    root = package.name
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.split(".")[0] == root)
        elif isinstance(node, ast.ImportFrom):
            base = own_package.rsplit(".", node.level - 1)[0] if node.level else ""
            module = ".".join(p for p in (base, node.module) if p)
            if module.split(".")[0] != root:
                continue
            submodules = {f"{module}.{a.name}" for a in node.names
                          if _is_module(f"{module}.{a.name}", package)}
            found |= submodules
            if len(submodules) < len(node.names):
                found.add(module)
    return found


def _graph(package: Path = PACKAGE) -> nx.DiGraph:
    """Import graph of every module of ``package`` (``__init__`` files as their packages)."""
    g = nx.DiGraph()
    for path in package.rglob("*.py"):
        src = _module_name(path, package)
        g.add_node(src)
        for dst in _imports(path, package):
            if dst != src:
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


def _cycles(g: nx.DiGraph) -> list[list[str]]:
    return [c for c in nx.simple_cycles(g) if len(c) > 1]


def test_no_import_cycles():
    cycles = _cycles(_graph())
    assert not cycles, "import cycles:\n" + "\n".join(" -> ".join(c) for c in cycles[:10])


def _write(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root / "toy"


@pytest.mark.parametrize("files, cycle", [
    ({"toy/__init__.py": "", "toy/a.py": "from toy.b import B\n",
      "toy/b.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from toy.a import A\n"},
     {"toy.a", "toy.b"}),
    ({"toy/__init__.py": "", "toy/a.py": "import toy.b\n",
      "toy/b.py": "def f():\n    from toy import a\n    return a\n"},
     {"toy.a", "toy.b"}),
    ({"toy/__init__.py": "", "toy/sub/__init__.py": "from toy.sub.rows import read\n",
      "toy/sub/rows.py": "def read():\n    from toy.sub import _private\n"},
     {"toy.sub", "toy.sub.rows"}),
    ({"toy/__init__.py": "", "toy/a.py": "from . import b\n", "toy/b.py": "from .a import x\n"},
     {"toy.a", "toy.b"}),
])
def test_the_cycle_check_sees_type_only_deferred_init_and_relative_imports(tmp_path, files,
                                                                             cycle):
    cycles = _cycles(_graph(_write(tmp_path, files)))
    assert [set(c) for c in cycles] == [cycle]


def test_a_submodule_imported_by_name_from_its_package_is_no_cycle(tmp_path):
    package = _write(tmp_path, {"toy/__init__.py": "from toy.sub import rows\n",
                                "toy/sub/__init__.py": "from toy.sub.rows import read\n",
                                "toy/sub/rows.py": "from toy.sub import table\n",
                                "toy/sub/table.py": "X = 1\n"})
    assert _cycles(_graph(package)) == []


MODULE_LINES = 520
"""Longest module of bearingsim in lines (about 500: a module that grows past it holds more
than one concern and is split, unless :data:`LONG_MODULES` states why not)."""
LONG_MODULES: dict[str, str] = {}
"""Modules allowed past :data:`MODULE_LINES`, each with the reason."""


def test_no_module_is_longer_than_about_500_lines_without_a_reason():
    long = {str(path.relative_to(PACKAGE)): n for path in sorted(PACKAGE.rglob("*.py"))
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MODULE_LINES}
    unexplained = {name: n for name, n in long.items() if name not in LONG_MODULES}
    assert not unexplained, (f"modules over {MODULE_LINES} lines (split them, or state the "
                             f"reason in LONG_MODULES): {unexplained}")
    stale = set(LONG_MODULES) - set(long)
    assert not stale, f"LONG_MODULES names modules that are no longer long: {sorted(stale)}"
