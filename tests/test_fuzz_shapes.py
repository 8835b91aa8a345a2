"""Fuzzing shapes that turn, and mixed scenes of them (issue "Bodies that turn", Reliability).

* Construction: point sets of every awkward kind (nearly collinear, tiny (1e-4 m) and huge
  (1e4 m), far from the origin (1e6 m), repeated points, clockwise, nan and inf, 2 and 9
  points, not convex, points in a shuffled order) make a ``Polygon``, ``Polygon.box`` or a
  capsule ``Segment`` that is convex, counter-clockwise, of positive finite area and finite
  positive moment, or a TypeError / ValueError whose message names the argument the caller
  gave. Convex point sets that rounding cannot spoil always build; sets that cannot be a
  convex polygon never do. (The exact refusals and geometry are in tests/test_polygons.py.)
* Scenes: a closed room (a room ``Box`` or four ``Plane`` walls), gravity, and 2 to 12
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
import warnings
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from fuzzing import fuzz, numbers
from hypothesis import assume, example, given, note
from hypothesis import strategies as st

from engine import (
    Body,
    Box,
    Circle,
    OverlapWarning,
    Plane,
    Polygon,
    Segment,
    StabilityWarning,
    Vector,
    World,
)
from engine.forces import Gravity

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
    """The shape's moment for ``mass`` about its frame's origin, finite and > 0, or a refusal
    naming the argument where it leaves the float range; and its Body's, which holds the
    shape about its centroid (engine.body_shapes) unless that is the origin to rounding: the
    shape's moved there, the moment about the origin less the parallel axes' term m |c|^2
    (likewise finite and > 0, or the Body refused naming its shape)."""
    try:
        inertia: float | None = shape.moment(mass)
    except ValueError as exc:
        refused(exc, "vertices", "a and b", "radius")
        inertia = None
    c = shape.centroid
    x0, y0, x1, y1 = shape.bounds()
    size = max(abs(x0), abs(y0), abs(x1), abs(y1))
    kept = math.hypot(c.x, c.y) <= 1e-12 * size  # centred to rounding: held as drawn
    try:
        about: float | None = inertia if kept else shape.moved(-c.x, -c.y).moment(mass)
    except ValueError:
        about = None
    if inertia is not None:
        assert 0.0 < inertia < math.inf
    if about is None or not 0.0 < about < math.inf:
        with pytest.raises(ValueError) as again:
            Body(Vector(0.0, 0.0), shape=shape, mass=mass)
        refused(again.value, "shape")
        return inertia
    body = Body(Vector(0.0, 0.0), shape=shape, mass=mass)
    assert body.turns
    if body.center_of_gravity == (0.0, 0.0):
        assert body.moment == inertia
    else:
        assert body.center_of_gravity == c and body.moment == about
    if inertia is not None:
        # The parallel axes' term moves with the centroid, which a sliver holds no better than
        # its area (check_polygon's slack: a few roundings of the corners' products, reach^2,
        # over the area): 2 m |c| reach times that share, nothing for a shape of some width.
        # (A 1e4 m quadrilateral of 0.15 m^2, 2,750 m out, was 0.053 off: found exploring.)
        unsure = 0.0
        if isinstance(shape, Polygon) and shape.radius == 0.0:
            first = shape.vertices[0]
            reach = max(abs(v.x - first.x) + abs(v.y - first.y) for v in shape.vertices)
            share = 4 * len(shape.vertices) * 2.0**-52 * reach * reach / shape.area
            unsure = 2.0 * mass * math.hypot(c.x, c.y) * reach * share
        assert abs(about - (inertia - mass * (c.x**2 + c.y**2))) <= 1e-9 * inertia + unsure
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
    "many",
    "too_many",
    "line",
]


@st.composite
def point_sets(draw: st.DrawFn) -> tuple[str, list[tuple[float, float]], bool | None]:
    """(kind, points, whether they must build: True, False, or None for either)."""
    kind = draw(st.sampled_from(KINDS))
    # 3 to 8 points mostly; "many" 9 to 64 (a polygon takes up to
    # engine.geometry.convex.MAX_VERTICES)
    least = 4 if kind == "dent" else 9 if kind == "many" else 3
    n = {"two": 2, "too_many": 257}.get(kind, draw(st.integers(least, 64 if kind == "many" else 8)))
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
    if kind == "two" or kind == "too_many":
        return kind, pts, False
    if kind in ("convex", "many"):
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
# Found exploring: a sliver of 0.15 m^2 between corners 1e4 m apart, its centroid 2,750 m out,
# whose moment about the centroid was 0.053 off the parallel axes' value (check_moment).
@example(
    case=(
        "convex",
        [
            (7316.888688738209, 6816.387600233341),
            (5605.061916546521, 5221.655848007063),
            (-3658.4443502722675, -3408.1937937800576),
            (1270.5643937039943, 1183.653277846249),
        ],
        None,
    ),
    radius=0.0,
    mass=1.0,
)
# Found exploring: a 1e-4 m triangle about the origin rounded by 3e28 m, whose centroid rounds
# to 1.2e12 m, within 1e-12 of its size: the Body holds it as drawn (engine.body_shapes.centred),
# where check_moment moved it by that centroid and expected a refusal.
@example(
    case=(
        "convex",
        [
            (0.0001, 0.0),
            (-4.999999999999998e-05, 8.660254037844388e-05),
            (-5.000000000000005e-05, -8.660254037844384e-05),
        ],
        True,
    ),
    radius=3.0574275424575294e28,
    mass=1.0,
)
# Found exploring (2,000 examples, fast path, 2026-12-05): nine points of a 1e-4 m sliver, one
# a midpoint, whose turn at vertices[2] is -1.7e-26 exactly, where the floats' edges and cross
# product said +: it was built, not convex. A turn within the rounding's bound is now taken
# exactly (engine.geometry.convex), and the set refused.
@example(
    case=(
        "midpoint",
        [
            (8.490701837107582e-05, -5.282800612680544e-05),
            (6.387979784097402e-05, -3.9745152008199654e-05),
            (2.392358960613153e-05, -1.4884936045729871e-05),
            (-1.6032618628710956e-05, 9.97527991673991e-06),
            (-8.369783004913409e-05, 5.2075665398025455e-05),
            (-8.276801264456468e-05, 5.149714550075241e-05),
            (-2.583500745242927e-05, 1.607419455029383e-05),
            (3.482153144921145e-05, -2.1665489049504293e-05),
            (7.947655294956338e-05, -4.944924349843312e-05),
        ],
        None,
    ),
    radius=0.0,
    mass=1.0,
)
def test_point_sets_make_a_convex_polygon_or_an_error_naming_vertices(
    case: tuple[str, list[tuple[float, float]], bool | None], radius: Any, mass: float
) -> None:
    kind, pts, must = case
    note(f"{kind}: {pts!r}")
    # A rounding whose cube overflows raises OverflowError: test_a_huge_rounding_is_refused_by_name.
    try:
        assume(not 1e100 <= abs(float(radius)) < math.inf)
    except (TypeError, ValueError, OverflowError):
        pass
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
# Found exploring: a rod of 1e-150 m whose moment about its centre, L^2 / 12 = 8e-302, was
# taken as L^3 / 6 over 2 L, L^3 underflowing to 0: the Body was refused (its moment 0).
@example(far=0.0, towards=0.0, length=1e-150, along=0.0, radius=0.0, mass=1.0)
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


# -- scenes --------------------------------------------------------------------------------------

#: Scenes in CI (each stepped three times: the run, the rerun and the replay from a snapshot).
SCENES = 400 if LONG else 12
DT = 1.0 / 60.0

#: The deepest any shape may end a step in a wall (m). The walls are solved by the pile's soft
#: step (engine.exact.soft: Box2D v3's soft contacts, pushing an overlap out at a bounded speed,
#: with speculative rows so that nothing passes a wall at up to 1,000 m/s): a contact gives
#: a little under load and under a fast blow and is pushed out over the next steps, so a
#: shape may end a step a few centimetres in (the tumbler's corners go up to 0.1 m into its
#: walls, README "Links, and bodies the game moves"), never through. Bodies here are at most
#: 1.8 m across, at most 10 kg on 0.1 kg, and a wall is 1 m thick or a half plane.
WALL_DEPTH = 0.1


@st.composite
def scenes(draw: st.DrawFn) -> dict[str, Any]:
    """A room 6 to 16 m wide under gravity, with 2 to 12 shapes placed apart in it, as a plain
    description that ``build`` turns into a World (twice, for the rerun)."""
    half = (draw(st.floats(3.0, 8.0)), draw(st.floats(3.0, 8.0)))
    spec: dict[str, Any] = {
        "half": half,
        "walls": draw(st.sampled_from(["room", "planes", "polygons"])),
        "wall_material": (draw(st.floats(0.0, 1.0)), draw(st.floats(0.0, 1.0))),
        "gravity": draw(st.floats(0.0, 20.0)),
        "steps": draw(st.sampled_from([60, 120, 180])),
    }
    spec["snap"] = draw(st.integers(0, spec["steps"] - 1))
    spin = None
    if draw(st.booleans()):  # a kinematic bat turning about the room's centre
        length = draw(st.floats(0.5, min(half) - 1.0))
        spin = (draw(st.sampled_from(["box", "capsule"])), length, draw(st.floats(0.1, 0.4)),
                draw(st.floats(-10.0, 10.0)))  # fmt: skip
    spec["kinematic"] = spin
    reach = 0.0 if spin is None else spin[1] + spin[2]
    kinds = []
    for _ in range(draw(st.integers(2, 12))):
        kind = draw(st.sampled_from(["box", "polygon", "capsule", "disc"]))
        if kind == "box":
            geometry: Any = (draw(st.floats(0.1, 1.2)), draw(st.floats(0.1, 1.2)),
                             draw(st.sampled_from([0.0, 0.0, 0.05])))  # fmt: skip
        elif kind == "polygon":
            n = draw(st.integers(3, 8))
            geometry = (draw(st.lists(st.floats(0.25, 1.0), min_size=n, max_size=n)),
                        draw(st.sampled_from([1.0, 0.5, 0.2])), draw(st.floats(0.1, 0.7)),
                        draw(st.sampled_from([0.0, 0.0, 0.05])))  # fmt: skip
        elif kind == "capsule":
            geometry = (draw(st.floats(0.1, 0.8)), draw(st.floats(0.03, 0.3)))
        else:
            geometry = (draw(st.floats(0.05, 0.6)),)
        kinds.append(
            {
                "kind": kind,
                "geometry": geometry,
                "mass": draw(st.floats(0.1, 10.0)),
                "restitution": draw(st.floats(0.0, 1.0)),
                "friction": draw(st.floats(0.0, 1.0)),
                "angle": draw(st.floats(-math.pi, math.pi)),
                "spin": draw(st.floats(-100.0, 100.0)),
                "speed": draw(st.floats(0.0, 100.0)),
                "heading": draw(st.floats(-math.pi, math.pi)),
                "fixed": draw(st.integers(0, 4)) == 0,
            }
        )
    # Places: the cells of a grid as wide as the widest body, clear of the walls and of the
    # bat's circle, drawn without repeats; bodies past the cells' count are left out.
    cell = 2.0 * max(shape_of(k)[1] for k in kinds) + 0.05
    nx, ny = int(2.0 * half[0] / cell), int(2.0 * half[1] / cell)
    cells = [
        (-half[0] + cell * (i + 0.5), -half[1] + cell * (j + 0.5))
        for i in range(nx)
        for j in range(ny)
        if math.hypot(-half[0] + cell * (i + 0.5), -half[1] + cell * (j + 0.5))
        > reach + 0.5 * cell + 0.05
    ]
    assume(len(cells) >= 2)
    order = draw(st.permutations(range(len(cells))))
    spec["bodies"] = [dict(k, at=cells[c]) for k, c in zip(kinds, order, strict=False)]
    # The solver: the exact models, or World()'s own choice (the soft step for these rooms
    # of shapes, engine.pipeline.solver_choice), half the scenes each.
    spec["solver"] = draw(st.sampled_from(["exact", "auto"]))
    return spec


def shape_of(k: dict[str, Any]) -> tuple[Any, float]:
    """A body's shape from its description, and the radius of the circle that holds it."""
    g = k["geometry"]
    if k["kind"] == "box":
        box = Polygon.box(g[0], g[1], radius=g[2])
        return box, 0.5 * math.hypot(g[0], g[1]) + g[2]
    if k["kind"] == "polygon":
        gaps, squash, size, rounding = g
        pts = [(size * x, size * y) for x, y in _on_circle(gaps, squash, 0.0)]
        return Polygon(pts, rounding), size + rounding
    if k["kind"] == "capsule":
        return Segment((-g[0], 0.0), (g[0], 0.0), g[1]), g[0] + g[1]
    return None, g[0]


def build(spec: dict[str, Any]) -> tuple[World, list[Body], Body | None]:
    """The World a scene describes: (world, its dynamic bodies, the kinematic bat or None), on
    its ``solver`` (the exact models where it names none: the regression scenes below, each
    found on them)."""
    w = World(integrator="auto", solver=spec.get("solver", "exact"))
    w.add_force(Gravity((0.0, -spec["gravity"])))
    hx, hy = spec["half"]
    e, mu = spec["wall_material"]
    if spec["walls"] == "room":
        w.add_collider(Box((-hx, -hy), (hx, hy), restitution=e, friction=mu))
    elif spec["walls"] == "planes":  # four half planes whose faces make the room
        for point, normal in (((0.0, -hy), (0.0, 1.0)), ((0.0, hy), (0.0, -1.0)),
                              ((-hx, 0.0), (1.0, 0.0)), ((hx, 0.0), (-1.0, 0.0))):  # fmt: skip
            w.add_collider(Plane(point, normal, restitution=e, friction=mu))
    else:  # four solid Polygon walls 1 m thick, overlapping at the corners
        ox, oy = hx + 1.0, hy + 1.0
        for x0, y0, x1, y1 in ((-ox, -oy, ox, -hy), (-ox, hy, ox, oy),
                               (-ox, -oy, -hx, oy), (hx, -oy, ox, oy)):  # fmt: skip
            w.add_collider(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], restitution=e,
                                   friction=mu))  # fmt: skip
    bat = None
    if spec["kinematic"] is not None:
        kind, length, thick, omega = spec["kinematic"]
        shape = (
            Polygon.box(2.0 * length, 2.0 * thick)
            if kind == "box"
            else Segment((-length, 0.0), (length, 0.0), thick)
        )
        bat = w.add(Body(Vector(0.0, 0.0), shape=shape, kinematic=True, angular_velocity=omega))
    bodies = []
    for k in spec["bodies"]:
        shape, size = shape_of(k)
        v = Vector(math.cos(k["heading"]), math.sin(k["heading"])) * k["speed"]
        made = Body(
            Vector(*k["at"]),
            v,
            mass=k["mass"],
            shape=shape,
            radius=0.0 if shape is not None else size,
            restitution=k["restitution"],
            friction=k["friction"],
            angle=0.0 if k["fixed"] else k["angle"],
            angular_velocity=0.0 if k["fixed"] else k["spin"],
            fixed_rotation=k["fixed"],
        )
        bodies.append(w.add(made))
    return w, bodies, bat


def depth_in_walls(body: Body, half: tuple[float, float]) -> float:
    """How far the body's shape reaches past the room's inner faces (m; <= 0 inside), from
    its corners (or a disc's, a capsule's ends') in world coordinates plus its rounding."""
    shape, (x, y) = body.shape, body.pos
    if shape is None or isinstance(shape, Circle):
        return max(abs(x) + body.radius - half[0], abs(y) + body.radius - half[1])
    local = shape.vertices if isinstance(shape, Polygon) else (shape.a, shape.b)
    c, s = math.cos(body.angle), math.sin(body.angle)
    xs = [x + c * p.x - s * p.y for p in local]
    ys = [y + s * p.x + c * p.y for p in local]
    r = shape.radius
    return max(max(xs) + r - half[0], -min(xs) + r - half[0],
               max(ys) + r - half[1], -min(ys) + r - half[1])  # fmt: skip


def state(w: World, bodies: list[Body]) -> bytes:
    """Every number of the state a step leaves, as bytes: positions, velocities, angles,
    angular velocities, and each open contact's point, normal and impulse (the warm start)."""
    index = {id(b): i for i, b in enumerate(w.bodies)}
    index.update({id(c): -1 - i for i, c in enumerate(w.colliders)})
    contacts = sorted(
        (index[id(ev.body)], index[id(ev.collider)], *ev.point, *ev.normal, *ev.impulse)
        for ev in w.touching
    )
    spins = [(b.angle, b.angular_velocity) for b in w.bodies]
    return b"".join(
        (
            w.positions().tobytes(),
            w.velocities().tobytes(),
            np.array(spins, dtype=float).tobytes(),
            np.array(contacts, dtype=float).tobytes(),
        )
    )


def run(spec: dict[str, Any], snap: int | None = None) -> tuple[list[bytes], dict[str, float]]:
    """Step the scene, checking every step's end; the states after each step, and what was
    seen (the deepest in a wall, warnings counted). With ``snap``: a snapshot after that many
    steps, restored at the end and stepped on again, each state compared with the first."""
    w, bodies, _ = build(spec)
    half = spec["half"]
    # (and "deepest i": how deep body i of the spec went, for a test of one body)
    seen = {"deepest": -math.inf, "stability": 0, "overlap": 0}
    seen |= {f"deepest {i}": -math.inf for i in range(len(bodies))}
    trace, saved = [], None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for k in range(spec["steps"]):
            if k == snap:
                saved = w.snapshot()
            w.step(DT)
            trace.append(state(w, bodies))
            warned = any(issubclass(c.category, StabilityWarning) for c in caught)
            for i, b in enumerate(bodies):
                p, v = b.pos, b.vel
                assert all(map(math.isfinite, (*p, *v, b.angle, b.angular_velocity))), (k, b)
                # The shape's centroid, which is inside it (a body's position need not be: a
                # triangle with its origin on an edge rests with it on the floor).
                shape = b.shape
                c = b.local_to_world(shape.centroid) if isinstance(shape, Polygon) else p
                assert abs(c.x) < half[0] and abs(c.y) < half[1], f"step {k}: {b} left the room"
                d = depth_in_walls(b, half)
                seen["deepest"] = max(seen["deepest"], d)
                seen[f"deepest {i}"] = max(seen[f"deepest {i}"], d)
                # Deeper than WALL_DEPTH only where the World has said its pile is past the
                # solver (StabilityWarning): a 10 kg capsule landing on a 0.1 kg box presses
                # the box 0.13 m into the floor for a few steps (a mass ratio of 100, the
                # soft step's known limit), and the World warns of it.
                assert d <= WALL_DEPTH or warned, f"step {k}: {b} is {d:.4f} m in a wall"
        if saved is not None:
            w.restore(saved)
            for k in range(snap, spec["steps"]):  # type: ignore[arg-type]
                w.step(DT)
                assert state(w, bodies) == trace[k], f"the replay from step {snap} differs at {k}"
    for c in caught:
        if issubclass(c.category, StabilityWarning):
            seen["stability"] += 1
        elif issubclass(c.category, OverlapWarning):
            seen["overlap"] += 1
        else:
            raise AssertionError(f"an undocumented warning: {c.category.__name__}: {c.message}")
    return trace, seen


def _fixed_box(at: tuple[float, float]) -> dict[str, Any]:
    """A 1 m box that never turns, at rest at ``at``, of no bounce or friction."""
    return {"kind": "box", "geometry": (1.0, 1.0, 0.0), "mass": 1.0, "restitution": 0.0,
            "friction": 0.0, "angle": 0.0, "spin": 0.0, "speed": 0.0, "heading": 0.0,
            "fixed": True, "at": at}  # fmt: skip


@fuzz(SCENES)
# An exploring run's scene (2026-12-03): discs and capsules of fixed rotation in a room with no
# gravity. The soft step had dropped a pair of bodies' speculative point whose path, at the
# step's start, passed by (engine.geometry.passing); a neighbour pushed one into the other
# within the step, and a disc ended 0.126 m in the floor at step 6. Pairs of bodies keep
# their points now.
@example(
    spec={
        "half": (6.0, 5.0),
        "walls": "room",
        "wall_material": (0.0, 0.0),
        "gravity": 0.0,
        "steps": 60,
        "snap": 0,
        "kinematic": None,
        "bodies": [
            {
                "kind": "capsule",
                "geometry": (0.5, 0.25),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-4.975, -3.975),
            },
            {
                "kind": "disc",
                "geometry": (0.5,),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-4.975, -1.9250000000000003),
            },
            {
                "kind": "box",
                "geometry": (1.0, 1.0, 0.0),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (1.174999999999999, -1.9250000000000003),
            },
            {
                "kind": "box",
                "geometry": (1.0, 1.0, 0.0),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (1.174999999999999, 0.125),
            },
            {
                "kind": "capsule",
                "geometry": (0.5, 0.25),
                "mass": 5.0,
                "restitution": 0.25,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 56.0,
                "heading": -1.25,
                "fixed": True,
                "at": (-4.975, 0.125),
            },
            {
                "kind": "disc",
                "geometry": (0.5,),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 26.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-2.9250000000000003, -1.9250000000000003),
            },
            {
                "kind": "disc",
                "geometry": (0.5,),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-2.9250000000000003, 2.174999999999999),
            },
            {
                "kind": "disc",
                "geometry": (0.4375,),
                "mass": 0.25,
                "restitution": 0.5,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 6.0,
                "heading": 2.0,
                "fixed": True,
                "at": (-2.9250000000000003, 0.125),
            },
            {
                "kind": "capsule",
                "geometry": (0.71875, 0.28125),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-4.975, 2.174999999999999),
            },
            {
                "kind": "disc",
                "geometry": (0.5,),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-0.875, -1.9250000000000003),
            },
            {
                "kind": "capsule",
                "geometry": (0.5, 0.25),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-0.875, 2.174999999999999),
            },
            {
                "kind": "capsule",
                "geometry": (0.5, 0.25),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (1.174999999999999, -3.975),
            },
        ],
        "solver": "auto",
    }
)
# An exploring run's scene (2026-12-03, numpy path, 6 of its first 19 scenes failed alike): a
# 0.44 m disc at rest on the floor of a room of 1 m polygon walls, on the exact models, under a
# 9.7 kg polygon falling at 87 m/s. The pile's soft step squeezed it out along the floor at
# 88 m/s, 2 m in the step, through the left wall, which it had no row with (its rows reach
# 0.05 r + |v0| dt from the start, and it started at rest): it ended at x = -4.44, outside the
# room. A disc sent past its reach now stops where its path first touches a face it had no
# row with (engine.exact.pile.set_back).
@example(
    spec={
        "half": (3.0, 3.0),
        "walls": "polygons",
        "wall_material": (0.0, 0.75),
        "gravity": 0.0,
        "steps": 60,
        "snap": 0,
        "kinematic": None,
        "bodies": [
            {
                **_fixed_box((-2.375, -2.375)),
                "kind": "disc",
                "geometry": (0.44,),
                "mass": 0.25,
                "friction": 0.35,
                "speed": 85.0,
            },
            {
                **_fixed_box((-2.375, -1.1)),
                "kind": "polygon",
                "geometry": ([0.85, 0.55, 0.675, 0.53, 0.33, 0.72, 0.98], 1.0, 0.46, 0.0),
                "mass": 9.7,
                "speed": 87.5,
                "heading": -1.45,
            },
            {**_fixed_box((-1.1, -2.375)), "geometry": (1.0, 0.5, 0.0)},
        ],
        "solver": "exact",
    }  # fmt: skip
)
@given(spec=scenes())
def test_mixed_scenes_stay_finite_in_the_room_and_replay_bit_for_bit(spec: dict[str, Any]) -> None:
    first, seen = run(spec, snap=spec["snap"])
    again, _ = run(spec)
    differ = [k for k, (a, b) in enumerate(zip(first, again, strict=True)) if a != b]
    assert not differ, f"the rerun differs from step {differ[0]}"
    note(f"seen: {seen}")


def test_a_ball_landing_on_a_box_stays_above_a_polygon_floor() -> None:
    # Found by the scene fuzz (with four 1 m Polygon walls): a 1 m box resting on a static
    # Polygon floor 1 m thick (y from -4 to -3), a ball of radius 0.5 let go above it. As the
    # ball comes within the box's reach it joins the box's pile, whose rows took every solid
    # face within reach of it (engine.exact.pile_rows.face_rows): the floor's bottom face (normal
    # (0, -1) at y = -4, one-sided) put the ball 3.35 m "into" it, and the soft step's
    # projection moved it out there, to y = -4.5, at step 16. A polygon's faces now give a
    # ball a row only at its face of greatest separation (``_fronts``).
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -9.81)))
    w.add_collider(Polygon([(-4.0, -4.0), (4.0, -4.0), (4.0, -3.0), (-4.0, -3.0)]))
    w.add(Body(Vector(0.0, -2.5), shape=Polygon.box(1.0, 1.0), restitution=0.0))
    ball = w.add(Body(Vector(0.0, -0.8), radius=0.5, restitution=0.0))
    for _ in range(30):
        w.step(1.0 / 60.0)
        assert ball.pos.y > -2.0, ball.pos


def test_a_huge_rounding_is_refused_by_name() -> None:
    # Found by the construction fuzz with FUZZ_LONG=1: a triangle 1e-4 m wide rounded by 1e300
    # raised OverflowError from Polygon(...) (engine/geometry/convex.py, the sectors' r**3), not a
    # ValueError naming radius. Polygon.box(1, 1, radius=1e300) did the same.
    for make in (
        lambda: Polygon([(0.0, 0.0), (1e-4, 0.0), (0.0, 1e-4)], radius=1e300),
        lambda: Polygon.box(1.0, 1.0, radius=1e300),
    ):
        with pytest.raises(ValueError) as exc:
            make()
        refused(exc.value, "radius")
    # A rounding the float range holds is kept.
    assert Polygon.box(1.0, 1.0, radius=1e100).area == pytest.approx(math.pi * 1e200)


#: The room of the long fuzz's scenes below, as hypothesis shrank them (no gravity, 60 steps).
_SHRUNK_ROOM: dict[str, Any] = {
    "half": (4.546275801218975, 4.115578676986017),
    "walls": "room",
    "wall_material": (0.777778317812019, 0.0),
    "gravity": 0.0,
    "steps": 60,
    "snap": 0,
    "kinematic": None,
}


def test_a_box_pushed_into_the_ceiling_by_another_stays_in_the_room() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1, fast path): at step 25 the 0.94 x 0.1 m box
    # (body 2) ended with its centre 0.028 m past the ceiling, pushed from behind by the
    # heavier capsule: 0.49 m in the step at 18.7 m/s, from 0.41 m below the ceiling, so no
    # row with it (its own speed covers 0.31 m), and no impact on its start motion. It is now
    # stopped where its straight move first touches the ceiling (engine.exact.shape_impacts).
    spec = {
        **_SHRUNK_ROOM,
        "bodies": [
            {
                "kind": "capsule",
                "geometry": (0.5916442123757829, 0.1),
                "mass": 1.8334745924213043,
                "restitution": 0.8505595029203568,
                "friction": 0.6444984101954271,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 49.73973292451122,
                "heading": -1.542756739296369,
                "fixed": True,
                "at": (-3.8296315888431924, -1.965646039858668),
            },
            {
                "kind": "box",
                "geometry": (0.1, 0.7900274988431263, 0.0),
                "mass": 0.3333333333333333,
                "restitution": 0.8993278345358483,
                "friction": 0.6514455216901592,
                "angle": 1.0,
                "spin": 0.0,
                "speed": 0.1,
                "heading": 0.0,
                "fixed": True,
                "at": (-3.8296315888431924, -3.398934464610234),
            },
            {
                "kind": "box",
                "geometry": (0.9399090108438946, 0.1, 0.0),
                "mass": 0.1,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.9079782966682873,
                "heading": 0.25,
                "fixed": True,
                "at": (-3.8296315888431924, -0.5323576151071023),
            },
            {
                "kind": "box",
                "geometry": (0.1, 0.41810232930382274, 0.0),
                "mass": 8.351497991277535,
                "restitution": 0.0016213262053075277,
                "friction": 0.01784578143226501,
                "angle": 0.276365268460236,
                "spin": 59.948083326251265,
                "speed": 93.16912018995995,
                "heading": 0.4661686242455194,
                "fixed": False,
                "at": (-3.8296315888431924, 0.9009308096444633),
            },
        ],
    }
    run(spec)


def test_a_light_polygon_struck_into_a_wall_by_a_heavy_disc_stays_out_of_it() -> None:
    # Found by the fast path's exploring fuzz (find 11, 2026-12-05), cut down to its two
    # bodies: a 6 kg disc at 88 m/s behind a 1 kg rounded polygon, both along +x at the
    # room's wall, no gravity, the soft step (solver "auto"). The polygon struck the wall and
    # bounced; the disc struck it back into the wall, and the soft solver moved it by its
    # velocity less half the "held" change of it (exact for a held force), where the wall's
    # last impulse (an impact's, -58.8 m/s a part) counted as held and the disc's fresh push
    # did not: 0.115 m into the wall in a step, though its rows had stopped it at 0.23 m/s,
    # and no StabilityWarning. A held change of an impact's size (over 1 m/s a part) is now
    # at most the part's own change of velocity, and of its sign (engine.dynamics.solver,
    # ``_within``): 1.2 mm.
    spec = {
        "half": (6.584629063534493, 6.11),
        "walls": "room",
        "wall_material": (0.6095436360079732, 0.0),
        "gravity": 0.0,
        "steps": 20,
        "snap": 0,
        "kinematic": None,
        "solver": "auto",
        "bodies": [
            {
                "kind": "polygon",
                "geometry": (
                    [0.52, 0.662341146314867, 0.7017350256411681, 0.5843150158082417,
                     0.5380520562650017], 1.0, 0.6405326664302635, 0.05,
                ),
                "mass": 1.019302629360792,
                "restitution": 0.6202574237647608,
                "friction": 0.1409344979950067,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (2.717295600058934, 1.7608593307328988),
            },
            {
                "kind": "disc",
                "geometry": (0.4375,),
                "mass": 6.0,
                "restitution": 0.0,
                "friction": 1.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 88.0,
                "heading": 0.0,
                "fixed": True,
                "at": (1.2862302671984063, 1.7608593307328988),
            },
        ],
    }  # fmt: skip
    _, seen = run(spec)
    assert seen["deepest"] < 0.005, seen
    # The disc (no bullet: Box2D sweeps a body against static shapes alone) ends step 2
    # 13.4 cm into the polygon, 31% of its radius, and the World says so, once (the soft
    # step's limit told: engine.pipeline.stepping's ``SOFT_GIVE``).
    assert seen["stability"] == 1, seen


def test_a_polygon_knocked_on_into_a_wall_it_was_turning_into_stays_out_of_it() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1): at step 6 the thin polygon (body 2, 9 kg,
    # 6 mm from the right wall, turning at -77 rad/s toward it) is struck by the spinning
    # 8.4 kg polygon behind it. The pair's impact was retaken at its moment (0.0094 s) on the
    # start motions, and the polygon placed there 0.136 m into the wall: its own start motion
    # reached the wall before the two met. The wall's moment, the earlier, now places it
    # (engine.exact.shape_impacts, ``retake``): it ends the step touching the wall.
    spec = {
        **_SHRUNK_ROOM,
        "bodies": [
            {
                "kind": "capsule",
                "geometry": (0.5916442123757829, 0.1),
                "mass": 1.8334745924213043,
                "restitution": 0.8505595029203568,
                "friction": 0.6444984101954271,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 49.73973292451122,
                "heading": -1.542756739296369,
                "fixed": True,
                "at": (1.9035221101630713, 2.3342192343960297),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [0.78125, 0.75, 0.34375, 0.8993278345358483, 0.6514455216901592, 1.0],
                    0.5,
                    0.1,
                    0.0,
                ),
                "mass": 8.421710106135983,
                "restitution": 0.8521328216097326,
                "friction": 0.9399090108438946,
                "angle": -2.435168987991175,
                "spin": 0.0,
                "speed": 54.56915472618115,
                "heading": 0.0,
                "fixed": False,
                "at": (-0.9630547393400608, -0.5323576151071023),
            },
            {
                "kind": "polygon",
                "geometry": ([0.90625, 0.25, 0.5, 0.5], 0.2, 0.421875, 0.0),
                "mass": 9.0,
                "restitution": 0.00390625,
                "friction": 0.015625,
                "angle": 0.25,
                "spin": 60.0,
                "speed": 93.25,
                "heading": 0.46875,
                "fixed": False,
                "at": (-2.3963431640916264, -3.398934464610234),
            },
            {
                "kind": "box",
                "geometry": (0.5, 1.0, 0.0),
                "mass": 1.0,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-3.8296315888431924, 0.9009308096444633),
            },
        ],
    }
    run(spec)


@pytest.mark.parametrize("solver", ["exact", "auto"])
def test_a_fast_spinning_capsule_among_fixed_boxes_stays_out_of_the_wall(solver: str) -> None:
    # On the exact models it ended step 1 0.111 m into the left wall (the bound: 0.1 m): the
    # advancement of its moment ran out of rounds, as the grazing 8-gon's (below) did, and
    # counted no impact; the rest of the step is now searched (``_first_touch``).
    # Found by the shapes fuzz while it shrank a failure (2026-12-03, on both paths): a 0.25 m
    # capsule at 40 m/s, heading 3 rad and turning -9 rad/s, starts 0.9 m from the left wall
    # of a 6 m room without gravity, among four fixed 1 m boxes, a fixed capsule and a
    # kinematic box at the centre. At step 0 one end strikes the wall and the capsule spins
    # off it at 98 rad/s; at step 1 the other end swings a quarter turn into the wall. On the
    # soft step (auto's choice here) the continuous stage's sweep of a pair that touches at
    # the start (engine.dynamics.game_continuous) sets it back where its cores came a slop
    # nearer than they started: it ends 8 mm in, where Box2D's fallback alone left 0.112 m.
    spec = {
        "half": (3.0, 3.0), "walls": "room", "wall_material": (0.0, 0.0), "gravity": 0.0,
        "steps": 60, "snap": 0, "kinematic": ("box", 0.5, 0.25, 0.0), "solver": solver,
        "bodies": [
            {**_fixed_box((-2.1, -2.1)), "kind": "capsule", "geometry": (0.625, 0.25)},
            _fixed_box((-2.1, -0.2999999999999998)),
            _fixed_box((-0.2999999999999998, -2.1)),
            _fixed_box((1.5, -2.1)),
            _fixed_box((1.5, 1.5)),
            {**_fixed_box((-2.1, 1.5)), "kind": "capsule", "geometry": (0.25, 0.0625),
             "angle": 0.5, "spin": -9.0, "speed": 40.0, "heading": 3.0, "fixed": False},
        ],
    }  # fmt: skip
    run(spec, snap=0)


def test_a_spinning_polygon_that_grazes_the_floor_before_it_goes_in_stays_out() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1): at step 4 a thin 8-gon (body 2) turning at
    # -47 rad/s passes a corner within 27 um of the floor and then goes in; the conservative
    # advancement for its moment crept on by a hair a round at the graze, ran out of rounds
    # and counted no impact, and it ended the step 0.143 m in the floor. Out of rounds, the
    # rest of the step is now searched for where it is first in, and the moment it touches
    # found by bisection (engine.exact.shape_impacts, ``_first_touch``).
    spec = {
        "half": (7.238069437585297, 4.5),
        "walls": "room",
        "wall_material": (3.294732097155501e-244, 0.0),
        "gravity": 0.98,
        "steps": 120,
        "snap": 68,
        "kinematic": None,
        "bodies": [
            {
                "kind": "box",
                "geometry": (0.6911759931115531, 0.4873000331988705, 0.0),
                "mass": 4.129777627384456,
                "restitution": 0.0,
                "friction": 0.7639249409908562,
                "angle": 3.0847410076620623,
                "spin": 3.513447535632571e-248,
                "speed": 70.20812643952434,
                "heading": 5.054370643954588e-103,
                "fixed": False,
                "at": (-6.61549319400992, 2.3483386793291494),
            },
            {
                "kind": "box",
                "geometry": (1.0894804419770996, 0.4734029807742819, 0.0),
                "mass": 3.1921188423821065,
                "restitution": 0.215,
                "friction": 0.23359385924211568,
                "angle": 0.03245341098572618,
                "spin": -20.453283792039016,
                "speed": 5e-324,
                "heading": 4.7455550391148835e-265,
                "fixed": False,
                "at": (0.8554217288946067, 2.3483386793291494),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [
                        0.924729849717896,
                        0.4286759135193237,
                        0.9809454249233676,
                        0.5271726862708053,
                        0.9472959649399391,
                        0.7865180076108738,
                        0.9472959649399391,
                        0.8918154816564805,
                    ],
                    0.2,
                    0.5975762435753772,
                    0.0,
                ),
                "mass": 0.2873463019787252,
                "restitution": 0.7728661668234402,
                "friction": 0.037184914069273496,
                "angle": 2.894867547239282,
                "spin": 74.51500594967743,
                "speed": 53.4273670798657,
                "heading": -0.9560890166781433,
                "fixed": False,
                "at": (-2.8800357325576567, -1.387118782123114),
            },
            {
                "kind": "capsule",
                "geometry": (0.46780698707891344, 0.0350120738060104),
                "mass": 0.3333333333333333,
                "restitution": 0.37967880400602827,
                "friction": 0.9541742322472715,
                "angle": 2.7886046582422948,
                "spin": 94.68968925296144,
                "speed": 95.80303147001223,
                "heading": -2.305082870284117,
                "fixed": False,
                "at": (-5.3703407068591655, 2.3483386793291494),
            },
        ],
    }
    run(spec)


def test_a_thin_polygon_spun_off_a_wall_by_its_corner_stays_out_of_it() -> None:
    # Found exploring the mixed scenes (FUZZ_EXAMPLES=300, fast path; numpy alike), reduced
    # to its one body: a thin 8-gon (0.87 kg, 0.98 m by 0.17 m) thrown at 81 m/s down and to
    # the left, alone in a room without gravity, on the exact models. At step 0 a corner
    # strikes the left wall and it spins off at 50 rad/s; in step 1 it turns 1 rad and ends
    # 0.19 m in the wall (the bound: 0.1 m), where the same body ends 2 mm short of it on the soft
    # step. The grazing 8-gon's bug (above): the advancement against the wall, from a corner
    # 0.1 mm off it, crept on by a hair a round (its gap 9.7e-5 m to 1.2e-4 m in its 50
    # rounds), ran out of them and counted no impact.
    spec = {
        "half": (3.0, 5.256068631653733), "walls": "room", "wall_material": (0.0, 0.0),
        "gravity": 0.0, "steps": 60, "snap": 0, "kinematic": None, "solver": "exact",
        "bodies": [
            {"kind": "polygon",
             "geometry": ([0.6377980159112417, 0.25, 0.9469682095683524, 0.982040984276159,
                           0.6249576468302744, 0.9562225911916955, 0.6349861448256828, 0.25],
                          0.2, 0.49391098412203793, 0.0),
             "mass": 0.8700525609240923, "restitution": 0.0, "friction": 0.0,
             "angle": -2.171190390910053, "spin": 0.0, "speed": 80.90399644081543,
             "heading": -1.8966312184585101, "fixed": False,
             "at": (-2.2913759631448265, 1.1215477000428287)},
        ],
    }  # fmt: skip
    run(spec)


def test_a_thin_spinning_polygon_falling_beside_a_disc_stays_out_of_the_wall() -> None:
    # Found on the exact models as a strict xfail before a body was held about its centre of
    # mass (engine.body_shapes): the 7-gon, drawn off its centroid, turned about its frame's
    # origin and ended step 14 0.19 m in the wall. Held about its centroid it stays out.
    # Found by a scan of 1,372 fresh scenes of the mixed-scenes test (fast path; numpy alike),
    # reduced to two bodies: a thin 7-gon (1.47 kg) thrown down at 18.7 m/s turning at
    # 31.7 rad/s and a 0.58 m disc at 28 m/s, under gravity 14.3 in a room (Box).
    run(
        {
            "half": (7.510074796601765, 7.62562426981028),
            "walls": "room",
            "wall_material": (0.38170221231833124, 0.16535274360343613),
            "gravity": 14.295681071392378,
            "steps": 16,
            "snap": 108,
            "kinematic": None,
            "bodies": [
                {
                    "kind": "polygon",
                    "geometry": (
                        [
                            0.9085656700093552,
                            1.0,
                            0.5610082544479084,
                            0.635443295299853,
                            0.7357924471005258,
                            0.25000000000000006,
                            0.9586317483548188,
                        ],
                        0.2,
                        0.4263390202143692,
                        0.0,
                    ),
                    "mass": 1.470110886454675,
                    "restitution": 1e-07,
                    "friction": 6.6283072941289116e-276,
                    "angle": -1.7169503472850025,
                    "spin": 31.74155540316505,
                    "speed": 18.72680890344012,
                    "heading": -1.5866851263965787,
                    "fixed": False,
                    "at": (-1.7737415959502147, -3.1640317804146294),
                },
                {
                    "kind": "disc",
                    "geometry": (0.5816986075830435,),
                    "mass": 1.9,
                    "restitution": 0.01038094606994089,
                    "friction": 0.21069125702131558,
                    "angle": -2.1595376972453426,
                    "spin": 5.1360694257378075e-278,
                    "speed": 28.062835935947454,
                    "heading": -2.831146527597887,
                    "fixed": True,
                    "at": (2.050480537817485, -4.43877249167053),
                },
            ],
            "solver": "exact",
        }
    )


def test_a_disc_struck_into_a_corner_of_polygon_walls_stays_out_of_them() -> None:
    # Found by a scan of 1,372 fresh scenes of the mixed-scenes test (fast path; numpy alike),
    # reduced to three bodies (the box, far off, makes World() choose the soft step): no
    # gravity; the 0.52 m disc (1.05 kg, fixed rotation) reaches the floor at step 2, the
    # 5 kg disc thrown at 88 m/s bounces off the floor and strikes it at step 3, sending it
    # left along the floor at 78 m/s into the bottom left corner; at step 4 it was 0.145 m in
    # (the bound: 0.1 m), without a StabilityWarning. The 5 kg disc that strikes it (six of its
    # radii a step) has a speculative row with it along the normal of the step's start, which
    # turns 34 degrees as they pass (Box2D's rows are the same, linear in the step): it ended
    # step 3 0.1425 m into the light disc, and step 4's rows pushed the light one out of it
    # into the wall. A strict xfail until 2026-12-05: since then the continuous stage sweeps a
    # body whose contacts with what does not move end deeper than a quarter of its least
    # extent (engine.dynamics.game_continuous, ``DEEP``), and the light disc ends 0.01 m in.
    _, seen = run(
        {
            "half": (7.713322514063948, 6.073881719610145),
            "walls": "polygons",
            "wall_material": (0.409592794218825, 0.11901805676927071),
            "gravity": 2.2250738585e-313,
            "steps": 6,
            "snap": 104,
            "kinematic": None,
            "bodies": [
                {
                    "kind": "disc",
                    "geometry": (0.5208207798891358,),
                    "mass": 1.05,
                    "restitution": 0.7363995625060594,
                    "friction": 0.8,
                    "angle": -0.5492845800434623,
                    "spin": 3.0712623000754437e-176,
                    "speed": 34.017554754538565,
                    "heading": -2.141592653589793,
                    "fixed": True,
                    "at": (-5.706874539505593, -4.06743374505179),
                },
                {
                    "kind": "disc",
                    "geometry": (0.24227706715820063,),
                    "mass": 5.052509322137923,
                    "restitution": 0.7949198072465509,
                    "friction": 1e-09,
                    "angle": -1.175494351e-38,
                    "spin": -1.192092896e-07,
                    "speed": 88.3682609764061,
                    "heading": -2.2395317476856356,
                    "fixed": False,
                    "at": (-3.0316105734277885, -2.729801762012888),
                },
                {
                    "kind": "box",
                    "geometry": (0.31231085808120596, 0.7760881330806797, 0.05),
                    "mass": 9.241834914811658,
                    "restitution": 6.66503669006511e-93,
                    "friction": 0.2843848946501986,
                    "angle": -0.5,
                    "spin": 1.1754943508222875e-38,
                    "speed": 73.66073550897417,
                    "heading": 0.08795607700096264,
                    "fixed": True,
                    "at": (-4.369242556466691, 1.2830941871038197),
                },
            ],
            "solver": "auto",
        }
    )
    assert seen["deepest"] <= 0.25 * 0.5208207798891358, seen


def test_a_capsule_rising_into_the_ceiling_as_a_box_meets_it_stays_below() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1): at step 15 the capsule (body 0) rises at
    # 16.5 m/s 32 mm below the ceiling as the spinning polygon meets it. The pair was taken
    # again from its moment, later than the capsule's own reaching the ceiling, and where the
    # rest of the step ended the two deep in each other they were put back at that moment:
    # the capsule 0.103 m into the ceiling, its centre past it. The ceiling's moment on the
    # start motion, the earlier, now places it.
    spec = {
        **_SHRUNK_ROOM,
        "bodies": [
            {
                "kind": "capsule",
                "geometry": (0.5916442123757829, 0.1),
                "mass": 1.8334745924213043,
                "restitution": 0.8505595029203568,
                "friction": 0.6444984101954271,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 49.73973292451122,
                "heading": -1.542756739296369,
                "fixed": True,
                "at": (1.9035221101630713, 2.3342192343960297),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [
                        0.7900274988431263,
                        0.9049728003391908,
                        0.3333333333333333,
                        0.8993278345358483,
                        0.6514455216901592,
                        1.0,
                    ],
                    0.5,
                    0.1,
                    0.0,
                ),
                "mass": 8.421710106135983,
                "restitution": 0.8521328216097326,
                "friction": 0.9399090108438946,
                "angle": -2.435168987991175,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": False,
                "at": (-0.9630547393400608, -0.5323576151071023),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [0.9079782966682873, 0.25, 0.5349860129039891, 0.5],
                    0.2,
                    0.41810232930382274,
                    0.0,
                ),
                "mass": 8.351497991277535,
                "restitution": 0.0016213262053075277,
                "friction": 0.01784578143226501,
                "angle": 0.276365268460236,
                "spin": 59.948083326251265,
                "speed": 93.16912018995995,
                "heading": 0.4661686242455194,
                "fixed": False,
                "at": (-2.3963431640916264, -3.398934464610234),
            },
            {
                "kind": "box",
                "geometry": (0.7253051734871245, 0.6621911439075416, 0.0),
                "mass": 1.6816668422869354,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (-3.8296315888431924, -0.5323576151071023),
            },
        ],
    }
    run(spec)


def test_a_thin_polygon_stays_in_the_room_over_three_seconds_of_a_crowded_drop() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1, numpy) against a fix for the grazing 8-gon
    # above (taking an advancement that ran out of rounds where it got to): a body then left
    # the room at step 147. It stays in without that fix; this keeps the next attempt honest.
    spec = {
        "half": (4.6, 4.432030261347735),
        "walls": "room",
        "wall_material": (0.752615701296111, 1.192092896e-07),
        "gravity": 19.845106339584536,
        "steps": 180,
        "snap": 82,
        "kinematic": None,
        "bodies": [
            {
                "kind": "polygon",
                "geometry": (
                    [
                        0.3333333333333333,
                        0.987903848193274,
                        0.4887992893801666,
                        0.3,
                        0.6034303398690813,
                    ],
                    1.0,
                    0.11972900045383415,
                    0.05,
                ),
                "mass": 4.48747889862088,
                "restitution": 0.20991284750815847,
                "friction": 0.4383190389239643,
                "angle": 1.9419769407121734,
                "spin": 3.0945613150407607e-108,
                "speed": 37.77310429964954,
                "heading": -1.0343126127529598,
                "fixed": False,
                "at": (-3.5219911269402253, -1.1980036421684117),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [
                        0.3109525330158197,
                        0.3198205254503988,
                        0.3501176017687645,
                        0.6515943190747494,
                        0.25040100412828564,
                        0.8250664004330064,
                        0.30558755202477844,
                        0.48842536298411904,
                    ],
                    1.0,
                    0.6912949683603132,
                    0.0,
                ),
                "mass": 8.843684376972645,
                "restitution": 7.769214373918728e-174,
                "friction": 0.6854276077949887,
                "angle": 0.52,
                "spin": 99.0,
                "speed": 44.17486997164962,
                "heading": 0.34,
                "fixed": False,
                "at": (-3.5219911269402253, -3.3540213882879604),
            },
            {
                "kind": "disc",
                "geometry": (0.18627549820504946,),
                "mass": 0.745,
                "restitution": 0.7488657292256268,
                "friction": 0.8910896616772048,
                "angle": 2.442989749176735e-213,
                "spin": 93.75064297016462,
                "speed": 17.0,
                "heading": 1.3128754206150663,
                "fixed": False,
                "at": (-3.5219911269402253, 0.958014103951137),
            },
            {
                "kind": "polygon",
                "geometry": (
                    [0.35470968985062157, 0.858420049393309, 0.6425116468471912],
                    0.2,
                    0.5437466780469272,
                    0.0,
                ),
                "mass": 1.5234811913388637,
                "restitution": 6.829454988769013e-222,
                "friction": 0.9779674775095419,
                "angle": -0.5313420109271458,
                "spin": 14.792578289226626,
                "speed": 80.55699139155044,
                "heading": 1.25,
                "fixed": False,
                "at": (-3.5219911269402253, 3.1140318500706856),
            },
            {
                "kind": "box",
                "geometry": (0.35035033605546806, 1.1, 0.0),
                "mass": 9.750937907986438,
                "restitution": 0.822138371944741,
                "friction": 1.175494351e-38,
                "angle": -3.1297681226081275,
                "spin": 1.727827783551512e-301,
                "speed": 94.84928579620673,
                "heading": 2.469568455651091,
                "fixed": True,
                "at": (-1.3659733808206767, -3.3540213882879604),
            },
            {
                "kind": "disc",
                "geometry": (0.47,),
                "mass": 0.99999,
                "restitution": 0.6529041042375773,
                "friction": 2.225073858507e-311,
                "angle": -0.8442816431959699,
                "spin": 1.1541838210774625e-64,
                "speed": 70.41349155485347,
                "heading": 1.50236803166609,
                "fixed": True,
                "at": (-1.3659733808206767, -1.1980036421684117),
            },
            {
                "kind": "box",
                "geometry": (0.7385864821855644, 0.8091769503430349, 0.0),
                "mass": 0.98,
                "restitution": 0.8526528936721243,
                "friction": 0.6633606959789752,
                "angle": 0.155,
                "spin": 6.681807107889554,
                "speed": 10.354627863036272,
                "heading": 9.626771771403385e-31,
                "fixed": False,
                "at": (-1.3659733808206767, 0.958014103951137),
            },
            {
                "kind": "capsule",
                "geometry": (0.7999348726251763, 0.25307400043459816),
                "mass": 6.751107371074613,
                "restitution": 0.6226312207353525,
                "friction": 0.0724703408386418,
                "angle": -0.8933334158180548,
                "spin": -2.2013307619659784e-301,
                "speed": 2.2250738585072014e-308,
                "heading": -2.4151942881251887,
                "fixed": False,
                "at": (-1.3659733808206767, 3.1140318500706856),
            },
            {
                "kind": "box",
                "geometry": (0.1, 0.44620868325892515, 0.0),
                "mass": 0.9999999999999999,
                "restitution": 1.0,
                "friction": 0.7710627979498552,
                "angle": 0.5906426723762145,
                "spin": 0.46032598553199755,
                "speed": 0.52,
                "heading": 0.0,
                "fixed": True,
                "at": (0.790044365298872, -3.3540213882879604),
            },
            {
                "kind": "capsule",
                "geometry": (0.1, 0.03),
                "mass": 0.1,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.0,
                "spin": -1.4151796842779196,
                "speed": 0.0,
                "heading": 0.0,
                "fixed": True,
                "at": (0.790044365298872, -1.1980036421684117),
            },
            {
                "kind": "box",
                "geometry": (0.5355972293283774, 0.2723672847107648, 0.0),
                "mass": 0.1,
                "restitution": 0.0,
                "friction": 0.0,
                "angle": 0.05,
                "spin": 0.0,
                "speed": 0.0,
                "heading": 0.24719714346121938,
                "fixed": True,
                "at": (2.9460621114184207, 0.958014103951137),
            },
        ],
    }
    run(spec)


#: Found exploring the mixed scenes (500 examples, numpy, 2026-12-04), on the exact models: a
#: crowd of 12 bodies from 0.1 to 9.6 kg dropped in a room 6 m wide. The World warns at step 11
#: that the pile is past what 4 contact iterations a step can hold; at step 76 the 0.1 m wide
#: box (body 7, 0.16 kg), squeezed by the heavy ones, is 0.0755 m into the right wall, its
#: centre 0.0255 m past it. With 8 iterations, as the warning advises, the deepest is 0.025 m
#: and every body stays in; with 16, 0.6 mm. Since a body that begins a step in a wall by no
#: more than the soft step's give is taken again where it ends deeper by that again
#: (engine.exact.shape_impacts, 2026-12-05), 4 iterations keep the box to 0.047 m as well.
CROWD_PAST_ITS_ITERATIONS: dict[str, Any] = {
    "half": (3.0, 7.84408796347998),
    "walls": "room",
    "wall_material": (0.0, 0.0),
    "gravity": 7.07828761080486,
    "steps": 120,
    "snap": 0,
    "kinematic": None,
    "solver": "exact",
    "bodies": [
        {
            **_fixed_box((-2.0272326398926266, -4.925785883157859)),
            "kind": "capsule",
            "geometry": (0.7135602956601945, 0.23420706444717906),
            "mass": 0.155,
            "speed": 82.99477579953869,
        },
        {
            **_fixed_box((-2.0272326398926266, -1.0347164427283646)),
            "kind": "polygon",
            "geometry": (
                [0.5625349723417749, 0.25, 0.5216767768394381],
                1.0,
                0.3393378497197621,
                0.0,
            ),
            "mass": 4.253678673125816,
        },
        {
            **_fixed_box((-2.0272326398926266, -2.9802511629431123)),
            "kind": "capsule",
            "geometry": (0.25, 0.2623342485321345),
            "mass": 8.965877300776489,
            "speed": 9.288045820504733,
        },
        {
            **_fixed_box((1.863836800536868, 2.85635299770113)),
            "kind": "capsule",
            "geometry": (0.6258653336691613, 0.12649311579365427),
            "mass": 1.790339338494073,
            "restitution": 0.118,
            "angle": -0.2013782909940658,
            "speed": 4.288523265471556,
            "fixed": False,
        },
        {
            **_fixed_box((-2.0272326398926266, 2.85635299770113)),
            "kind": "polygon",
            "geometry": (
                [0.5625349723417749, 0.25, 0.5216767768394381],
                0.5,
                0.11279455518750653,
                0.0,
            ),
            "mass": 9.571699394404085,
            "restitution": 0.43366699951203624,
            "speed": 23.245273979915744,
        },
        {
            **_fixed_box((1.863836800536868, -6.871320603372607)),
            "geometry": (0.4954966692296363, 0.1, 0.0),
            "mass": 0.3768480243365061,
        },
        {
            **_fixed_box((1.863836800536868, 4.801887717915877)),
            "geometry": (0.1, 0.1, 0.0),
            "mass": 0.4162973529198356,
        },
        {
            **_fixed_box((1.863836800536868, -2.9802511629431123)),
            "geometry": (0.1, 0.599371482953266, 0.0),
            "mass": 0.1558205539346993,
        },
        {
            **_fixed_box((-0.08169791967787887, -4.925785883157859)),
            "geometry": (0.39934013614254377, 0.956478602329816, 0.0),
            "mass": 0.724639555572002,
        },
        {
            **_fixed_box((-0.08169791967787887, 4.801887717915877)),
            "geometry": (0.1, 0.1, 0.0),
            "mass": 0.1,
        },
        {
            **_fixed_box((1.863836800536868, 6.747422438130624)),
            "geometry": (0.1, 0.1, 0.0),
            "mass": 0.14211955104497323,
        },
        {
            **_fixed_box((-0.08169791967787887, -6.871320603372607)),
            "geometry": (0.1, 0.1, 0.0),
            "mass": 0.18448348304669876,
            "speed": 18.594559951898646,
        },
    ],
}


@pytest.mark.parametrize("iterations", [4, 8])
def test_a_crowd_past_its_iterations_stays_in_the_room_with_the_iterations_the_warning_asks(
    iterations: int,
) -> None:
    stays_in_the_room(CROWD_PAST_ITS_ITERATIONS, iterations, 0.05)


def stays_in_the_room(spec: dict[str, Any], iterations: int, deepest: float) -> None:
    """Step ``spec``'s scene with ``iterations`` contact iterations, each body's centroid in
    the room and its shape at most ``deepest`` (m) in a wall after every step."""
    w, bodies, _ = build(spec)
    w.contact_iterations = iterations
    half = spec["half"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(spec["steps"]):
            w.step(DT)
            for b in bodies:
                shape = b.shape
                c = b.local_to_world(shape.centroid) if isinstance(shape, Polygon) else b.pos
                assert abs(c.x) < half[0] and abs(c.y) < half[1], f"step {k}: {b} left the room"
                assert depth_in_walls(b, half) <= deepest, (k, b)


# Found exploring the mixed scenes (2,000 examples, numpy path, 2026-12-05; the fast path alike,
# to the same depths), on the exact models: a 0.1 kg capsule 0.03 m thick lying on the floor is
# struck at once by an 8.6 kg capsule spinning at 19 rad/s and a 9.4 kg box sliding in at
# 5.4 m/s, a mass ratio of about 90 (the soft pile's known limit, engine/guide/contacts.md). It
# was pressed 4.5 cm into the floor, its centre 1.3 cm past the room's wall line, while a
# body's depth in a wall was counted in its bounding radius (engine.exact.shape_impacts: 5% of
# 0.66 m); counted in its least extent, the capsule is taken back to where it touched the
# floor. The pile still gives between the bodies (5.5 cm, 41% of the capsule's bounding
# radius), and the World says so.
THIN_CAPSULE_STRUCK_INTO_THE_FLOOR: dict[str, Any] = {
    "half": (3.1134376107434867, 5.762431327717733), "walls": "polygons",
    "wall_material": (0.9122131086755749, 0.9743875596018914), "gravity": 5.293643647661917,
    "steps": 120, "snap": 44, "kinematic": None, "solver": "exact",
    "bodies": [
        {"kind": "disc", "geometry": (0.23334435553227323,), "mass": 6.923209068083001,
         "restitution": 0.0, "friction": 0.01088469137500825,
         "angle": -1.7102586474386158e-259, "spin": 67.54936151817924,
         "speed": 24.84902032775314, "heading": 1.2302035341595152, "fixed": True,
         "at": (-0.5310365009938809, 3.706372741364154)},
        {"kind": "capsule", "geometry": (0.13817277318517754, 0.08023673664001896),
         "mass": 8.606993960049312, "restitution": 0.9669922311845134,
         "friction": 2.2250738585e-313, "angle": -1e-12, "spin": -59.12905702901162,
         "speed": 99.21749031076214, "heading": 6.103515625e-05, "fixed": False,
         "at": (-2.2526372408269513, 0.2631712616980133)},
        {"kind": "capsule", "geometry": (0.6428274114505916, 0.19297295846594353),
         "mass": 4.324519719616753, "restitution": 1.192092896e-07, "friction": 0.0,
         "angle": -1.8122616672823602, "spin": 0.0, "speed": 0.0, "heading": 0.0,
         "fixed": False, "at": (1.190564238839189, -4.901630957801198)},
        {"kind": "capsule", "geometry": (0.6289620759856985, 0.03), "mass": 0.1,
         "restitution": 0.0, "friction": 0.9662552525476453, "angle": 0.0, "spin": 0.0,
         "speed": 99.0, "heading": 0.0, "fixed": True,
         "at": (-2.2526372408269513, 1.9847720015310832)},
        {"kind": "box", "geometry": (0.1, 0.25, 0.0), "mass": 8.963506457406465,
         "restitution": 1e-05, "friction": 0.4906382756564963,
         "angle": -5.960464477539063e-08, "spin": 0.23334435553227323,
         "speed": 95.03415914016749, "heading": -1.2314572621719404, "fixed": False,
         "at": (-0.5310365009938809, -1.4584294781350575)},
        {"kind": "box", "geometry": (0.7290038094253348, 0.3333333333333333, 0.0),
         "mass": 9.393637137980786, "restitution": 0.4185362216560268,
         "friction": 0.07799838686077944, "angle": -3.0529246871888045, "spin": 1.9,
         "speed": 70.61894055265233, "heading": 2.7, "fixed": False,
         "at": (1.190564238839189, -1.4584294781350575)},
    ],
}  # fmt: skip


def test_a_light_capsule_struck_into_the_floor_stays_in_the_room() -> None:
    _, seen = run(THIN_CAPSULE_STRUCK_INTO_THE_FLOOR)
    assert seen["deepest"] <= 0.002, seen  # (4.5 cm in before, its centre past the floor)
    # The pile's give between the bodies is told: "past what 4 contact iterations a step can
    # hold; raise world.contact_iterations".
    assert seen["stability"] >= 1, seen


@pytest.mark.parametrize("iterations", [8, 16])
def test_a_light_capsule_struck_into_the_floor_stays_out_with_the_iterations_the_warning_asks(
    iterations: int,
) -> None:
    stays_in_the_room(THIN_CAPSULE_STRUCK_INTO_THE_FLOOR, iterations, 0.01)  # (4.5 cm at 4)


# Found exploring the mixed scenes (1,500 examples, numpy path, 2026-12-06; the fast path alike,
# to the same depth), on the exact models: a 0.1 kg box 0.1 m a side resting on the floor is
# pressed into it by an 8.2 kg box spinning at 29 rad/s that comes down on it (a mass ratio of
# 82, past the pile's 4 iterations: the World warns, "raise world.contact_iterations"). At
# step 106 it was 5.8 cm in, its centre 8 mm past the floor's line, and out again two steps
# later; with the 8 iterations the warning asks for it never goes in. It had crept 3.6 mm in by
# step 104 (1.5, 1.8, 3.6 mm: each step less than DEEP_WALL deeper), and a body that began a
# step in a wall was taken again (engine.exact.shape_impacts) only while it began at most
# DEEP_WALL in (2.5 mm: 5% of its least extent), so the pile pressed it on unchecked. Taken
# again however deep it began, it stays 3.6 mm in, held where it was until the heavy box has
# passed over it.
LIGHT_BOX_CRUSHED_INTO_THE_FLOOR: dict[str, Any] = (
    {'half': (3.0000000000000004, 6.416290342610909),
     'walls': 'polygons',
     'wall_material': (0.3490459514914122, 0.2696716379759792),
     'gravity': 17.727403725674876,
     'steps': 120,
     'snap': 108,
     'kinematic': ('box', 1.334526332758128, 0.31711969096581594, -6.9919396623854),
     'bodies': [{'kind': 'polygon',
                 'geometry': ([0.3333333333333333, 0.36028206736166746, 0.5087173296804475], 1.0,
                              0.1, 0.05),
                 'mass': 0.47891520465273196,
                 'restitution': 0.0,
                 'friction': 0.0,
                 'angle': 0.6081037198209281,
                 'spin': 0.4928195177714837,
                 'speed': 3.194679702111744e-221,
                 'heading': 0.0,
                 'fixed': True,
                 'at': (-2.1660197824951064, 2.757492049942927)},
                {'kind': 'box',
                 'geometry': (0.1, 0.1, 0.0),
                 'mass': 0.3333333333333333,
                 'restitution': 0.36028206736166746,
                 'friction': 0.5087173296804475,
                 'angle': 0.8807420724621455,
                 'spin': 0.9678479735473451,
                 'speed': 0.0,
                 'heading': 0.5,
                 'fixed': True,
                 'at': (-2.1660197824951064, -3.914349690096226)},
                {'kind': 'box',
                 'geometry': (0.1, 0.8050877794624978, 0.0),
                 'mass': 0.1,
                 'restitution': 1.6564311593274674e-224,
                 'friction': 0.0002,
                 'angle': 0.0,
                 'spin': 0.0,
                 'speed': 0.0,
                 'heading': 0.25,
                 'fixed': True,
                 'at': (-2.1660197824951064, -2.246389255086438)},
                {'kind': 'box',
                 'geometry': (0.1, 0.1, 0.0),
                 'mass': 0.1,
                 'restitution': 0.0,
                 'friction': 0.0,
                 'angle': 0.0,
                 'spin': 0.3333333333333333,
                 'speed': 0.36028206736166746,
                 'heading': 0.5087173296804475,
                 'fixed': True,
                 'at': (-2.1660197824951064, -5.582310125106014)},
                {'kind': 'box',
                 'geometry': (0.1, 0.41791522574668793, 0.05),
                 'mass': 8.23317366468763,
                 'restitution': 0.738501884711685,
                 'friction': 3.416861303036848e-238,
                 'angle': -0.025,
                 'spin': -28.87244638573854,
                 'speed': 2.0149097286551236,
                 'heading': 1.3144872521634996,
                 'fixed': False,
                 'at': (-2.1660197824951064, 4.425452484952716)},
                {'kind': 'disc',
                 'geometry': (0.3333333333333333,),
                 'mass': 3.4,
                 'restitution': 0.7884711710048256,
                 'friction': 1.468885269363741e-90,
                 'angle': -0.8657499032917495,
                 'spin': 17.2509279991299,
                 'speed': 35.81088308702159,
                 'heading': 2.362086590795954,
                 'fixed': True,
                 'at': (-0.4980593474853179, -5.582310125106014)},
                {'kind': 'box',
                 'geometry': (1.15, 1.1381107016705638, 0.0),
                 'mass': 0.99999,
                 'restitution': 0.4430449132413278,
                 'friction': 0.7494656097446272,
                 'angle': 1.2816110176263598,
                 'spin': -4.181645357436253,
                 'speed': 2.9668064458696838e-254,
                 'heading': 5.960464477539063e-08,
                 'fixed': False,
                 'at': (-0.4980593474853179, -3.914349690096226)},
                {'kind': 'polygon',
                 'geometry': ([0.29549409779508035, 0.2630379474013446, 0.5908352469812327,
                               0.7788377768497645],
                              0.2, 0.15349372788676732, 0.05),
                 'mass': 4.928466068372396,
                 'restitution': 0.42720820327051656,
                 'friction': 1.6282431981710861e-100,
                 'angle': 0.3490459514914122,
                 'spin': -2.2250738585072014e-308,
                 'speed': 80.29313848701894,
                 'heading': 0.1062294254004792,
                 'fixed': False,
                 'at': (-0.4980593474853179, 2.757492049942927)},
                {'kind': 'polygon',
                 'geometry': ([0.7292163296658272, 0.7215608827042513, 0.3900364451884284,
                               0.9927556927135486, 0.36036011834841, 0.6937714639789518,
                               0.6504044265683916, 0.33830281340005575],
                              1.0, 0.4985790182256351, 0.05),
                 'mass': 9.0,
                 'restitution': 0.8897023577449967,
                 'friction': 0.24116563040858235,
                 'angle': 0.0,
                 'spin': 0.0,
                 'speed': 3.6833837495006136,
                 'heading': 2.297199340745454,
                 'fixed': True,
                 'at': (-0.4980593474853179, 4.425452484952716)}],
     'solver': 'exact'}
)  # fmt: skip


def test_a_light_box_crushed_into_the_floor_by_a_heavy_spinning_box_stays_in_the_room() -> None:
    # (run: every centroid in the room after every step, and the replay bit for bit.)
    _, seen = run(LIGHT_BOX_CRUSHED_INTO_THE_FLOOR)
    # The pile's give between the bodies is told: "raise world.contact_iterations".
    assert seen["stability"] >= 1, seen
    # The light box itself (5.8 cm in before), over every step.
    light = LIGHT_BOX_CRUSHED_INTO_THE_FLOOR["bodies"][3]
    assert light["mass"] == 0.1 and light["geometry"] == (0.1, 0.1, 0.0)
    assert 0.0 < seen["deepest 3"] <= 0.005, seen  # (3.6 mm: how deep it had crept when taken)


@pytest.mark.parametrize("iterations", [8, 16])
def test_a_light_box_crushed_into_the_floor_stays_out_with_the_iterations_the_warning_asks(
    iterations: int,
) -> None:
    stays_in_the_room(LIGHT_BOX_CRUSHED_INTO_THE_FLOOR, iterations, 0.01)  # (5.8 cm at 4)


def test_a_thin_triangle_flipped_off_the_floor_by_a_landing_box_stays_out_of_it() -> None:
    # Found exploring the mixed scenes (500 examples, fast path, 2026-12-04; numpy alike),
    # reduced to two bodies: a thin triangle (1.24 by 0.12 m) lying on the floor is flipped by
    # a 5.4 kg box landing on its end, to 59 rad/s, and in the next step it turned 1 rad and
    # ended 0.257 m in the floor, on the soft step, without a StabilityWarning: its rows are
    # the features nearest at the step's start, and the continuous stage's sweep of a body
    # touching the floor as the step begins, to a slop nearer than it started, had its target
    # held at 0, where a half plane's distance (its corners' least, signed) was already. The
    # other end, swinging down, is now stopped a slop below where the body began.
    run(
        {
            "half": (5.02144705837112, 7.457438845181193),
            "walls": "room",
            "wall_material": (0.0, 1.192092896e-07),
            "gravity": 12.260816913464058,
            "steps": 180,
            "snap": 0,
            "kinematic": None,
            "solver": "auto",
            "bodies": [
                {
                    **_fixed_box((2.735275530045927, 5.940536534811886)),
                    "geometry": (0.6403220498879141, 0.9580487718676275, 0.0),
                    "mass": 5.390171622091221,
                    "friction": 0.9341714104576149,
                    "angle": 3.05078125,
                    "spin": 59.0,
                    "speed": 53.47720153205465,
                    "fixed": False,
                },
                {
                    **_fixed_box((-2.905977261530107, -6.752282246234189)),
                    "kind": "polygon",
                    "geometry": ([0.9375, 0.25, 0.5], 0.2, 0.640625, 0.0),
                    "speed": 67.0,
                    "heading": -1.48046875,
                    "fixed": False,
                },
            ],
        }
    )


def test_a_spinning_polygon_left_in_a_wall_by_its_impact_turns_no_deeper_into_it() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1, numpy, 2026-12-05; the fast path alike),
    # reduced to two bodies: an 8-gon (0.7 m across its largest corner) at 55 m/s, knocked to
    # 10 m/s upward by a spinning ball, meets the room's right wall on a corner and leaves the
    # step 0.017 m in it, its centre still going in at 25 m/s while it turns at -78 rad/s.
    # In the next step it turned 1.5 rad and ended 0.66 m in the wall: it began that step in
    # by more than the 2% of its size that counts as apart, so the exact step's search for a
    # late impact passed it by. A body that begins within the soft step's give of the wall
    # (5%) and ends deeper by that again is now taken again, to the moment it is a hair deeper
    # than it began.
    bodies = [
        {**_fixed_box((1.0455375037502392, 1.759855216550621)), "kind": "disc",
         "geometry": (0.5,), "mass": 8.925550611073454, "restitution": 0.6148097836361518,
         "friction": 0.7658662749551196, "spin": -67.13462052483513,
         "speed": 12.445586701780668, "fixed": False},
        {**_fixed_box((1.0455375037502392, 3.209855216550621)), "kind": "polygon",
         "geometry": ([1.0, 0.9794746452477976, 0.7658662749551196, 0.25, 0.25,
                       0.3333333333333333, 0.6364299139425895, 0.6540346943623587], 0.2,
                      0.6999999999999998, 0.0),
         "mass": 7.0651614115041, "restitution": 0.2449607474165854, "friction": 0.5,
         "angle": 1.0160448887490139, "spin": 44.916444855387255,
         "speed": 55.05969502263982, "fixed": False},
    ]  # fmt: skip
    spec = {"half": (5.479462496249759, 6.215144783449378), "walls": "room",
            "wall_material": (0.0, 0.0), "gravity": 0.0, "steps": 60, "snap": 0,
            "kinematic": None, "solver": "exact", "bodies": bodies}  # fmt: skip
    _, seen = run(spec)
    # No deeper than the soft step's give (5% of its bounding radius, 0.7 m): where the impact
    # left it.
    assert seen["deepest"] <= 0.05 * 0.7, seen


def test_a_light_capsule_squeezed_into_a_wall_by_a_heavy_box_is_swept_back_out() -> None:
    # Found by the long scene fuzz (FUZZ_LONG=1, fast path, 2026-12-05; numpy alike), reduced
    # to four bodies and the kinematic bar: on the soft step (World()'s choice) a 0.11 kg
    # capsule that never turns rattles at 50 m/s between the room's right wall and a 3 kg box
    # (mass ratio 27, restitution 0.9 and 1). Struck into the wall by the box, it ended a step
    # 0.09 m in and the next 0.17 m, with no StabilityWarning: the solve's rows give way under
    # the heavy box, and it moved too little for its size to count as fast. A body whose
    # contacts with what the solve does not move end deeper than a quarter of its least
    # extent is now swept by the continuous stage as a fast one is, to a slop deeper than it
    # began.
    bodies = [
        {**_fixed_box((5.160131587098018, 0.2407637906746638)), "kind": "capsule",
         "geometry": (0.373046875, 0.07421875), "mass": 7.5, "restitution": 0.75,
         "friction": 0.25, "spin": -50.0, "fixed": False},
        {**_fixed_box((5.160131587098018, 2.9218698853458998)), "kind": "disc",
         "geometry": (0.291015625,), "restitution": 0.75, "friction": 1.0, "spin": -2.0,
         "speed": 51.0, "heading": -1.312486420171676, "fixed": False},
        {**_fixed_box((-5.564292791586928, -1.0997892566609546)),
         "geometry": (0.21875, 0.828125, 0.05), "mass": 3.0,
         "restitution": 0.5167373309157347, "friction": 0.25, "spin": 1.0, "speed": 80.125,
         "heading": 2.625, "fixed": False},
        {**_fixed_box((5.160131587098018, 1.5813168380102818)), "kind": "capsule",
         "geometry": (0.35126010377027905, 0.29401641989753), "mass": 0.109375,
         "restitution": 0.90625, "friction": 0.75},
    ]  # fmt: skip
    spec = {"half": (7.5751223625903545, 4.451171875), "walls": "room",
            "wall_material": (1.0, 0.3984375), "gravity": 5.0, "steps": 60, "snap": 0,
            "kinematic": ("box", 3.450721365045437, 0.33885269979442506, 0.0),
            "solver": "auto", "bodies": bodies}  # fmt: skip
    _, seen = run(spec)
    # No deeper than a quarter of the capsule's least extent (its radius, 0.294 m).
    assert seen["deepest"] <= 0.25 * 0.29401641989753, seen


def test_a_light_polygon_battered_in_a_corner_stays_in_the_room() -> None:
    # Found exploring the mixed scenes (2,000 examples, fast path, 2026-12-05; numpy alike,
    # and so before that day's changes), reduced to six bodies: on the soft step a 0.23 kg
    # polygon 0.2 m across that never turns, wedged in the bottom right corner of a room of
    # polygon walls, is struck again and again by bodies 8 to 39 times its mass at 10 to 50
    # m/s. It was pushed 4 to 6 cm deeper at each of steps 13, 19 and 20, and at step 20 was
    # 0.13 m in, its centroid past the wall, with no StabilityWarning. The continuous stage
    # swept it (it ended deeper than a quarter of its least extent), but the sweep's distance
    # of two cores is 0 wherever they overlap, so for a body that began the step in a wall
    # of polygons it could say nothing of going deeper. It now takes B's separation along
    # the wall's edge normals, signed, as a half plane's: the body stops a slop deeper than
    # it began (engine.dynamics.game_continuous), and is never 1.5 cm in.
    bodies = [
        {
            **_fixed_box((2.297239359056392, -1.7906058542071066)),
            "kind": "polygon",
            "geometry": (
                [
                    0.5998033001779732,
                    0.3378813757823358,
                    0.5354898340234631,
                    0.5361719079302348,
                    0.6029800577996749,
                    0.867144558517656,
                    0.25,
                    0.25,
                ],
                1.0,
                0.10757699995458975,
                0.0,
            ),
            "mass": 0.23223341410485063,
            "restitution": 0.9,
            "friction": 0.32118990830165434,
        },
        {
            **_fixed_box((2.297239359056392, 2.6281824373786797)),
            "kind": "capsule",
            "geometry": (0.45848803494692636, 0.1572948602952849),
            "mass": 6.41739782207506,
            "restitution": 0.9404454252541672,
            "friction": 0.5688010265613342,
            "speed": 88.10197706899068,
            "heading": -2.777400250817704,
            "fixed": False,
        },
        {
            **_fixed_box((0.8243099285277973, 2.6281824373786797)),
            "kind": "polygon",
            "geometry": (
                [0.6982664605166109, 0.9851696872158127, 0.5198273774942943, 0.25, 0.25],
                1.0,
                0.6295310799083368,
                0.0,
            ),
            "mass": 9.0,
            "restitution": 0.31315597135523393,
            "friction": 0.75,
            "speed": 63.620525274261084,
        },
        {
            **_fixed_box((-0.6486195020007988, 2.6281824373786797)),
            "kind": "disc",
            "geometry": (0.5999999999999999,),
            "mass": 8.951958333268555,
            "friction": 1.0,
            "spin": 21.844319435037846,
            "speed": 91.43665495518944,
            "heading": -1.6818516335198703,
            "fixed": False,
        },
        {
            **_fixed_box((-2.1215489325293944, -0.317676423678511)),
            "geometry": (0.3866660779219335, 0.25349337223401236, 0.0),
            "mass": 6.701017769239442,
            "friction": 0.5054686113487549,
            "speed": 41.76594518702675,
        },
        {
            **_fixed_box((-0.6486195020007988, -1.7906058542071066)),
            "geometry": (0.32671495135834394, 1.114880978462464, 0.0),
            "mass": 1.9,
            "restitution": 0.8009335008927063,
            "friction": 0.42082530116103,
            "angle": 0.13537689409373055,
            "spin": 80.92511071177685,
            "speed": 78.1554625842034,
            "heading": 0.2,
            "fixed": False,
        },
    ]
    _, seen = run(
        {
            "half": (4.330943078322288, 4.0),
            "walls": "polygons",
            "wall_material": (0.0, 0.0),
            "gravity": 0.0,
            "steps": 60,
            "snap": 0,
            "kinematic": None,
            "solver": "auto",
            "bodies": bodies,
        }
    )
    assert seen["deepest"] <= 0.02, seen


def test_corners_too_far_apart_for_an_area_are_refused_naming_the_vertices() -> None:
    # Found exploring (2026-12-04, 2,000 examples): a convex quadrilateral with corners at
    # 1e308 m passes the convexity checks, but its area overflows; the error blamed the
    # radius (0.0), which the caller did not give.
    with pytest.raises(ValueError, match="vertices") as caught:
        Polygon([(0.0, 0.0), (1e308, 1e308), (1.0, 0.0), (1e308, 2.0)])
    assert "radius" not in str(caught.value).split(",")[0]


#: Find 12 (the fast path's exploring fuzz, 2026-12-05; the numpy path alike): a 1.6 kg rounded
#: box at rest on the floor 3.7 cm from the left wall, a 1 kg capsule lying on it, struck at the
#: start of step 69 by a 6 kg disc (radius 0.05 m) at 19.7 m/s.
STRUCK_OUT_OF_A_WALLS_REACH: dict[str, Any] = {
    "half": (6.5320131361691764, 5.8136756803616265),
    "walls": "planes",
    "wall_material": (0.25652782726567086, 0.16274154205684302),
    "gravity": 19.999999999999996,
    "steps": 120,
    "snap": 0,
    "kinematic": None,
    "bodies": [
        {
            "kind": "capsule",
            "geometry": (0.7578125, 0.125),
            "mass": 9.5,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": -2.73046875,
            "spin": -38.25,
            "speed": 34.0,
            "heading": -1.79296875,
            "fixed": False,
            "at": (-5.57468625577081, -1.0270412783697935),
        },
        {
            "kind": "capsule",
            "geometry": (0.625, 0.03),
            "mass": 1.0,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-5.57468625577081, -2.9416950391665266),
        },
        {
            "kind": "disc",
            "geometry": (0.05,),
            "mass": 6.0,
            "restitution": 0.7872663860929177,
            "friction": 1.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 56.0,
            "heading": 0.37890625,
            "fixed": False,
            "at": (2.0839287874161236, 2.8022662432236736),
        },
        {
            "kind": "box",
            "geometry": (0.625, 1.1875, 0.05),
            "mass": 1.625,
            "restitution": 0.0,
            "friction": 0.625,
            "angle": 1.625,
            "spin": 0.0,
            "speed": 24.0,
            "heading": 1.4375,
            "fixed": False,
            "at": (-5.57468625577081, -4.85634879996326),
        },
        {
            "kind": "capsule",
            "geometry": (0.5, 0.125),
            "mass": 2.0,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-3.6600324949740766, 0.88761248242694),
        },
        {
            "kind": "capsule",
            "geometry": (0.7218318617068693, 0.21049501869149737),
            "mass": 1.0,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-3.6600324949740766, 2.8022662432236736),
        },
    ],
    "solver": "auto",
}


def test_a_box_struck_from_rest_toward_a_wall_out_of_its_reach_stays_out_of_it() -> None:
    # The step, traced in the solver: the box's rows were with the capsule on it, the disc
    # (0.0044 m open) and the floor; none with the wall, 0.037 m away where its reach at rest
    # is g dt^2 and the speculative distance. The disc's fresh contact gave it -8.95 m/s in
    # the first part, and it moved 0.146 m, 0.114 m into the wall: no row held it, and the
    # continuous stage swept it not (it moved less than half its least extent and ended less
    # than a quarter of it deep by its rows). A body's reach toward static shapes is grown by
    # twice its partners' now (engine.pipeline.game_broadphase.struck): the box has a row with
    # the wall before it is struck, and ends 3.3 mm into it (the bound is 2 cm).
    run(STRUCK_OUT_OF_A_WALLS_REACH)


#: Find 13 (the same run): the exact models (solver "exact"), a 6.8 kg disc of radius 0.05 m
#: thrown at 56 m/s (restitution 0.79) among capsules and a box in a room 6 m wide with gravity
#: 20 m/s^2; the disc falls at 17.6 m/s onto a 1.3 kg capsule 1.4 m long and 6 cm thick lying on
#: the floor, capsules of 6.8 and 7.2 kg falling after it.
DISC_PAST_THE_FLOOR: dict[str, Any] = {
    "half": (3.0, 5.8136756803616265),
    "walls": "planes",
    "wall_material": (0.25652782726567086, 0.16274154205684302),
    "gravity": 19.999999999999996,
    "steps": 120,
    "snap": 0,
    "kinematic": None,
    "bodies": [
        {
            "kind": "capsule",
            "geometry": (0.7541698964523624, 0.16178294819082265),
            "mass": 9.515131023684475,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": -2.731428388090301,
            "spin": -38.369050848399624,
            "speed": 38.47939828618222,
            "heading": -1.7922054975963904,
            "fixed": False,
            "at": (-2.0426731196016332, -1.0270412783697935),
        },
        {
            "kind": "capsule",
            "geometry": (0.7037818905480456, 0.03),
            "mass": 1.321429911324084,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-2.0426731196016332, -2.9416950391665266),
        },
        {
            "kind": "disc",
            "geometry": (0.05,),
            "mass": 6.843332182927982,
            "restitution": 0.7872663860929177,
            "friction": 0.534864332194101,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 55.93530337761655,
            "heading": 0.37884976519242297,
            "fixed": False,
            "at": (-2.0426731196016332, -4.85634879996326),
        },
        {
            "kind": "box",
            "geometry": (0.7180561520650118, 1.1726442338064105, 0.05),
            "mass": 1.619118421565575,
            "restitution": 0.0,
            "friction": 0.7072073977264255,
            "angle": -1.5932162071878306,
            "spin": 0.0,
            "speed": 24.490672532603803,
            "heading": 1.4792816620610374,
            "fixed": False,
            "at": (-2.0426731196016332, 0.88761248242694),
        },
        {
            "kind": "capsule",
            "geometry": (0.7072073977264255, 0.08648322854513843),
            "mass": 6.816015827582242,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-2.0426731196016332, 2.8022662432236736),
        },
        {
            "kind": "capsule",
            "geometry": (0.7218318617068693, 0.21049501869149737),
            "mass": 7.2063518751632225,
            "restitution": 0.0,
            "friction": 0.0,
            "angle": 0.0,
            "spin": 0.0,
            "speed": 0.0,
            "heading": 0.0,
            "fixed": True,
            "at": (-2.0426731196016332, 4.716920004020407),
        },
    ],
    "solver": "exact",
}


def test_a_heavy_small_disc_among_capsules_stays_above_the_floor() -> None:
    # The disc's impact sent the capsule down into the floor, and the pile's rows let it go
    # 1.7 cm in, then 3.1 cm under the capsules landing after (the World warns that the pile
    # is past its iterations): its centre 1 mm past the floor's line. A body that ends a step
    # deep in a wall is taken again to its moment of impact (engine.exact.shape_impacts), and
    # deep was counted in its bounding radius, 0.73 m: DEEP_WALL of it, 3.7 cm, is more than
    # the capsule's thickness. Counted in its least extent (its radius, 3 cm), the capsule is
    # stopped where it touches: 1.5 mm in at most.
    _, seen = run(DISC_PAST_THE_FLOOR)
    assert seen["deepest"] <= 0.002, seen
