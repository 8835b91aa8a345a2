"""No circle of imports among the engine's modules: each imports only modules below it.

Every import counts, wherever it stands: at the top, inside a function, or under ``if
TYPE_CHECKING:``. A circle in the layering is a circle even where Python never runs the
import: the modules in it cannot be read, tested or changed one without the other.
``from . import kernels`` imports the module ``engine.kernels``, not the package's names, so the
package's re-exports in ``engine/__init__.py`` close no circle.
"""

from __future__ import annotations

import ast

from test_layers import ENGINE, import_statements, module_name


def imports_of(source: str, module: str, is_package: bool, known: set[str]) -> set[str]:
    """The modules of ``known`` that ``source`` (the text of ``module``) imports, anywhere in it.

    ``from p import name`` imports the module ``p.name`` when there is one, else ``p`` (for
    its names).
    """
    found: set[str] = set()
    for origin, names in import_statements(source, module, is_package):
        taken = [f"{origin}.{name}" for name in names]
        found.update([m if m in known else origin for m in taken] or [origin])
    return (found & known) - {module}


def engine_graph() -> dict[str, set[str]]:
    """Module name -> the engine's modules it imports, for every module under engine/."""
    paths = sorted(ENGINE.rglob("*.py"))
    known = {module_name(p) for p in paths}
    return {
        module_name(p): imports_of(
            p.read_text(encoding="utf-8"), module_name(p), p.name == "__init__.py", known
        )
        for p in paths
    }


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """A circle in ``graph`` (module -> the modules it imports): its modules in order, each
    importing the next, the first again at the end; None when there is none."""
    done: set[str] = set()
    path: list[str] = []  # the modules being walked, each importing the next

    def walk(module: str) -> list[str] | None:
        path.append(module)
        for imported in sorted(graph[module]):
            if imported in path:
                return path[path.index(imported) :] + [imported]
            if imported not in done:
                cycle = walk(imported)
                if cycle is not None:
                    return cycle
        path.pop()
        done.add(module)
        return None

    for module in sorted(graph):
        if module not in done:
            cycle = walk(module)
            if cycle is not None:
                return cycle
    return None


def test_the_scanner_sees_every_import_and_resolves_it() -> None:
    known = {"engine", "engine.a", "engine.b", "engine.c", "engine.d", "engine.render"}
    known |= {"engine.render.draw"}
    source = (
        "from typing import TYPE_CHECKING\n"
        "from . import a\n"
        "from .b import Thing\n"
        "if TYPE_CHECKING:\n"
        "    from .c import Other\n"
        "def f():\n"
        "    import engine.d\n"
        "    from ..render import draw\n"
    )
    found = imports_of(source, "engine.render.scene", False, known)
    assert found == {"engine.render", "engine.render.draw", "engine.d"}
    found = imports_of(source, "engine.x", False, known)
    assert found == {"engine.a", "engine.b", "engine.c", "engine.d"}  # not the package engine
    # A name that is no module is the package's: importing it imports the package.
    found = imports_of("from .. import a, Vector", "engine.render", True, known)
    assert found == {"engine", "engine.a"}


def test_a_circle_is_found_with_its_modules_in_order() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    assert find_cycle(graph) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None


def test_the_engines_modules_form_no_circle_of_imports() -> None:
    graph = engine_graph()
    assert len(graph) > 50 and "engine.body" in graph["engine.world"]  # the scan found them
    cycle = find_cycle(graph)
    assert cycle is None, (
        "a circle of imports (each imports the next): "
        + " -> ".join(cycle)
        + "; the lower module must not import the higher one, even under TYPE_CHECKING or "
        "inside a function (move the shared part down, or take what it needs as an argument "
        "or by a Protocol)"
    )


# -- The layers, in the folders ------------------------------------------------------------------

#: The engine's layers, bottom up: a module imports modules of its own layer or of one below.
#: The core is the lesson's own (engine/*.py but the doors); the doors open the rest to a user.
LAYERS = ("core", "geometry", "dynamics", "exact", "pipeline", "door", "render")
#: The top-level modules that are doors, not core: each may import any layer below the renderer.
DOORS = {
    "engine", "engine.world", "engine.particles", "engine.measure", "engine.habits",
    "engine.warmup",
}  # fmt: skip


def layer(module: str) -> str:
    """The layer of an engine module: its folder's, or the core's or a door's at the top."""
    parts = module.split(".")
    if module in DOORS:
        return "door"
    if len(parts) == 2 and parts[1] not in LAYERS:
        return "core"
    assert parts[1] in LAYERS, f"{module}: engine/{parts[1]}/ is no layer of {LAYERS}"
    return parts[1]


def run_time_imports(source: str, module: str, is_package: bool, known: set[str]) -> set[str]:
    """The modules of ``known`` that ``source`` imports when it runs: the imports under ``if
    TYPE_CHECKING:`` left out (an annotation names a type; it loads nothing, and a circle
    through one is still found by the test above)."""
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test).endswith("TYPE_CHECKING"):
            node.body = [ast.Pass()]
    return imports_of(ast.unparse(tree), module, is_package, known)


def test_the_layer_scanner_leaves_out_annotations_only() -> None:
    known = {"engine.a", "engine.b"}
    source = (
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from .a import A\n"
        "from .b import B\n"
    )
    assert run_time_imports(source, "engine.x", False, known) == {"engine.b"}
    assert layer("engine.body") == "core" and layer("engine.world") == "door"
    assert layer("engine.geometry.manifold") == "geometry"


def test_no_module_imports_one_of_a_layer_above_it() -> None:
    paths = sorted(ENGINE.rglob("*.py"))
    known = {module_name(p) for p in paths}
    up: dict[str, list[str]] = {}
    for p in paths:
        module = module_name(p)
        rank = LAYERS.index(layer(module))
        found = run_time_imports(
            p.read_text(encoding="utf-8"), module, p.name == "__init__.py", known
        )
        above = sorted(m for m in found if LAYERS.index(layer(m)) > rank)
        if above:
            up[module] = above
    assert len(known) > 90  # the scan found the engine
    assert up == {}, (
        f"imports of a higher layer (the layers, bottom up: {', '.join(LAYERS)}); move the shared "
        "part down, or take what it needs as an argument"
    )
