"""No circle of imports among the engine's modules: each imports only modules below it.

Every import counts, wherever it stands: at the top, inside a function, or under ``if
TYPE_CHECKING:``. A circle in the layering is a circle even where Python never runs the
import: the modules in it cannot be read, tested or changed one without the other.
``from . import kernels`` imports the module ``engine.kernels``, not the package's names, so the
package's re-exports in ``engine/__init__.py`` close no circle.
"""

from __future__ import annotations

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
