"""Every ```python block in README.md and docs/*.md runs without error.

The blocks of one page run in order in one namespace, as a reader would run them.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [p for p in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
         if "```python" in p.read_text()]


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_doc_examples_run(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__doc__"}
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), re.S)
    for k, code in enumerate(blocks):
        exec(compile(code, f"<{page.name} block {k}>", "exec"), namespace)
