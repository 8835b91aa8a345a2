"""pygame's own Vector2 tests, run against engine.Vector with only the class name rebound.

pygame ships its test suite: ``pygame/tests/math_test.py`` holds ``Vector2TypeTest``. This
file loads a private copy of that module, binds its global ``Vector2`` to ``engine.Vector``
and runs every test method of ``Vector2TypeTest``, one pytest case each. Every test must
pass except those in ``DELIBERATE``, each of which rests on a deliberate difference (the
README's "Vector names") and must fail for that reason: its failure has to match the
pattern given. The list is strict both ways: a test not in it that fails fails the suite,
and a test in it that starts passing fails the suite too, so a new pygame release (a new
test, a changed one) shows up as a failure to look at, not as silence.
"""

from __future__ import annotations

import importlib.util
import re
import unittest
from pathlib import Path
from types import ModuleType

import pygame
import pytest

from engine import Vector

MATH_TEST = Path(pygame.__file__).parent / "tests" / "math_test.py"

# The reasons, shared by several tests.
IMMUTABLE_IP = (
    "immutable: no in-place `_ip` methods (v = v.method(...) instead)",
    r"Vector is immutable, so it has no \w+_ip\(\)",
)
ITEM_ASSIGNMENT = (
    "immutable: no item or slice assignment (a Vector is a tuple)",
    r"'Vector' object does not support item assignment",
)
EXACT_EQ = (
    "== is exact, as a tuple's (so equal vectors hash alike); pygame's == allows 1e-6, "
    "and this test compares rounded results with ==",
    r"AssertionError: Vector\(",
)
LESSON_SCALAR = (
    "the lesson's Vector(x) and Vector(x=1) are (x, 0); pygame's are (x, x)",
    r"AssertionError: 0\.0 != 1\.0",
)

#: pygame test name -> (the deliberate difference it rests on, a regex its failure must match)
DELIBERATE: dict[str, tuple[str, str]] = {
    "testConstructionScalar": LESSON_SCALAR,
    "testConstructionScalarKeywords": LESSON_SCALAR,
    "testAttributeAccess": (
        "immutable: v.x = ... is refused",
        r"AttributeError: Vector is immutable: make a new one",
    ),
    "testSequence": (
        "a Vector is a tuple: a slice is a tuple, (1.2, 3.4), where pygame's is a list "
        "(overriding __getitem__ would slow every v[0] on the hot path), and item "
        "assignment is refused (immutable)",
        r"AssertionError: \(1\.2, 3\.4\) != \[1\.2, 3\.4\]",
    ),
    "testExtendedSlicing": ITEM_ASSIGNMENT,
    "testStr": ("the lesson's str: 'X: 1.2 Y: 3.4', not '[1.2, 3.4]'", r"X: 1\.2 Y: 3\.4"),
    "testRepr": (
        "a repr that round-trips through eval, Vector(1.2, 3.4), not '<Vector2(1.2, 3.4)>' "
        "(so a Vector is not built from its repr string either)",
        r"Vector\(1\.2, 3\.4\)",
    ),
    "test_dot": (
        "* between two vectors is refused in favour of v.dot(w) (the lesson's * was the dot "
        "product, which hides bugs)",
        r"TypeError: Vector \* Vector is ambiguous",
    ),
    "test_collection_abc": (
        "a Vector is a tuple underneath (immutable, hashable, numpy-ready), so it is a "
        "collections.abc.Sequence; pygame's Vector2 deliberately is not",
        r"AssertionError: True is not false",
    ),
    "test_swizzle": (
        "no swizzles: reading v.yx would need a __getattr__, which slows every attribute "
        "lookup; assigning v.xy = ... is refused (immutable)",
        r"'Vector' object has no attribute 'yx'",
    ),
    "test_swizzle_return_types": (
        "no swizzles (see test_swizzle)",
        r"'Vector' object has no attribute 'xy'",
    ),
    "test_update": (
        "immutable: no update(); v = Vector(x, y) instead",
        r"Vector is immutable, so it has no update\(\)",
    ),
    "test_polar": (
        "immutable: v.from_polar(p) cannot change v; Vector.from_polar(p) returns the vector",
        r"Vector is immutable, so v\.from_polar\(\.\.\.\) cannot change v",
    ),
    "test_scale_to_length": (
        "immutable: scale_to_length returns the scaled vector (as pymunk's) instead of "
        "changing v and returning None",
        r"AssertionError: Vector\(1\.0, 1\.0\) != Vector\(1\.76",
    ),
    "test_rotate_rad": (
        EXACT_EQ[0] + ": it expects (cos pi, sin pi) = (-1, 1.2e-16) from rotate_rad(pi), "
        "which gives pygame's exact quarter turn (-1, -0)",
        r"AssertionError: Vector\(-1\.0, -0\.0\) != \(-1\.0, 1\.22",
    ),
    "test_angle_to": (
        EXACT_EQ[0] + ": v.rotate(v.angle_to(w)).normalize() == w.normalize() holds to "
        "1e-16, not exactly",
        EXACT_EQ[1],
    ),
    "test_rotate_ip": IMMUTABLE_IP,
    "test_rotate_rad_ip": IMMUTABLE_IP,
    "test_normalize_ip": IMMUTABLE_IP,
    "test_reflect_ip": IMMUTABLE_IP,
    # move_towards and clamp_magnitude themselves pass these tests' checks up to the first
    # _ip call; tests/test_vector_names.py checks them against pygame's own results.
    "test_move_towards_basic": IMMUTABLE_IP,
    "test_move_towards_max_distance": IMMUTABLE_IP,
    "test_move_nowhere": IMMUTABLE_IP,
    "test_move_away": IMMUTABLE_IP,
    "test_move_towards_self": IMMUTABLE_IP,
    "test_move_towards_errors": IMMUTABLE_IP,
    "test_clamp_mag_v2_max": IMMUTABLE_IP,
    "test_clamp_mag_v2_min": IMMUTABLE_IP,
    "test_clamp_mag_v2_no_change": IMMUTABLE_IP,
    "test_clamp_mag_v2_edge_cases": IMMUTABLE_IP,
    "test_clamp_mag_v2_errors": IMMUTABLE_IP,
}


def _load() -> ModuleType | None:
    """A private copy of pygame's math_test with ``Vector2`` bound to ``engine.Vector``."""
    if not MATH_TEST.is_file():
        return None
    spec = importlib.util.spec_from_file_location("_pygame_math_test_on_engine_vector", MATH_TEST)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.Vector2 = Vector  # the only change: the name the tests build their vectors with
    return module


MODULE = _load()
# Held in a dict, not as a module-level class: pytest collects any unittest.TestCase class it
# finds at module level and would run it again, without the list of deliberate differences.
PYGAME: dict[str, type[unittest.TestCase]] = (
    {} if MODULE is None else {"Vector2TypeTest": MODULE.Vector2TypeTest}
)
NAMES = [name for case in PYGAME.values() for name in unittest.TestLoader().getTestCaseNames(case)]

needs_pygame_tests = pytest.mark.skipif(
    not PYGAME,
    reason=f"pygame's test suite is not installed ({MATH_TEST} is absent)",
)


def _run(name: str) -> str | None:
    """Run one of pygame's tests; None when it passes, else its failure's traceback."""
    result = unittest.TestResult()
    PYGAME["Vector2TypeTest"](name).run(result)
    problems = result.failures + result.errors
    if result.skipped:
        return f"skipped: {result.skipped[0][1]}"
    return problems[0][1] if problems else None


@needs_pygame_tests
def test_pygame_test_class_is_the_one_this_list_was_written_for() -> None:
    # 69 tests in pygame 2.6.1's Vector2TypeTest; more or fewer means a new pygame to read.
    assert len(NAMES) >= 60, NAMES
    assert pygame.version.vernum >= (2, 5)


@needs_pygame_tests
@pytest.mark.parametrize("name", NAMES)
def test_pygame_vector2_test_on_engine_vector(name: str) -> None:
    failure = _run(name)
    if name not in DELIBERATE:
        assert failure is None, f"pygame's {name} fails on engine.Vector:\n{failure}"
        return
    reason, pattern = DELIBERATE[name]
    assert failure is not None, (
        f"pygame's {name} now passes on engine.Vector: remove it from DELIBERATE "
        f"(it was listed because: {reason})"
    )
    assert re.search(pattern, failure), (
        f"pygame's {name} fails, but not for its listed reason ({reason}); "
        f"expected /{pattern}/ in:\n{failure}"
    )


@needs_pygame_tests
def test_every_listed_exception_is_a_test_pygame_has() -> None:
    # A name that pygame renamed or dropped would otherwise stay in the list for nothing.
    assert set(DELIBERATE) <= set(NAMES), sorted(set(DELIBERATE) - set(NAMES))
