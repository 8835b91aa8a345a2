"""The layers hold in the code: the engine never imports its demos, and its core never the renderer.

The layers, bottom up: the engine's core (``engine/`` outside ``engine/render/``: numpy and the
standard library), the renderer (``engine/render/``, the only part that imports pygame), the
demos (``demos/``), and the benchmarks (``demos/bench/``), which time all of them. Each layer
imports only those below it, so a game can use the physics without pygame, and the engine can
be shipped and tested without its demos.
"""

from __future__ import annotations

import ast
import importlib
import pkgutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
ENGINE = ROOT / "engine"


def module_name(path: Path) -> str:
    """``engine/render/scene.py`` -> ``engine.render.scene``; a package's ``__init__`` -> it."""
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def import_statements(
    source: str, module: str, is_package: bool = False
) -> Iterator[tuple[str, tuple[str, ...]]]:
    """Each import statement in ``source`` (the text of ``module``), inside functions too: the
    module it names, relative imports resolved, and the names it takes from it (none for
    ``import a.b``)."""
    package = module if is_package else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, ()
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                origin = ".".join(base + ([node.module] if node.module else []))
            else:
                origin = node.module or ""
            yield origin, tuple(alias.name for alias in node.names)


def imported_names(source: str, module: str, is_package: bool = False) -> set[str]:
    """Every module ``source`` (the text of ``module``) imports, relative imports resolved.

    Counts ``import a.b``, ``from a import b`` (as ``a`` and ``a.b``), imports inside
    functions, and ``importlib.import_module("a.b")`` with a literal name.
    """
    found: set[str] = set()
    for origin, names in import_statements(source, module, is_package):
        found.add(origin)
        found.update(f"{origin}.{name}" for name in names)
    for node in ast.walk(ast.parse(source)):
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute)
            and node.func.attr == "import_module"
            and node.args
            and isinstance(node.args[0], ast.Constant)
            and isinstance(node.args[0].value, str)
        ):
            found.add(node.args[0].value)
    return found


def is_under(name: str, top: str) -> bool:
    """Whether the module ``name`` is ``top`` or inside it."""
    return name == top or name.startswith(top + ".")


def engine_imports() -> dict[str, set[str]]:
    """Module name -> the modules it imports, for every module under engine/."""
    return {
        module_name(path): imported_names(
            path.read_text(encoding="utf-8"), module_name(path), path.name == "__init__.py"
        )
        for path in sorted(ENGINE.rglob("*.py"))
    }


def test_the_scanner_sees_every_way_of_importing() -> None:
    source = (
        "import demos.fireworks\n"
        "from ..render import draw\n"
        "def f():\n"
        "    import pygame\n"
        "    importlib.import_module('demos.car')\n"
    )
    names = imported_names(source, "engine.bench.core")
    assert {"demos.fireworks", "engine.render", "engine.render.draw", "pygame"} <= names
    assert "demos.car" in names
    assert imported_names("from . import scene", "engine.render", is_package=True) == {
        "engine.render",
        "engine.render.scene",
    }


def test_nothing_under_engine_imports_the_demos() -> None:
    imports = engine_imports()
    assert len(imports) > 10  # the scan found the engine
    bad = {m: sorted(n for n in names if is_under(n, "demos")) for m, names in imports.items()}
    assert {m: names for m, names in bad.items() if names} == {}


def test_the_engine_core_never_imports_the_renderer_or_pygame() -> None:
    core = {m: names for m, names in engine_imports().items() if not is_under(m, "engine.render")}
    assert "engine.world" in core and "engine.particles" in core
    bad = {
        m: sorted(n for n in names if is_under(n, "engine.render") or is_under(n, "pygame"))
        for m, names in core.items()
    }
    assert {m: names for m, names in bad.items() if names} == {}


def test_importing_every_core_module_loads_neither_pygame_nor_the_demos() -> None:
    # The same rule at run time, in a fresh interpreter: what actually gets loaded.
    script = (
        "import importlib, sys, engine\n"
        "from pathlib import Path\n"
        "top = Path(engine.__file__).parent\n"
        "for p in sorted(top.rglob('*.py')):\n"
        "    m = '.'.join(p.relative_to(top.parent).with_suffix('').parts)\n"
        "    if not m.startswith('engine.render'):\n"
        "        importlib.import_module(m.removesuffix('.__init__'))\n"
        "assert 'engine.pipeline.game_step' in sys.modules  # the walk went into the folders\n"
        "bad = [n for n in sys.modules if n.split('.')[0] in ('pygame', 'demos')]\n"
        "print(sorted(bad + [n for n in sys.modules if n.startswith('engine.render')]))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert run.stdout.strip() == "[]", run.stdout


def test_every_benchmark_module_is_a_topic_of_the_one_command() -> None:
    # `python -m demos.bench` runs every topic in TOPICS: a new benchmark module must be one.
    bench = importlib.import_module("demos.bench")
    modules = {
        f"demos.bench.{m.name}"
        for m in pkgutil.iter_modules(bench.__path__)
        if m.name != "__main__"
    }
    assert sorted(bench.TOPICS.values()) == sorted(modules)
    for name in modules:
        assert callable(importlib.import_module(name).report)


def test_the_benchmark_command_refuses_an_unknown_topic(capsys) -> None:
    from demos.bench.__main__ import main

    with pytest.raises(SystemExit) as info:
        main(["nosuchtopic"])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "nosuchtopic" in err and "core" in err
