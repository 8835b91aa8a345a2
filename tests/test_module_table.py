"""The README's "What is in the box" names every module of the engine, and no module twice."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).parent.parent


def test_every_engine_module_is_in_the_readmes_table() -> None:
    text = (ROOT / "README.md").read_text()
    table = text[text.index("## What is in the box") :]
    table = table[: table.index("\n## ")]
    found = re.findall(r"`(engine/(?:[a-z_]+/)?[a-z_]+\.py)`", table)
    named = [n for n in found if not n.startswith("engine/render/")]  # the renderer's own list
    files = sorted(
        p.relative_to(ROOT).as_posix()
        for p in (ROOT / "engine").rglob("*.py")
        if p.name != "__init__.py" and p.parent.name != "render"
    )
    assert sorted(set(named)) == files
    assert len(named) == len(set(named)), "a module named twice"
