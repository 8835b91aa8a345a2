"""Fuzzing shapes that turn, and mixed scenes of them (issue "Bodies that turn", Reliability).

* Construction: point sets of every awkward kind (nearly collinear, tiny (1e-4 m) and huge
  (1e4 m), far from the origin (1e6 m), repeated points, clockwise, nan and inf, 2 and 9
  points, not convex, points in a shuffled order) make a ``Polygon``, ``Polygon.box`` or a
  capsule ``Segment`` that is convex, counter-clockwise, of positive finite area and finite
  positive moment, or a TypeError / ValueError whose message names the argument the caller
  gave. Convex point sets that rounding cannot spoil always build; sets that cannot be a
  convex polygon never do. (The exact refusals and geometry are in tests/test_polygons.py.)
* Scenes: a closed room (a room ``Box`` or four ``Polygon`` walls), gravity, and 2 to 12
  boxes, convex polygons (rounded or not), capsules and discs of random size, mass,
  material, angle, spin (to 100 rad/s) and speed (to 100 m/s), some with
  ``fixed_rotation``, maybe a kinematic shape turning in the middle; stepped 1 to 3 s at
  dt = 1/60. After every step: the state is finite, every centre is inside the room, and no
  shape is deeper in a wall than ``WALL_DEPTH``; a rerun is bit-identical, and a snapshot
  taken at a random step and restored replays the rest bit for bit (angles, angular
  velocities and the contacts' impulses included).

Examples (CI, derandomized): construction 300 + 150 + 150, scenes ``SCENES``; set
``FUZZ_LONG=1`` for 20 times as many.
"""

from __future__ import annotations

import math
import os
import re
from fractions import Fraction
from typing import Any

from fuzzing import fuzz, numbers
from hypothesis import given, note
from hypothesis import strategies as st

from engine import (
    Body,
    Polygon,
    Segment,
    Vector,
)

LONG = bool(os.environ.get("FUZZ_LONG"))
SCALE = 20 if LONG else 1

# -- construction ------------------------------------------------------------------------------

# What a message must do besides naming the argument: say what would be valid or what to do.
_REMEDY = re.compile(
    r"must|valid|takes|needs|expected|use |give |cannot|only|not in|holds|leave|split"
)


def refused(exc: BaseException, *names: str) -> None:
    """``exc`` is a TypeError / ValueError that names one of ``names`` and says what to do."""
    assert isinstance(exc, (TypeError, ValueError)), repr(exc)
    text = str(exc)
    assert any(n in text for n in names), f"does not name {' or '.join(names)}: {text!r}"
    assert _REMEDY.search(text.lower()), f"does not say what would do: {text!r}"


def exact_twice_area(pts: list[tuple[float, float]]) -> Fraction:
    """Twice the signed area of the float points, exactly (Fractions)."""
    q = [(Fraction(x), Fraction(y)) for x, y in pts]
    n = len(q)
    return sum(
        (q[i][0] * q[(i + 1) % n][1] - q[(i + 1) % n][0] * q[i][1] for i in range(n)), Fraction(0)
    )


def check_polygon(p: Polygon, given_pts: list[tuple[float, float]], mass: float) -> None:
    """A built polygon: the given points, counter-clockwise, convex, unit outward normals,
    positive finite area (the exact one for a sharp polygon), finite positive moment."""
    verts = [(v.x, v.y) for v in p.vertices]
    assert sorted(verts) == sorted(given_pts)
    assert verts[0] == given_pts[0]  # the first point stays first
    n = len(verts)
    for i in range(n):
        (ax, ay), (bx, by), (cx, cy) = verts[i - 1], verts[i], verts[(i + 1) % n]
        # Strictly left at every corner, exactly (the corners are floats: Fractions are exact).
        turn = (Fraction(bx) - Fraction(ax)) * (Fraction(cy) - Fraction(by)) - (
            Fraction(by) - Fraction(ay)
        ) * (Fraction(cx) - Fraction(bx))
        assert turn > 0, (i, verts)
        nx, ny = p.normals[i]
        ex, ey = verts[(i + 1) % n][0] - bx, verts[(i + 1) % n][1] - by
        assert abs(math.hypot(nx, ny) - 1.0) < 1e-12
        scale = max(abs(ex), abs(ey))
        assert abs(nx * ex + ny * ey) <= 1e-12 * scale  # along the edge's perpendicular
        assert nx * ey - ny * ex > 0.0  # outward: on the edge's right
    assert 0.0 < p.area < math.inf
    if p.radius == 0.0:
        # The shoelace about the first corner, in floats: off by a few roundings of the
        # products of the corners' offsets from it (a sliver's area is that uncertain).
        exact = exact_twice_area(verts) / 2
        assert exact > 0
        reach = max(abs(x - verts[0][0]) + abs(y - verts[0][1]) for x, y in verts)
        slack = Fraction(4 * n * 2.0**-52 * reach * reach)
        assert abs(Fraction(p.area) - exact) <= slack + exact / 10**12, (p.area, exact)
    lo_x, lo_y, hi_x, hi_y = p.bounds()
    assert lo_x <= p.centroid.x <= hi_x and lo_y <= p.centroid.y <= hi_y
    inertia = check_moment(p, mass)
    if inertia is not None:
        # The moment about the origin holds the parallel axes' term m |c|^2.
        assert inertia >= mass * (p.centroid.x**2 + p.centroid.y**2) * (1.0 - 1e-9)


def check_moment(shape: Polygon | Segment, mass: float) -> float | None:
    """The shape's moment for ``mass``, finite and > 0, the same as its Body's; or, for a
    shape whose moment leaves the float range, a refusal by both naming the argument."""
    try:
        inertia = shape.moment(mass)
    except ValueError as exc:
        refused(exc, "vertices", "a and b", "radius")
        try:
            Body(Vector(0.0, 0.0), shape=shape, mass=mass)
        except ValueError as again:
            refused(again, "shape")
            return None
        raise AssertionError(f"a Body took {shape!r}, whose moment is refused") from None
    assert 0.0 < inertia < math.inf
    body = Body(Vector(0.0, 0.0), shape=shape, mass=mass)
    assert body.moment == inertia and body.turns
    return inertia


def _on_circle(gaps: list[float], squash: float, turn: float) -> list[tuple[float, float]]:
    """Points at angles that step by ``gaps`` (normalised to one turn) on a unit circle,
    squashed to an ellipse of axes 1 and ``squash``, then turned by ``turn``."""
    total = sum(gaps)
    out, a = [], 0.0
    c, s = math.cos(turn), math.sin(turn)
    for g in gaps:
        x, y = math.cos(a), squash * math.sin(a)
        out.append((c * x - s * y, s * x + c * y))
        a += 2.0 * math.pi * g / total
    return out


SIZES = [1e-4, 1e-2, 1.0, 1e2, 1e4]
KINDS = [
    "convex",
    "clockwise",
    "repeat",
    "midpoint",
    "dent",
    "shuffle",
    "nan",
    "inf",
    "two",
    "nine",
    "line",
]


@st.composite
def point_sets(draw: st.DrawFn) -> tuple[str, list[tuple[float, float]], bool | None]:
    """(kind, points, whether they must build: True, False, or None for either)."""
    kind = draw(st.sampled_from(KINDS))
    n = {"two": 2, "nine": 9}.get(kind, draw(st.integers(3 if kind != "dent" else 4, 8)))
    gaps = draw(st.lists(st.floats(0.25, 1.0), min_size=n, max_size=n))
    squash = draw(st.sampled_from([1.0, 0.3, 1e-3, 1e-6, 1e-9, 1e-13]))
    size = draw(st.sampled_from(SIZES))
    far = draw(st.sampled_from([0.0, 1.0, 1e3, 1e6]))
    towards = draw(st.floats(0.0, 2.0 * math.pi))
    turn = draw(st.floats(0.0, 2.0 * math.pi))
    ox, oy = far * math.cos(towards), far * math.sin(towards)
    pts = [(ox + size * x, oy + size * y) for x, y in _on_circle(gaps, squash, turn)]
    # Rounding cannot spoil the polygon when its flattest turn stays far above the rounding of
    # its coordinates: then a convex set must build and a clockwise one too.
    sound = squash >= 1e-6 and size * squash >= 1e-8 * (far + size)
    if kind == "two" or kind == "nine":
        return kind, pts, False
    if kind == "convex":
        return kind, pts, True if sound else None
    if kind == "clockwise":
        return kind, pts[:1] + pts[:0:-1], True if sound else None
    i = draw(st.integers(0, n - 1))
    if kind == "repeat":
        return kind, pts[: i + 1] + pts[i:], False
    if kind == "midpoint":  # on the edge's line up to rounding: a bare flat corner, or refused
        j = (i + 1) % n
        mid = (0.5 * (pts[i][0] + pts[j][0]), 0.5 * (pts[i][1] + pts[j][1]))
        return kind, pts[: i + 1] + [mid] + pts[i + 1 :], None
    if kind == "dent":  # a corner pushed in past the chord of its neighbours: concave there
        (ax, ay), (vx, vy), (bx, by) = pts[i - 1], pts[i], pts[(i + 1) % n]
        mx, my = 0.5 * (ax + bx), 0.5 * (ay + by)
        dent = (mx + 0.5 * (mx - vx), my + 0.5 * (my - vy))
        return kind, pts[:i] + [dent] + pts[i + 1 :], False if sound else None
    if kind == "shuffle":
        order = draw(st.permutations(range(n)))
        out = [pts[k] for k in order]
        k0 = order.index(0)
        rolled = order[k0:] + order[:k0]
        cyclic = rolled == list(range(n)) or rolled == [0, *range(n - 1, 0, -1)]
        return kind, out, (True if sound else None) if cyclic else (False if sound else None)
    if kind == "line":  # every point on one line (or a hair off it, by rounding)
        return (
            kind,
            [(ox + size * t, oy + 0.5 * size * t) for t in sorted(gaps)],
            (False if far == 0.0 else None),
        )
    bad = math.nan if kind == "nan" else draw(st.sampled_from([math.inf, -math.inf]))
    pts[i] = (bad, pts[i][1]) if draw(st.booleans()) else (pts[i][0], bad)
    return kind, pts, False


@fuzz(300 * SCALE)
@given(
    case=point_sets(),
    radius=st.one_of(st.just(0.0), st.sampled_from([1e-4, 0.1, 1.0, 1e4]), numbers),
    mass=st.floats(1e-3, 1e3),
)
def test_point_sets_make_a_convex_polygon_or_an_error_naming_vertices(
    case: tuple[str, list[tuple[float, float]], bool | None], radius: Any, mass: float
) -> None:
    kind, pts, must = case
    note(f"{kind}: {pts!r}")
    try:
        p = Polygon(pts, radius)
    except (TypeError, ValueError) as exc:
        if "radius" in str(exc):
            return refused(exc, "radius")
        refused(exc, "vertices")
        assert must is not True, f"a convex set was refused: {exc}"
        return
    assert must is not False, f"{kind} built {p!r}"
    check_polygon(p, [(float(x), float(y)) for x, y in pts], mass)


finite_or_not = st.one_of(
    st.floats(-1e6, 1e6), st.floats(-1e-3, 1e-3), st.sampled_from([math.nan, math.inf, 1e308])
)


@fuzz(150 * SCALE)
@given(
    pts=st.lists(st.tuples(finite_or_not, finite_or_not), max_size=10),
    mass=st.floats(1e-3, 1e3),
)
def test_any_points_make_a_convex_polygon_or_an_error_naming_vertices(
    pts: list[tuple[float, float]], mass: float
) -> None:
    try:
        p = Polygon(pts)
    except (TypeError, ValueError) as exc:
        return refused(exc, "vertices")
    check_polygon(p, pts, mass)


sizes = st.one_of(
    st.sampled_from([*SIZES, 0.0, -1.0, 1e-12, 1e-200, 1e300, math.nan, math.inf]),
    st.floats(1e-4, 1e4),
)
centres = st.sampled_from([0.0, 1.0, 1e3, 1e6, 1e300, math.nan]).flatmap(
    lambda far: st.floats(0.0, 2.0 * math.pi).map(
        lambda a: (far * math.cos(a), far * math.sin(a)) if math.isfinite(far) else (far, 0.0)
    )
)


@fuzz(150 * SCALE)
@given(
    width=sizes,
    height=sizes,
    center=centres,
    radius=st.sampled_from([0.0, 1e-4, 0.5, 1e4, -1.0, math.nan]),
    mass=st.floats(1e-3, 1e3),
)
def test_polygon_box_makes_a_box_or_an_error_naming_its_arguments(
    width: float, height: float, center: tuple[float, float], radius: float, mass: float
) -> None:
    # Polygon.box's caller gave width, height, center and radius: an error names those, not
    # the vertices it makes of them.
    try:
        p = Polygon.box(width, height, center=center, radius=radius)
    except (TypeError, ValueError) as exc:
        return refused(exc, "width", "height", "center", "radius")
    assert len(p.vertices) == 4
    check_polygon(p, [(v.x, v.y) for v in p.vertices], mass)
    if radius == 0.0 and max(abs(center[0]), abs(center[1])) <= 1e3 * min(width, height):
        assert math.isclose(p.area, width * height, rel_tol=1e-9)


ends = st.sampled_from([0.0, 1.0, 1e3, 1e6, 1e300, math.inf, math.nan])


@fuzz(150 * SCALE)
@given(
    far=ends,
    towards=st.floats(0.0, 2.0 * math.pi),
    length=st.sampled_from([0.0, 1e-200, 1e-150, 1e-12, 1e-4, 1.0, 1e4, 1e300, math.nan]),
    along=st.floats(0.0, 2.0 * math.pi),
    radius=st.sampled_from([0.0, 1e-4, 0.5, 1e4, -1.0, math.inf, math.nan]),
    mass=st.floats(1e-3, 1e3),
)
def test_a_capsule_is_made_or_refused_by_the_name_of_its_argument(
    far: float, towards: float, length: float, along: float, radius: float, mass: float
) -> None:
    a = (far * math.cos(towards), far * math.sin(towards)) if math.isfinite(far) else (far, 0.0)
    b = (a[0] + length * math.cos(along), a[1] + length * math.sin(along))
    try:
        s = Segment(a, b, radius)
    except (TypeError, ValueError) as exc:
        return refused(exc, "a must", "b must", "a and b", "radius")
    assert s.a != s.b and 0.0 <= s.radius < math.inf
    assert all(map(math.isfinite, (*s.a, *s.b)))
    if check_moment(s, mass) is not None:
        assert 0.0 < Body(Vector(0.0, 0.0), shape=s, mass=mass).radius < math.inf
    for q in ((0.0, 0.0), a, (a[0] + 1.0, a[1] - 2.0)):
        point, normal, d = s.closest(q)
        assert math.isfinite(d) and math.isfinite(point.x) and math.isfinite(point.y)


# -- found by the fuzz ---------------------------------------------------------------------------


def test_polygon_box_refusals_name_its_own_arguments() -> None:
    # Polygon.box(1e-4, 1e-200) made corners 1e-200 apart, refused as "vertices[1] = ... and
    # vertices[2] = ...": arguments its caller never gave. Likewise 1e300 by 1e300 (the area
    # overflows) and 1e-200 by 1e-200 (the area underflows to 0).
    for args in ((1e-4, 1e-200), (1e300, 1e300), (1e-200, 1e-200), (1e-12, 1.0, (1e6, 0.0))):
        try:
            Polygon.box(*args)  # type: ignore[arg-type]
        except ValueError as exc:
            refused(exc, "width", "height", "center")
        else:
            raise AssertionError(f"Polygon.box{args} was made")


def test_a_shape_whose_moment_leaves_the_float_range_is_refused_not_nan() -> None:
    # Polygon([(0, 0), (1e100, 0), (0, 1e100)]).moment(1) was nan (its second moment of area,
    # ~1e400, overflows; inf / area = ... nan through the parallel axes' sum), and a Body of it
    # silently had a nan moment and did not turn; a triangle 1e-150 wide had moment 0.0, so
    # its Body turned with a zero moment and apply_impulse divided by it (ZeroDivisionError).
    # A capsule 1e300 long gave nan too.
    for shape in (
        Polygon([(0.0, 0.0), (1e100, 0.0), (0.0, 1e100)]),
        Polygon([(0.0, 0.0), (1e-150, 0.0), (0.0, 1e-150)]),
        Segment((0.0, 0.0), (1e300, 0.0)),
        Segment((0.0, 0.0), (1.0, 0.0), 1e300),
    ):
        try:
            inertia = shape.moment(1.0)
        except ValueError as exc:
            refused(exc, "vertices", "a and b", "radius")
        else:
            assert 0.0 < inertia < math.inf, (shape, inertia)
        try:
            body = Body(Vector(0.0, 0.0), shape=shape)
        except ValueError as exc:
            refused(exc, "shape")
        else:
            assert 0.0 < body.moment < math.inf, (shape, body.moment)
