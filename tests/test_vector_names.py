"""engine.Vector's pygame and pymunk names, checked against pygame's and pymunk's own results.

Each name is run on the same inputs as ``pygame.math.Vector2`` (or pymunk's ``Vec2d``) and
must give the same floats, bit for bit where the arithmetic is the same, and the same kind
of error; where the engine's arithmetic differs on purpose (hypot for lengths, a reflection
without a square root) the bound is a few ulps and the reason is given.
"""

from __future__ import annotations

import math
import pickle
import re
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pygame.math import Vector2

from engine import Vector

try:  # pymunk comes with the bench extra
    from pymunk import Vec2d
except ImportError:  # pragma: no cover - the bench extra is not installed
    Vec2d = None

needs_pymunk = pytest.mark.skipif(Vec2d is None, reason="pymunk (the bench extra) is absent")

EPS = sys.float_info.epsilon

# Components are 0 or at least 1e-100 in size: below ~1e-154, pygame's x*x + y*y underflows
# to 0 (its length of (0, 1e-189) is 0.0), where math.hypot keeps the true length.
coords = st.one_of(
    st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False).filter(
        lambda c: c == 0.0 or abs(c) > 1e-100
    ),
    st.integers(-50, 50).map(float),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, 1e-7, 0.5]),
)
pairs = st.tuples(coords, coords)
angles = st.one_of(
    st.floats(min_value=-1e4, max_value=1e4, allow_nan=False, allow_infinity=False),
    st.sampled_from([0.0, 90.0, -90.0, 180.0, 270.0, 360.0, 359.99999999, 450.0, -720.0]),
)
radians = st.one_of(
    st.floats(min_value=-100, max_value=100, allow_nan=False, allow_infinity=False),
    st.sampled_from([0.0, math.pi, math.pi / 2, -math.pi / 2, 2 * math.pi, math.pi / 4]),
)
fractions = st.floats(min_value=-1.0, max_value=1.0, allow_nan=False)


def same(ours: Any, theirs: Any) -> bool:
    """The same floats, component by component (0.0 and -0.0 alike, as == has them)."""
    a, b = tuple(ours), tuple(theirs)
    return len(a) == len(b) and all(x == y for x, y in zip(a, b, strict=True))


def within_ulps(ours: Any, theirs: Any, ulps: int, scale: float) -> bool:
    """Each component within ``ulps`` units in the last place of ``scale``."""
    tol = ulps * EPS * scale + 1e-300
    return all(abs(x - y) <= tol for x, y in zip(tuple(ours), tuple(theirs), strict=True))


def outcome(call: Callable[[], Any]) -> Any:
    """The result, or the type of the exception raised."""
    try:
        return call()
    except Exception as exc:  # noqa: BLE001 - the point is to compare whatever is raised
        return type(exc)


def same_outcome(ours: Callable[[], Any], theirs: Callable[[], Any]) -> None:
    """Both raise the same kind of error, or both give the same floats."""
    a, b = outcome(ours), outcome(theirs)
    if isinstance(a, type) or isinstance(b, type):
        assert a == b, (a, b)
    elif isinstance(a, float):
        assert a == b, (a, b)
    else:
        assert same(a, b), (a, b)


# -- the same floats as pygame -------------------------------------------------------------


@given(pairs, angles)
def test_rotate_is_pygames_rotate_bit_for_bit(p: tuple[float, float], deg: float) -> None:
    assert same(Vector(*p).rotate(deg), Vector2(p).rotate(deg))


@given(pairs, radians)
def test_rotate_rad_is_pygames_bit_for_bit(p: tuple[float, float], rad: float) -> None:
    assert same(Vector(*p).rotate_rad(rad), Vector2(p).rotate_rad(rad))


def test_lengths_stay_true_where_pygames_underflow_or_overflow() -> None:
    assert Vector(0, 1e-189).length() == 1e-189 and Vector2(0, 1e-189).length() == 0.0
    assert Vector(0, 1e-189).normalize() == (0, 1)  # pygame: "Can't normalize ... zero"
    assert math.isclose(Vector(3e200, 4e200).length(), 5e200, rel_tol=2 * EPS)
    assert Vector2(3e200, 4e200).length() == math.inf


def test_quarter_turns_are_exact() -> None:
    # pygame special-cases multiples of 90 degrees: swaps and sign flips, no cos/sin rounding.
    assert Vector(3, 4).rotate(90) == Vector(-4, 3)
    assert Vector(3, 4).rotate(-90) == Vector(4, -3)
    assert Vector(3, 4).rotate(180) == Vector(-3, -4)
    assert Vector(3, 4).rotate(360 * 5) == Vector(3, 4)
    assert Vector(0, 1).rotate(359.99999999) == Vector(0, 1)  # pygame's issue 214
    assert Vector(3, 4).rotate_rad(math.pi / 2) == Vector(-4, 3)


@given(pairs, pairs)
def test_angle_to_distance_squared_to_and_project_are_pygames(
    p: tuple[float, float], q: tuple[float, float]
) -> None:
    v, w = Vector(*p), Vector2(p)
    assert Vector(*p).angle_to(q) == w.angle_to(q)
    assert v.distance_squared_to(q) == w.distance_squared_to(q)
    same_outcome(lambda: v.project(q), lambda: w.project(q))
    assert v.dot(q) == w.dot(q) and v.cross(q) == w.cross(q)


@given(pairs)
def test_as_polar_and_from_polar_are_pygames(p: tuple[float, float]) -> None:
    v, w = Vector(*p), Vector2(p)
    r, phi = v.as_polar()
    pr, pphi = w.as_polar()
    assert phi == pphi
    # r is math.hypot(x, y), pygame's is sqrt(x*x + y*y): the same to an ulp.
    assert math.isclose(r, pr, rel_tol=2 * EPS, abs_tol=1e-300)
    assert same(Vector.from_polar((pr, pphi)), Vector2.from_polar((pr, pphi)))
    assert same(Vector.from_polar([pr, pphi]), Vector2.from_polar([pr, pphi]))


@given(pairs, st.floats(min_value=0, max_value=1e3), st.floats(min_value=0, max_value=1e3))
def test_clamp_magnitude_is_pygames(p: tuple[float, float], a: float, b: float) -> None:
    v, w = Vector(*p), Vector2(p)
    same_outcome(lambda: v.clamp_magnitude(a), lambda: w.clamp_magnitude(a))
    same_outcome(lambda: v.clamp_magnitude(a, b), lambda: w.clamp_magnitude(a, b))
    same_outcome(lambda: v.clamp_magnitude(-a - 1), lambda: w.clamp_magnitude(-a - 1))


@given(pairs, st.floats(min_value=-1e3, max_value=1e3))
def test_scale_to_length_returns_what_pygame_scales_to(p: tuple[float, float], n: float) -> None:
    v, w = Vector(*p), Vector2(p)
    theirs = outcome(lambda: w.scale_to_length(n))  # pygame changes w and returns None
    ours = outcome(lambda: v.scale_to_length(n))
    if isinstance(theirs, type):
        assert ours is theirs
    else:
        assert same(ours, w)


@given(pairs, pairs, st.floats(min_value=-1e3, max_value=1e3))
def test_move_towards_is_pygames(p: tuple[float, float], q: tuple[float, float], d: float) -> None:
    assert same(Vector(*p).move_towards(q, d), Vector2(p).move_towards(q, d))
    assert same(Vector(*p).move_towards(p, -abs(d)), Vector2(p).move_towards(p, -abs(d)))


@given(pairs, pairs, fractions)
def test_slerp_and_lerp_are_pygames(
    p: tuple[float, float], q: tuple[float, float], t: float
) -> None:
    v, w = Vector(*p), Vector2(p)
    same_outcome(lambda: v.slerp(q, t), lambda: w.slerp(q, t))
    same_outcome(lambda: v.lerp(q, t), lambda: w.lerp(q, t))
    same_outcome(lambda: v.lerp(q, abs(t)), lambda: w.lerp(q, abs(t)))


@given(pairs, pairs)
def test_reflect_agrees_with_pygame_and_is_exact_where_pygame_rounds(
    p: tuple[float, float], n: tuple[float, float]
) -> None:
    v, w = Vector(*p), Vector2(p)
    theirs = outcome(lambda: w.reflect(n))
    ours = outcome(lambda: v.reflect(n))
    if isinstance(theirs, type):
        assert ours is theirs
        return
    # The engine's v - n (2 (v . n) / (n . n)) skips pygame's square root: a few ulps apart.
    assert within_ulps(ours, theirs, 8, v.magnitude()), (ours, theirs)
    # A reflection keeps the length (to rounding) and reflecting twice gives v back.
    assert math.isclose(ours.magnitude(), v.magnitude(), rel_tol=8 * EPS, abs_tol=1e-300)


def test_reflect_exact_cases() -> None:
    assert Vector(1, -1).reflect((0, 1)) == Vector(1, 1)
    assert Vector(1, -1).reflect((0, 3)) == Vector(1, 1)
    assert Vector(1, -1).reflect((-1, 1)) == Vector(-1, 1)  # pygame: (-0.9999999999999996, ...)
    assert Vector(3, 4).reflect((1, 0)) == Vector(-3, 4)


@given(pairs)
def test_length_normalize_is_normalized_agree_with_pygame(p: tuple[float, float]) -> None:
    v, w = Vector(*p), Vector2(p)
    # hypot against pygame's sqrt(x*x + y*y): within an ulp.
    assert math.isclose(v.length(), w.length(), rel_tol=2 * EPS, abs_tol=1e-300)
    assert v.length() == v.magnitude()
    assert v.length_squared() == w.length_squared() == v.magnitude_squared()
    ours, theirs = outcome(v.normalize), outcome(w.normalize)
    if isinstance(theirs, type):
        assert ours is theirs
    else:
        assert within_ulps(ours, theirs, 4, 1.0)
        assert ours.is_normalized() and theirs.is_normalized()
    assert v.is_normalized() == w.is_normalized()


def test_zero_length_errors_are_pygames() -> None:
    zero, tiny = Vector(0, 0), Vector(1e-7, 0)
    cases: list[tuple[Callable[[Any], Any], type[Exception]]] = [
        (lambda v: v.normalize(), ValueError),
        (lambda v: v.scale_to_length(1), ValueError),
        (lambda v: v.clamp_magnitude(3), ValueError),
        (lambda v: v.slerp((1, 0), 0.5), ValueError),
        (lambda v: Vector(1, 0).reflect(v), ValueError),
        (lambda v: Vector(1, 0).project(v), ValueError),
    ]
    for call, error in cases:
        for v in (zero,):
            with pytest.raises(error):
                call(v)
            with pytest.raises(error):
                call(Vector2(v))
    # pygame's thresholds, kept: |v| < 1e-6 cannot be scaled or slerped, |n|^2 < 1e-6 is no
    # normal and no axis to project on.
    for call in (
        lambda v: v.scale_to_length(1),
        lambda v: v.slerp((1, 0), 0.5),
        lambda v: Vector(1, 0).reflect(v * 5),
        lambda v: Vector(1, 0).project(v * 5),
    ):
        with pytest.raises(ValueError):
            call(tiny)
        with pytest.raises(ValueError):
            call(Vector2(tiny))
    with pytest.raises(ValueError, match="Can't normalize Vector of length zero"):
        zero.normalize()
    with pytest.raises(ValueError, match="180 degrees"):
        Vector(1, 0).slerp((-1, 0), 0.5)


@pytest.mark.parametrize(
    "call",
    [
        lambda V: V(1, 2).rotate("90"),
        lambda V: V(1, 2).rotate_rad(None),
        lambda V: V(1, 2).angle_to("ab"),
        lambda V: V(1, 2).move_towards("ab", 1),
        lambda V: V(1, 2).move_towards((3, 4), "far"),
        lambda V: V(1, 2).move_towards((3, 4), 1, 2),
        lambda V: V(1, 2).clamp_magnitude("foo"),
        lambda V: V(1, 2).clamp_magnitude(1, 2, 3),
        lambda V: V(1, 2).scale_to_length("a"),
        lambda V: V(1, 2).lerp("ab", 0.5),
        lambda V: V(1, 2).lerp((1, 2), "a"),
        lambda V: V(1, 2).slerp("ab", 0.5),
        lambda V: V(1, 2).project(10),
        lambda V: V(1, 2).dot("ab"),
        lambda V: V(1, 2).cross("ab"),
        lambda V: V.from_polar("ab"),
        lambda V: V.from_polar((None, 1)),
        lambda V: V.from_polar(1, 2),
        lambda V: "a" in V(1, 2),
        lambda V: round(V(1, 2), 1.5),
        lambda V: V(1, 2) // V(1, 2),
        lambda V: 2 // V(1, 2),
    ],
)
def test_wrong_kinds_are_type_errors_as_in_pygame(call: Callable[[Any], Any]) -> None:
    with pytest.raises(TypeError):
        call(Vector2)
    with pytest.raises(TypeError):
        call(Vector)


@pytest.mark.parametrize(
    "call",
    [
        lambda V: V(1, 2).clamp_magnitude(-1),
        lambda V: V(1, 2).clamp_magnitude(4, 3),
        lambda V: V(1, 2).clamp_magnitude(-4, 10),
        lambda V: V(1, 2).lerp((3, 4), 1.5),
        lambda V: V(1, 2).slerp((3, 4), -1.5),
    ],
)
def test_out_of_range_numbers_are_value_errors_as_in_pygame(call: Callable[[Any], Any]) -> None:
    with pytest.raises(ValueError):
        call(Vector2)
    with pytest.raises(ValueError):
        call(Vector)


def test_errors_name_the_argument_and_what_is_valid() -> None:
    with pytest.raises(TypeError, match=r"normal must be a Vector or a pair .* 3 items"):
        Vector(1, 2).reflect((1, 2, 3))
    with pytest.raises(TypeError, match=r"target must be a Vector or a pair.*'ab'"):
        Vector(1, 2).move_towards("ab", 1)
    with pytest.raises(TypeError, match="component max_distance"):
        Vector(1, 2).move_towards((0, 0), "far")
    with pytest.raises(TypeError, match="component degrees"):
        Vector(1, 2).rotate("90")
    with pytest.raises(ValueError, match="min_length cannot exceed max_length"):
        Vector(1, 2).clamp_magnitude(4, 3)
    with pytest.raises(ValueError, match=r"t must be in range \[-1, 1\], got 1.5"):
        Vector(1, 2).slerp((3, 4), 1.5)
    with pytest.raises(ValueError, match=r"\|other\|\^2 = 0.0 < 1e-6"):
        Vector(1, 2).project((0, 0))


@given(pairs, st.floats(min_value=0.01, max_value=100), st.booleans())
def test_floor_division_is_pythons_on_each_component(
    p: tuple[float, float], s: float, negative: bool
) -> None:
    s = -s if negative else s
    v = Vector(*p) // s
    assert same(v, (p[0] // s, p[1] // s))
    # pygame's floor(x * (1 / s)) is the same but where x * (1 / s) rounds across an integer
    w = Vector2(p) // s
    assert all(abs(a - b) <= 1 + 4 * EPS * abs(a) for a, b in zip(v, w, strict=True))


def test_floor_division_by_zero_names_the_divisor() -> None:
    with pytest.raises(ZeroDivisionError, match="divisor"):
        Vector(1, 2) // 0
    assert Vector(7, -7) // 2 == Vector(3, -4)


@given(pairs, st.integers(-3, 3))
def test_round_is_pygames(p: tuple[float, float], n: int) -> None:
    assert same(round(Vector(*p), n), round(Vector2(p), n))
    assert same(round(Vector(*p)), round(Vector2(p)))
    assert type(round(Vector(*p))) is Vector


@given(pairs, pairs, st.floats(min_value=-10, max_value=10))
def test_elementwise_is_pygames(p: tuple[float, float], q: tuple[float, float], s: float) -> None:
    v, w = Vector(*p).elementwise(), Vector2(p).elementwise()
    for op in (
        lambda e: e * q,
        lambda e: e + s,
        lambda e: s - e,
        lambda e: e - q,
        lambda e: q * e,
        lambda e: abs(e),
        lambda e: -e,
    ):
        assert same(op(v), op(w))
    assert (v > s) == (w > s) and (v <= q) == (w <= q) and (s < v) == (s < w)
    if all(c != 0 for c in q):
        assert same(v / q, (p[0] / q[0], p[1] / q[1]))
        assert same(v % q, (p[0] % q[0], p[1] % q[1]))
    assert type(v * q) is Vector


def test_contains_copy_and_unary_plus_are_pygames() -> None:
    v = Vector(0, 1)
    assert 0 in v and 1 in v and 2 not in v
    with pytest.raises(TypeError):
        _ = "string" in v
    c = v.copy()
    assert c == v and c is not v and +v is not v and +v == v


# -- pymunk's names ---------------------------------------------------------------------------


@needs_pymunk
@given(pairs, radians)
def test_pymunk_names_are_pymunks(p: tuple[float, float], rad: float) -> None:
    v, w = Vector(*p), Vec2d(*p)
    assert same(v.rotated(rad), w.rotated(rad))
    assert same(v.perpendicular(), w.perpendicular())
    assert v.angle == w.angle
    assert same(v.projection((rad, 1.0)), w.projection((rad, 1.0)))
    assert same(v.projection((0, 0)), w.projection((0, 0)))  # zero, where pygame raises
    assert same(Vector.zero(), Vec2d.zero())


def test_rotated_is_pymunks_formula_and_rotate_rad_pygames() -> None:
    # The two ecosystems' radians rotations differ only in pygame's exact quarter turns.
    assert Vector(1, 0).rotated(math.pi / 2) == (math.cos(math.pi / 2), 1.0)
    assert Vector(1, 0).rotate_rad(math.pi / 2) == (0.0, 1.0)
    assert Vector(2, 0).angle == 0.0 and Vector(0, 0).angle == 0.0


# -- construction, coercion and mixing with pygame and numpy --------------------------------


@pytest.mark.parametrize(
    "arg",
    [(1.5, -2), [1.5, -2], np.array([1.5, -2.0]), Vector2(1.5, -2), Vector(1.5, -2)]
    + ([] if Vec2d is None else [Vec2d(1.5, -2)]),
)
def test_one_argument_builds_from_any_pair(arg: Any) -> None:
    v = Vector(arg)
    assert type(v) is Vector and v == (1.5, -2.0) and type(v.x) is float
    assert Vector.coerce(arg) == (1.5, -2.0)


def test_the_lessons_constructor_keeps_its_meaning() -> None:
    assert Vector() == (0, 0)
    assert Vector(x=0, y=0) == (0, 0)
    assert Vector(x=2) == (2, 0)
    assert Vector(y=3) == (0, 3)
    assert Vector(1) == (1, 0)  # the lesson's; pygame's Vector2(1) is (1, 1)
    assert Vector(np.float64(2.5)) == (2.5, 0)
    assert Vector(Vector(1, 2)) == (1, 2)
    assert Vector(x=(1, 2)) == (1, 2)  # pygame's keyword for a pair is x, too


@pytest.mark.parametrize(
    ("bad", "words"),
    [
        ("ab", r"x must be a Vector or a pair.*'ab'"),
        ((1, 2, 3), r"x must be a Vector or a pair.*3 items"),
        ([1], r"1 items"),
        ([1, "a"], r"not both real numbers"),
        (np.array([1.0, 2.0, 3.0]), r"3 items"),
        (None, r"NoneType"),
        (True, r"bool"),
        ({0: 1.0, 1: 2.0}, r"dict"),
    ],
)
def test_one_bad_argument_is_a_type_error_naming_what_would_do(bad: Any, words: str) -> None:
    with pytest.raises(TypeError, match=r"Vector\(x\) with one argument takes a number"):
        Vector(bad)
    with pytest.raises(TypeError, match=words):
        Vector(bad)


def test_coerce_names_the_argument() -> None:
    with pytest.raises(TypeError, match=r"where must be a Vector.*3 items"):
        Vector.coerce((1, 2, 3), "where")
    with pytest.raises(TypeError, match=r"where must be.*str 'ab'"):
        Vector.coerce("ab", "where")
    with pytest.raises(TypeError, match="component x"):
        Vector((1, 2), 3)  # type: ignore[arg-type]  # two arguments are two components


def test_mixing_with_pygame_vector2() -> None:
    v, w = Vector(1, 2), Vector2(3, 4)
    # Our operator answers first when the Vector is on the left: the result stays a Vector.
    assert type(v + w) is Vector and v + w == (4, 6)
    assert type(v - w) is Vector and v - w == (-2, -2)
    # With Vector2 on the left, pygame's operator answers first (it takes any pair).
    assert type(w + v) is Vector2 and w + v == Vector2(4, 6)
    assert v.dot(w) == 11.0 and v.cross(w) == -2.0
    assert v.distance_to(w) == math.hypot(2, 2) and v.lerp(w, 0.5) == (2, 3)
    with pytest.raises(TypeError, match=r"v\.dot\(w\)"):
        v * w  # noqa: B018 - refused, as between two Vectors
    assert v.reflect(Vector2(0, 1)) == (1, -2)


def test_mixing_with_numpy_rows() -> None:
    rows = np.array([[1.0, 2.0], [3.0, 4.0]])
    v = Vector(1, 1)
    assert type(v + rows[0]) is Vector and v + rows[0] == (2, 3)
    assert type(rows[1] - v) is Vector and rows[1] - v == (2, 3)
    assert v.dot(rows[1]) == 7.0
    assert np.array_equal(np.array(Vector(rows[1])), rows[1])


def test_in_place_names_say_what_to_write_instead() -> None:
    v = Vector(3, 4)
    for name, instead in (
        ("normalize_ip", "v = v.normalize()"),
        ("rotate_ip", "v = v.rotate(degrees)"),
        ("move_towards_ip", "v = v.move_towards(target, max_distance)"),
        ("update", "v = Vector(x, y)"),
    ):
        assert not hasattr(v, name)
        with pytest.raises(AttributeError, match=f"immutable.*{name}.*{re.escape(instead)}"):
            getattr(v, name)
    with pytest.raises(AttributeError, match=r"v = Vector\.from_polar"):
        v.from_polar((1, 90))
    assert Vector.from_polar((1, 0)) == (1, 0)
    assert v == (3, 4)


# -- subclasses ------------------------------------------------------------------------------


class Position(Vector):
    __slots__ = ()


class Tagged(Vector):
    __slots__ = ()

    def __add__(self, other: Any) -> Any:
        return "own add"


class SubTagged(Tagged):
    __slots__ = ()


@given(pairs, pairs, st.floats(min_value=-1e3, max_value=1e3).filter(lambda s: s != 0))
def test_subclass_arithmetic_keeps_the_subclass_and_the_values(
    p: tuple[float, float], q: tuple[float, float], s: float
) -> None:
    a, b, va, vb = Position(*p), Position(*q), Vector(*p), Vector(*q)
    for ours, plain in (
        (a + b, va + vb),
        (a - b, va - vb),
        (a * s, va * s),
        (s * a, s * va),
        (a / s, va / s),
        (-a, -va),
        (+a, +va),
        (q + a, q + va),
        (q - a, q - va),
        (a // s, va // s),
        (a.rotate(s), va.rotate(s)),
        (a.move_towards(q, s), va.move_towards(q, s)),
        (a.elementwise() * q, va.elementwise() * q),
        (a.copy(), va),
    ):
        assert type(ours) is Position, (ours, plain)
        assert same(ours, plain)
        assert math.copysign(1, ours.x) == math.copysign(1, plain.x)


def test_subclass_keeps_its_own_operators() -> None:
    assert Tagged(1, 2) + (1, 1) == "own add"
    assert SubTagged(1, 2) + (1, 1) == "own add"
    assert type(SubTagged(1, 2) - (1, 1)) is SubTagged
    # Python asks a subclass's reflected operator first: the subclass wins on either side.
    assert type(Vector(1, 2) + Position(1, 1)) is Position
    assert type(Vector(1, 2) + Vector(1, 1)) is Vector
    with pytest.raises(TypeError, match=r"v\.dot\(w\)"):
        Position(1, 2) * (1, 2)
    with pytest.raises(TypeError):
        (1,) + Position(1, 2)  # type: ignore[operator]
    assert pickle.loads(pickle.dumps(Position(1, 2))) == Position(1, 2)


@given(pairs)
def test_hot_operators_still_give_plain_vectors(p: tuple[float, float]) -> None:
    v = Vector(*p)
    for result in (v + v, v - v, v * 2.0, 2.0 * v, v / 2.0, -v, +v, (1, 2) + v):
        assert type(result) is Vector
