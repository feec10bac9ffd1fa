"""Every ``from bearingsim... import ...`` in ``bench/`` names a module and attribute that exist.

The benchmark modules import most of bearingsim inside their functions (a section imports what
it times), so a module moved in the package breaks a section only when ``make bench`` reaches
it. Imports inside ``try: ... except ImportError`` are left out: they are the ones that read
an older package on purpose (the side-by-side baselines).
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "bench"


def _guarded(tree: ast.AST) -> set[int]:
    """ids of the nodes inside a ``try`` that catches ImportError, and its handlers."""
    guarded = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Try) and any(
                isinstance(h.type, ast.Name) and h.type.id in ("ImportError",
                                                               "ModuleNotFoundError")
                for h in node.handlers):
            guarded |= {id(n) for part in [*node.body, *node.handlers] for n in ast.walk(part)}
    return guarded


def _imports(path: Path) -> list[tuple[int, str, str]]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    guarded = _guarded(tree)
    return [(node.lineno, node.module, alias.name) for node in ast.walk(tree)
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module
            and node.module.split(".")[0] == "bearingsim" and id(node) not in guarded
            for alias in node.names]


@pytest.mark.parametrize("path", sorted(BENCH.glob("*.py")), ids=lambda p: p.name)
def test_bench_imports_resolve(path: Path) -> None:
    missing = []
    for line, module, name in _imports(path):
        try:
            mod = importlib.import_module(module)
        except ImportError as exc:
            missing.append(f"line {line}: {module} ({exc})")
            continue
        if name != "*" and not hasattr(mod, name):
            try:
                importlib.import_module(f"{module}.{name}")
            except ImportError:
                missing.append(f"line {line}: {module}.{name}")
    assert not missing, f"{path.name} imports what bearingsim no longer has: {missing}"
