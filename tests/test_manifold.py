"""The narrowphase (engine.geometry.manifold): each manifold against exact geometry computed here by
brute force in Python floats (nearest points of segments, point-in-polygon, distances between
polygons as the least vertex-to-edge distance, depths as the least overlap over every edge
normal), never against numbers the module produced.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from engine import Box, Circle, Plane, Segment
from engine.geometry.colliders import Polygon
from engine.geometry.convex import convex_polygon
from engine.geometry.manifold import (
    LINEAR_SLOP,
    Capsules,
    Circles,
    HalfPlanes,
    Manifold,
    Polygons,
    collide,
    collide_capsule_circle,
    collide_capsules,
    collide_circles,
    collide_half_plane_circle,
    collide_half_plane_polygon,
    collide_polygon_capsule,
    collide_polygon_circle,
    collide_polygons,
    collide_static,
    polygon_distance,
    static_shapes,
)
from engine.geometry.manifold_polygon import segment_distance as ericson

P = tuple[float, float]
BIG = 100.0  # a margin that lets every pair of this size have its points


# -- brute-force geometry -----------------------------------------------------------------------
def turn(q: float, v: P) -> P:
    c, s = math.cos(q), math.sin(q)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def place(x: P, q: float, pts: Sequence[P]) -> list[P]:
    """Points of a body's shape in the world: x + R(q) v."""
    return [(x[0] + turn(q, v)[0], x[1] + turn(q, v)[1]) for v in pts]


def sub(a: P, b: P) -> P:
    return (a[0] - b[0], a[1] - b[1])


def dot(a: P, b: P) -> float:
    return a[0] * b[0] + a[1] * b[1]


def cross3(o: P, a: P, b: P) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def point_segment(p: P, a: P, b: P) -> float:
    d = sub(b, a)
    dd = dot(d, d)  # 0 for an edge shorter than rounding (a tiny edge, turned)
    u = min(1.0, max(0.0, dot(sub(p, a), d) / dd)) if dd > 0.0 else 0.0
    return math.hypot(p[0] - a[0] - u * d[0], p[1] - a[1] - u * d[1])


def segments_cross(a: P, b: P, c: P, d: P) -> bool:
    d1, d2, d3, d4 = cross3(c, d, a), cross3(c, d, b), cross3(a, b, c), cross3(a, b, d)
    return d1 * d2 < 0 and d3 * d4 < 0


def segment_distance(a: P, b: P, c: P, d: P) -> float:
    if segments_cross(a, b, c, d):
        return 0.0
    return min(
        point_segment(a, c, d),
        point_segment(b, c, d),
        point_segment(c, a, b),
        point_segment(d, a, b),
    )


def edges(poly: Sequence[P]) -> list[tuple[P, P]]:
    return [(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly))]


def inside(p: P, poly: Sequence[P]) -> bool:
    return all(cross3(a, b, p) >= 0.0 for a, b in edges(poly))


def signed_distance(p: P, poly: Sequence[P]) -> float:
    d = min(point_segment(p, a, b) for a, b in edges(poly))
    return -d if inside(p, poly) else d


def polygon_gap(A: Sequence[P], B: Sequence[P]) -> float:
    """Distance between convex polygons, 0 when they meet: apart, the nearest points include a
    vertex of one of them, so it is the least vertex-to-edge distance."""
    if any(inside(v, B) for v in A) or any(inside(w, A) for w in B):
        return 0.0
    if any(segments_cross(a, b, c, d) for a, b in edges(A) for c, d in edges(B)):
        return 0.0
    return min(
        min(point_segment(v, c, d) for v in A for c, d in edges(B)),
        min(point_segment(w, a, b) for w in B for a, b in edges(A)),
    )


def polygon_depth(A: Sequence[P], B: Sequence[P]) -> float:
    """Penetration depth of overlapping convex polygons: the least overlap of their shadows
    over every edge normal (the separating axis theorem: one of them is the least)."""
    best = math.inf
    for poly in (A, B):
        for a, b in edges(poly):
            e = sub(b, a)
            if e == (0.0, 0.0):  # an edge too short to survive turning: no axis
                continue
            n = (e[1] / math.hypot(*e), -e[0] / math.hypot(*e))
            pa = [dot(v, n) for v in A]
            pb = [dot(v, n) for v in B]
            best = min(best, min(max(pa) - min(pb), max(pb) - min(pa)))
    return best


def support(poly: Sequence[P], n: P) -> float:
    return max(dot(v, n) for v in poly)


def aim(d: float) -> float:
    """The error to allow in a direction between points d apart, and in what it projects:
    their coordinates' rounding (~1e-16 of a few units) over d."""
    return 1e-12 * max(1.0, 1.0 / abs(d))


def unit(v: P) -> P:
    length = math.hypot(*v)
    return (v[0] / length, v[1] / length)


# -- strategies ---------------------------------------------------------------------------------
coords = st.floats(-3.0, 3.0)
angles = st.floats(-math.pi, math.pi)
points = st.tuples(coords, coords)


@st.composite
def convex_polygons(draw: Any, low: int = 3, high: int = 8) -> tuple[P, ...]:
    """Points on an ellipse (axes 0.05 to 2, as thin as 1:1000: slivers), in angle order: a
    convex polygon, or a refusal that the test skips."""
    k = draw(st.integers(low, high))
    ts = sorted(draw(st.lists(st.floats(0.0, 6.283), min_size=k, max_size=k, unique=True)))
    a = draw(st.floats(0.05, 2.0))
    b = a * draw(st.sampled_from([1.0, 0.5, 0.02, 0.001]))
    phi = draw(angles)
    c = draw(st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)))
    pts = [
        (
            c[0] + turn(phi, (a * math.cos(t), b * math.sin(t)))[0],
            c[1] + turn(phi, (a * math.cos(t), b * math.sin(t)))[1],
        )
        for t in ts
    ]
    try:
        return convex_polygon(pts, "polygon")
    except ValueError:
        assume(False)
        raise


def same_points(got: Sequence[P], want: Sequence[P], tol: float) -> bool:
    """The same points in any order, each within tol."""
    return len(got) == len(want) and all(
        math.hypot(*sub(g, w)) <= tol for g, w in zip(sorted(got), sorted(want), strict=True)
    )


def one(m: Manifold, k: int = 0) -> dict[str, Any]:
    """Row k of a manifold as plain numbers."""
    c = int(m.count[k])
    return {
        "count": c,
        "normal": tuple(m.normal[k].tolist()),
        "point": [tuple(p) for p in m.point[k, :c].tolist()],
        "sep": m.separation[k, :c].tolist(),
        "feature": m.feature[k, :c].tolist(),
    }


def check_anchors(m: Manifold, xa: Any, xb: Any) -> None:
    for k in range(len(m)):
        c = int(m.count[k])
        assert np.array_equal(m.anchor_a[k, :c], m.point[k, :c] - np.asarray(xa)[k]) or np.allclose(
            m.anchor_a[k, :c], m.point[k, :c] - np.asarray(xa)[k], rtol=0, atol=1e-12
        )
        assert np.allclose(
            m.anchor_b[k, :c], m.point[k, :c] - np.asarray(xb)[k], rtol=0, atol=1e-12
        )
        assert np.all(np.isinf(m.separation[k, c:])) and np.all(m.feature[k, c:] == -1)
        assert abs(np.hypot(*m.normal[k]) - 1.0) < 1e-12


# -- circles and capsules -----------------------------------------------------------------------
@given(
    xa=points,
    qa=angles,
    ca=points,
    ra=st.floats(0.0, 1.0),
    xb=points,
    qb=angles,
    cb=points,
    rb=st.floats(0.0, 1.0),
    margin=st.floats(0.0, 4.0),
)
def test_circles_meet_at_their_distance_less_the_radii(
    xa: P, qa: float, ca: P, ra: float, xb: P, qb: float, cb: P, rb: float, margin: float
) -> None:
    (CA,), (CB,) = place(xa, qa, [ca]), place(xb, qb, [cb])
    d = math.hypot(*sub(CB, CA))
    assume(d > 1e-6)
    gap = d - ra - rb
    assume(abs(gap - margin) > 1e-9)
    A, B = Circles([ca], [ra]), Circles([cb], [rb])
    m = collide_circles(A, [xa], [qa], B, [xb], [qb], margin)
    if gap > margin:
        assert m.count[0] == 0
        return
    got = one(m)
    n = unit(sub(CB, CA))
    assert got["count"] == 1
    assert abs(got["sep"][0] - gap) < 1e-12
    assert math.hypot(*sub(got["normal"], n)) < aim(d)
    # Midway between A's surface point CA + ra n and B's CB - rb n.
    mid = ((CA[0] + ra * n[0] + CB[0] - rb * n[0]) / 2, (CA[1] + ra * n[1] + CB[1] - rb * n[1]) / 2)
    assert math.hypot(*sub(got["point"][0], mid)) < aim(d) * (1.0 + ra + rb)  # n's error, times r
    check_anchors(m, [xa], [xb])
    swapped = one(collide(B, [xb], [qb], A, [xa], [qa], margin))
    assert abs(swapped["sep"][0] - gap) < 1e-12
    assert math.hypot(swapped["normal"][0] + n[0], swapped["normal"][1] + n[1]) < aim(d)


@given(
    xa=points,
    qa=angles,
    a=points,
    b=points,
    ra=st.floats(0.0, 1.0),
    xb=points,
    qb=angles,
    c=points,
    rb=st.floats(0.0, 1.0),
)
def test_a_capsule_and_a_circle_meet_at_the_nearest_point_of_the_segment(
    xa: P, qa: float, a: P, b: P, ra: float, xb: P, qb: float, c: P, rb: float
) -> None:
    assume(math.hypot(*sub(a, b)) > 1e-3)
    (A1, A2), (C,) = place(xa, qa, [a, b]), place(xb, qb, [c])
    d = point_segment(C, A1, A2)
    assume(d > 1e-6)
    cap, circ = Capsules([a], [b], [ra]), Circles([c], [rb])
    got = one(collide_capsule_circle(cap, [xa], [qa], circ, [xb], [qb], BIG))
    assert got["count"] == 1
    assert abs(got["sep"][0] - (d - ra - rb)) < 1e-12
    # The normal points from the segment's nearest point to the centre: the centre lies d
    # along it from the segment's farthest-out point in that direction.
    n = got["normal"]
    assert abs(dot(C, n) - support([A1, A2], n) - d) < aim(d)
    swapped = one(collide(circ, [xb], [qb], cap, [xa], [qa], BIG))
    assert abs(swapped["sep"][0] - (d - ra - rb)) < 1e-12
    assert math.hypot(swapped["normal"][0] + n[0], swapped["normal"][1] + n[1]) < aim(d)


@given(
    xa=points,
    qa=angles,
    a1=points,
    a2=points,
    ra=st.floats(0.0, 0.5),
    xb=points,
    qb=angles,
    b1=points,
    b2=points,
    rb=st.floats(0.0, 0.5),
)
def test_capsules_meet_at_the_distance_of_their_segments_less_the_radii(
    xa: P, qa: float, a1: P, a2: P, ra: float, xb: P, qb: float, b1: P, b2: P, rb: float
) -> None:
    """One point: exactly the distance, along the nearest points. Two (one capsule lies along
    the other): the nearer at most LINEAR_SLOP farther than the exact distance (Box2D keeps
    the pair of points while one is that close), and the normal is one capsule's side."""
    assume(math.hypot(*sub(a1, a2)) > 1e-3 and math.hypot(*sub(b1, b2)) > 1e-3)
    A, B = place(xa, qa, [a1, a2]), place(xb, qb, [b1, b2])
    d = segment_distance(*A, *B)
    R = ra + rb
    CA, CB = Capsules([a1], [a2], [ra]), Capsules([b1], [b2], [rb])
    m = collide_capsules(CA, [xa], [qa], CB, [xb], [qb], BIG)
    got = one(m)
    check_anchors(m, [xa], [xb])
    assert got["count"] in (1, 2)
    n = got["normal"]
    least = min(got["sep"])
    # Nearest points of segments at a small angle t are ill-conditioned: the distance found
    # carries rounding of order 1e-16 / sin t.
    sides = [unit(sub(A[1], A[0])), unit(sub(B[1], B[0]))]
    sin_t = sides[0][0] * sides[1][1] - sides[0][1] * sides[1][0]
    tol = aim(sin_t) if sin_t != 0.0 else 1e-12  # parallel: exact again (one branch)
    if d == 0.0:  # the cores cross: as deep as the radii at least
        assert least <= -R + tol
        return
    assume(d > 1e-9)
    if got["count"] == 1:
        assert abs(least - (d - R)) < tol
        assert abs(min(dot(w, n) for w in B) - support(A, n) - d) < aim(d)
    else:
        assert d - R - tol <= least <= d - R + LINEAR_SLOP + tol
        assert min(abs(dot(n, s)) for s in sides) < 1e-12  # perpendicular to a side
    swapped = one(collide(CB, [xb], [qb], CA, [xa], [qa], BIG))
    if got["count"] == 1 and swapped["count"] == 1:
        assert abs(swapped["sep"][0] - (d - R)) < tol
        flip = math.hypot(swapped["normal"][0] + n[0], swapped["normal"][1] + n[1])
        assert flip < aim(d)
    else:
        assert abs(min(swapped["sep"]) - least) <= LINEAR_SLOP + 1e-12


def test_a_capsule_lying_on_a_capsule_has_two_points_at_the_overlap() -> None:
    """Parallel, 0.5 apart, B's segment from x = 1 to 4 over A's from 0 to 3: the points are
    B's clipped segment's ends over A (x = 1 and 3), separation 0.5 - 0.1 - 0.15 = 0.25."""
    A, B = Capsules([(0.0, 0.0)], [(3.0, 0.0)], [0.1]), Capsules([(1.0, 0.0)], [(4.0, 0.0)], [0.15])
    got = one(collide_capsules(A, [(0.0, 0.0)], [0.0], B, [(0.0, 0.5)], [0.0], 0.3))
    assert got["count"] == 2 and got["normal"] == (0.0, 1.0)
    assert got["sep"] == [0.25, 0.25]
    # Midway between the surfaces y = 0.1 and y = 0.35.
    assert same_points(got["point"], [(1.0, 0.225), (3.0, 0.225)], 1e-15)


# -- polygons -----------------------------------------------------------------------------------
@given(
    poly=convex_polygons(),
    r=st.sampled_from([0.0, 0.2]),
    xa=points,
    qa=angles,
    c=points,
    rb=st.floats(0.0, 1.0),
    xb=points,
    qb=angles,
)
def test_a_polygon_and_a_circle_meet_at_the_signed_distance(
    poly: tuple[P, ...], r: float, xa: P, qa: float, c: P, rb: float, xb: P, qb: float
) -> None:
    W = place(xa, qa, poly)
    (C,) = place(xb, qb, [c])
    d = signed_distance(C, W)
    assume(abs(d) > 1e-9)
    shape, circ = Polygons.of([poly], r), Circles([c], [rb])
    m = collide_polygon_circle(shape, [xa], [qa], circ, [xb], [qb], BIG)
    got = one(m)
    check_anchors(m, [xa], [xb])
    assert got["count"] == 1
    assert abs(got["sep"][0] - (d - r - rb)) < 1e-12
    # Outside, the normal runs from the nearest point to the centre; inside, it is the nearest
    # face's: either way the centre lies d beyond the polygon's support along it.
    assert abs(dot(C, got["normal"]) - support(W, got["normal"]) - d) < aim(d)
    swapped = one(collide(circ, [xb], [qb], shape, [xa], [qa], BIG))
    assert abs(swapped["sep"][0] - (d - r - rb)) < 1e-12


BOX = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
GROUND = [(-5.0, -0.5), (5.0, -0.5), (5.0, 0.5), (-5.0, 0.5)]


@pytest.mark.parametrize("d", [0.0, 0.1, 0.003])
@pytest.mark.parametrize("x", [1.0, -4.2])
def test_a_box_resting_flat_on_a_box_has_two_points_at_its_corners(d: float, x: float) -> None:
    """Lowered by d into the ground's top (y = 0.5): separation -d at each bottom corner,
    x -+ 0.5, midway between the surfaces (y = 0.5 - d / 2); the normal straight up."""
    m = collide_polygons(
        Polygons.of([GROUND]), [(0.0, 0.0)], [0.0], Polygons.of([BOX]), [(x, 1.0 - d)], [0.0]
    )
    got = one(m)
    assert got["count"] == 2 and got["normal"] == (0.0, 1.0)
    assert got["sep"] == pytest.approx([-d, -d], abs=1e-15)
    assert same_points(got["point"], [(x - 0.5, 0.5 - d / 2), (x + 0.5, 0.5 - d / 2)], 1e-15)
    # Seen from the box (A), the same points with the normal down.
    back = one(
        collide_polygons(
            Polygons.of([BOX]), [(x, 1.0 - d)], [0.0], Polygons.of([GROUND]), [(0.0, 0.0)], [0.0]
        )
    )
    assert back["normal"] == (0.0, -1.0) and back["sep"] == pytest.approx([-d, -d], abs=1e-15)
    assert same_points(back["point"], got["point"], 1e-15)


@pytest.mark.parametrize("gap", [0.0, 0.01, -0.05])
def test_a_box_on_its_corner_has_one_point_at_the_corner(gap: float) -> None:
    """Turned 45 degrees, its lowest corner h = sqrt(2) / 2 below its centre, gap above the
    ground: one point, under the corner, separation gap (the other corners are far)."""
    h = math.sqrt(2.0) / 2
    got = one(
        collide_polygons(
            Polygons.of([GROUND]),
            [(0.0, 0.0)],
            [0.0],
            Polygons.of([BOX]),
            [(1.3, 0.5 + h + gap)],
            [math.pi / 4],
        )
    )
    assert got["count"] == 1
    assert got["sep"][0] == pytest.approx(gap, abs=1e-12)
    assert got["normal"] == pytest.approx((0.0, 1.0), abs=1e-15)
    assert got["point"][0] == pytest.approx((1.3, 0.5 + gap / 2), abs=1e-12)


@given(g=st.floats(0.001, 0.5), alpha=st.floats(-0.7, 0.7), r=st.sampled_from([0.0, 0.1]))
def test_diamonds_tip_to_tip_meet_at_the_exact_distance(g: float, alpha: float, r: float) -> None:
    """B's left tip g from A's right tip along (cos a, sin a), |a| < 45 degrees: the nearest
    points are the two tips (each inside the other's corner cone), so the manifold is one
    point, separation g - 2r, along that direction."""
    diamond = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]
    u = (math.cos(alpha), math.sin(alpha))
    xb = (2.0 + g * u[0], g * u[1])
    got = one(
        collide_polygons(
            Polygons.of([diamond], r),
            [(0.0, 0.0)],
            [0.0],
            Polygons.of([diamond], r),
            [xb],
            [0.0],
            1.0,
        )
    )
    assert got["count"] == 1
    assert abs(got["sep"][0] - (g - 2 * r)) < 1e-12
    assert math.hypot(*sub(got["normal"], u)) < 1e-12
    assert math.hypot(*sub(got["point"][0], (1.0 + g / 2 * u[0], g / 2 * u[1]))) < 1e-12


def test_rounded_boxes_count_their_radii() -> None:
    """Boxes rounded by 0.1 and 0.05 whose cores are 0.15 apart touch: separation 0; and a
    rounded box's corner is round: against a box turned 45 degrees, the gap is measured from
    the corner's arc."""
    got = one(
        collide_polygons(
            Polygons.of([GROUND], 0.1),
            [(0.0, 0.0)],
            [0.0],
            Polygons.of([BOX], 0.05),
            [(0.0, 1.15)],
            [0.0],
        )
    )
    assert got["count"] == 2 and got["sep"] == pytest.approx([0.0, 0.0], abs=1e-15)


@given(
    A=convex_polygons(),
    B=convex_polygons(),
    ra=st.sampled_from([0.0, 0.1]),
    rb=st.sampled_from([0.0, 0.05]),
    xa=points,
    qa=angles,
    xb=points,
    qb=angles,
    margin=st.floats(0.0, 2.0),
)
def test_random_polygons_overlap_below_zero_and_apart_at_their_exact_distance(
    A: tuple[P, ...],
    B: tuple[P, ...],
    ra: float,
    rb: float,
    xa: P,
    qa: float,
    xb: P,
    qb: float,
    margin: float,
) -> None:
    WA, WB = place(xa, qa, A), place(xb, qb, B)
    gap = polygon_gap(WA, WB)
    R = ra + rb
    m = collide_polygons(Polygons.of([A], ra), [xa], [qa], Polygons.of([B], rb), [xb], [qb], margin)
    got = one(m)
    check_anchors(m, [xa], [xb])
    if gap == 0.0:
        depth = polygon_depth(WA, WB)
        assume(depth > 1e-9)
        assert got["count"] >= 1
        least = min(got["sep"])
        # Below zero, and no deeper than the true depth (each point lies on one polygon and
        # is measured along an edge normal of the other).
        assert -depth - R - 1e-9 <= least < 0.0
        return
    assume(abs(gap - R - margin) > 1e-9 and gap > 1e-9)
    if gap - R > margin:
        assert got["count"] == 0
        return
    assert got["count"] >= 1
    least = min(got["sep"])
    # Exactly the distance, or (Box2D's choice of the clip over a corner point within 0.1
    # LINEAR_SLOP) at most that much more.
    assert gap - R - 1e-9 <= least <= gap - R + 0.1 * LINEAR_SLOP + 1e-9
    # The normal separates the cores by no more than the nearest point's separation (exactly
    # that for a corner-to-corner point, the reference face's axis for clipped ones).
    n = got["normal"]
    assert min(dot(w, n) for w in WB) - support(WA, n) <= least + R + 1e3 * aim(gap)
    # Each point lies between the surfaces: A's surface point (the point less half the
    # separation along n) is on or in A's solid, B's (plus half) on or in B's.
    for p, s in zip(got["point"], got["sep"], strict=True):
        on_a = (p[0] - s / 2 * n[0], p[1] - s / 2 * n[1])
        on_b = (p[0] + s / 2 * n[0], p[1] + s / 2 * n[1])
        assert signed_distance(on_a, WA) <= ra + 1e-9
        assert signed_distance(on_b, WB) <= rb + 1e-9


@given(
    A=convex_polygons(),
    B=convex_polygons(),
    xa=points,
    qa=angles,
    xb=points,
    qb=angles,
    phi=angles,
    kind=st.sampled_from(["polygons", "capsule", "circle"]),
)
def test_turning_the_whole_scene_turns_the_manifold(
    A: tuple[P, ...], B: tuple[P, ...], xa: P, qa: float, xb: P, qb: float, phi: float, kind: str
) -> None:
    """Both bodies and the scene turned by phi about the origin: the normal and the points
    turn by phi, the separations and ids stay (to 1e-12)."""
    a = Polygons.of([A], 0.05)
    b: Any = {
        "polygons": Polygons.of([B]),
        "capsule": Capsules([B[0]], [B[1]], [0.1]),
        "circle": Circles([B[0]], [0.3]),
    }[kind]
    m1 = collide(a, [xa], [qa], b, [xb], [qb], BIG)
    m2 = collide(a, [turn(phi, xa)], [qa + phi], b, [turn(phi, xb)], [qb + phi], BIG)
    g1, g2 = one(m1), one(m2)
    assert g1["count"] == g2["count"] and g1["feature"] == g2["feature"]
    assert np.allclose(g1["sep"], g2["sep"], rtol=0, atol=1e-12)
    assert math.hypot(*sub(turn(phi, g1["normal"]), g2["normal"])) < 1e-12
    for p1, p2 in zip(g1["point"], g2["point"], strict=True):
        assert math.hypot(*sub(turn(phi, p1), p2)) < 1e-12


@pytest.mark.parametrize("phi", [0.0, 0.3, -2.0])
def test_a_resting_box_keeps_its_ids_when_it_moves_a_little(phi: float) -> None:
    """Feature ids name the vertices that make each point: nudged sideways and down, turned a
    hair, in a turned scene, the box keeps the same two ids in the same slots."""
    ground, box = Polygons.of([GROUND]), Polygons.of([BOX])

    def ids(x: float, y: float, q: float) -> list[int]:
        m = collide_polygons(ground, [(0.0, 0.0)], [phi], box, [turn(phi, (x, y))], [phi + q])
        assert m.count[0] == 2
        return m.feature[0].tolist()

    first = ids(1.0, 1.0, 0.0)
    assert len(set(first)) == 2
    for x, y, q in [(1.01, 1.0, 0.0), (0.97, 0.999, 0.0), (1.2, 0.998, 1e-3), (1.0, 1.001, -1e-3)]:
        assert ids(x, y, q) == first


def test_a_batch_gives_each_pair_what_it_gives_alone() -> None:
    """Mixed pairs in one call (3 to 8 vertices padded to 8, capsules as 2, radii) give the
    same bits as each pair in a call of its own, for every function."""
    rng = np.random.default_rng(7)

    def poly(k: int) -> list[P]:
        t = np.sort(rng.uniform(0.0, 2 * np.pi, k))
        a, b = rng.uniform(0.2, 1.0, 2)
        return [(float(a * np.cos(s)), float(b * np.sin(s))) for s in t]

    n = 40
    polys = [poly(int(rng.integers(3, 9))) for _ in range(n)]
    others = [poly(int(rng.integers(3, 9))) for _ in range(n)]
    ra, rb = rng.choice([0.0, 0.1], n), rng.choice([0.0, 0.05], n)
    xa, xb = rng.uniform(-1.0, 1.0, (n, 2)), rng.uniform(-1.0, 1.0, (n, 2))
    qa, qb = rng.uniform(-3.0, 3.0, n), rng.uniform(-3.0, 3.0, n)
    centers = rng.uniform(-0.5, 0.5, (n, 2))
    ends = rng.uniform(-1.0, 1.0, (n, 2, 2))
    kinds = {
        "polygons": (Polygons.of(polys, ra), Polygons.of(others, rb)),
        "polygon-circle": (Polygons.of(polys, ra), Circles(centers, rb + 0.1)),
        "polygon-capsule": (Polygons.of(polys, ra), Capsules(ends[:, 0], ends[:, 1], rb)),
        "capsules": (Capsules(ends[:, 0], ends[:, 1], ra), Capsules(ends[:, 1], centers, rb)),
        "capsule-circle": (Capsules(ends[:, 0], ends[:, 1], ra), Circles(centers, rb)),
        "circles": (Circles(centers, ra + 0.2), Circles(ends[:, 0], rb)),
        "plane-polygon": (HalfPlanes(centers, np.tile([[0.6, 0.8]], (n, 1))), Polygons.of(others)),
    }
    for name, (a, b) in kinds.items():
        batch = collide(a, xa, qa, b, xb, qb, 0.5)
        assert batch.count.sum() > 0, name
        for k in range(n):
            alone = collide(a.take([k]), xa[[k]], qa[[k]], _unpadded(b, k), xb[[k]], qb[[k]], 0.5)
            for field in ("normal", "count", "point", "anchor_a", "anchor_b", "separation"):
                want, got = getattr(alone, field)[0], getattr(batch, field)[k]
                assert np.array_equal(want, got), (name, k, field)
            assert np.array_equal(alone.feature[0], batch.feature[k]), (name, k)


def _unpadded(kind: Any, k: int) -> Any:
    """Row k alone, a polygon cut to its own vertex count (no padding at all)."""
    if isinstance(kind, Polygons):
        c = int(kind.count[k])
        return Polygons(
            kind.vertices[[k], :c], kind.normals[[k], :c], kind.count[[k]], kind.radius[[k]]
        )
    return kind.take([k])


# -- the static world's kinds -------------------------------------------------------------------
def test_a_box_on_a_floor_plane_and_on_its_corner() -> None:
    floor = HalfPlanes([(0.0, 0.0)], [(0.0, 1.0)])
    box = Polygons.of([BOX], 0.02)
    flat = one(collide_half_plane_polygon(floor, (0.0, 0.0), 0.0, box, [(2.0, 0.52 - 0.01)], [0.0]))
    assert flat["count"] == 2 and flat["sep"] == pytest.approx([-0.01, -0.01], abs=1e-15)
    assert same_points(flat["point"], [(1.5, -0.005), (2.5, -0.005)], 1e-15)
    h = math.sqrt(2.0) / 2
    tilted = one(
        collide_half_plane_polygon(
            floor, (0.0, 0.0), 0.0, box, [(2.0, h + 0.05)], [math.pi / 4], 0.1
        )
    )
    assert tilted["count"] == 1 and tilted["sep"][0] == pytest.approx(0.03, abs=1e-12)
    assert tilted["point"][0] == pytest.approx((2.0, 0.05 - 0.035), abs=1e-12)


def test_a_capsule_on_a_floor_has_a_point_under_each_end_until_it_tilts() -> None:
    """Level, 0.004 above the floor: both ends at 0.004. Tilted by 0.1 rad about its middle,
    the high end rises 2 sin(0.1) = 0.1997 past the margin: one point, the low end's."""
    floor = HalfPlanes([(0.0, 0.0)], [(0.0, 1.0)])
    cap = Capsules([(-1.0, 0.0)], [(1.0, 0.0)], [0.3])
    level = one(collide(floor, (0.0, 0.0), 0.0, cap, [(5.0, 0.304)], [0.0]))
    assert level["count"] == 2 and level["sep"] == pytest.approx([0.004, 0.004], abs=1e-15)
    assert same_points(level["point"], [(4.0, 0.002), (6.0, 0.002)], 1e-15)
    low = 0.304 - math.sin(0.1)  # the low end's centre height
    tilted = one(collide(floor, (0.0, 0.0), 0.0, cap, [(5.0, 0.304)], [0.1]))
    assert tilted["count"] == 1 and tilted["sep"][0] == pytest.approx(low - 0.3, abs=1e-15)
    assert tilted["feature"] == [0]  # the capsule's first end (a)
    # Seen from the capsule: the same point, the normal down.
    back = one(collide(cap, [(5.0, 0.304)], [0.1], floor, (0.0, 0.0), 0.0))
    assert back["normal"] == (0.0, -1.0) and back["sep"] == tilted["sep"]


def test_a_circle_on_a_slanted_plane() -> None:
    n = unit((1.0, 2.0))
    plane = HalfPlanes([(1.0, 1.0)], [n])
    got = one(
        collide_half_plane_circle(
            plane,
            (0.0, 0.0),
            0.0,
            Circles([(0.0, 0.0)], [0.2]),
            [(1.0 + 0.5 * n[0], 1.0 + 0.5 * n[1])],
            [1.0],
            0.5,
        )
    )
    assert got["sep"][0] == pytest.approx(0.3, abs=1e-15)
    assert got["normal"] == pytest.approx(n, abs=1e-15)


def test_every_collider_is_a_kind_and_a_box_meets_each_one() -> None:
    """A dynamic box (1 x 1, centre (x, y)) against a floor Plane, a room Box (its four walls),
    a Segment, a Circle and a Polygon, with no broadphase: each contact at the gap the
    geometry gives."""
    colliders = [
        Plane((0.0, 0.0), (0.0, 1.0)),
        Box((-10.0, -1.0), (10.0, 20.0)),
        Segment((4.0, 2.0), (6.0, 2.0), 0.1),
        Circle((-4.0, 3.0), 0.5),
        Polygon.box(1.0, 1.0, center=(8.0, 5.0)),
    ]
    statics = static_shapes(colliders)
    assert statics.half_plane_owner.tolist() == [0, 1, 1, 1, 1]
    assert statics.capsule_owner.tolist() == [2] and statics.circle_owner.tolist() == [3]
    assert statics.polygon_owner.tolist() == [4]
    # Boxes: resting on the floor, 0.01 under the segment's round bottom, 0.02 beside the
    # circle, 0.03 left of the polygon, against the room's left wall.
    x = np.array(
        [
            [0.0, 0.5],
            [5.0, 2.0 - 0.1 - 0.5 - 0.01],
            [-4.0 + 0.5 + 0.52, 3.0],
            [8.0 - 1.0 - 0.03, 5.0],
            [-9.5, 10.0],
        ]
    )
    shapes = Polygons.of([BOX] * len(x))
    found = {}
    for m, rows, owner in collide_static(shapes, x, 0.0, statics, 0.05):
        for k in range(len(m)):
            found[(int(rows[k]), int(owner[k]))] = one(m, k)
    assert found[(0, 0)]["sep"] == [0.0, 0.0]
    assert found[(1, 2)]["sep"] == pytest.approx([0.01, 0.01], abs=1e-12)
    assert found[(2, 3)]["sep"] == pytest.approx([0.02], abs=1e-12)
    assert found[(3, 4)]["sep"] == pytest.approx([0.03, 0.03], abs=1e-12)
    assert found[(4, 1)]["sep"] == [0.0, 0.0]
    assert found[(4, 1)]["normal"] == (-1.0, 0.0)  # from the box (A) into the wall
    assert len(found) == 5


STATIC = [
    Plane((0.0, -2.0), (0.6, 0.8)),
    Box((-5.0, -5.0), (5.0, 5.0)),
    Segment((1.0, 1.0), (3.0, 2.0), 0.2),
    Segment((-2.0, 2.0), (-2.0, 3.0)),
    Circle((-1.0, -1.0), 0.5),
    Polygon([(1.0, -2.0), (3.0, -1.5), (2.0, 0.0)], 0.1),
]


@given(x=st.floats(-4.5, 4.5), y=st.floats(-4.5, 4.5), r=st.floats(0.05, 0.5), q=angles)
def test_a_circle_meets_each_static_collider_at_the_colliders_own_distance(
    x: float, y: float, r: float, q: float
) -> None:
    """A dynamic circle (its centre off its body's origin, the body turned) against every
    collider as kinds: the least separation of each collider's manifolds is the collider's
    own signed distance (engine.geometry.colliders) from the centre, less r."""
    local = (0.1, -0.2)
    (c,) = place((x, y), q, [local])
    found: dict[int, float] = {}
    for m, _, owner in collide_static(
        Circles([local], [r]), [(x, y)], q, static_shapes(STATIC), 1.0
    ):
        for k in range(len(m)):
            o = int(owner[k])
            found[o] = min(found.get(o, math.inf), float(m.separation[k].min()))
    for k, collider in enumerate(STATIC):
        gap = collider.distance(c) - r
        assume(abs(gap - 1.0) > 1e-9)
        if gap <= 1.0:
            assert abs(found[k] - gap) < 1e-12, (k, collider)
        else:
            assert k not in found


@given(x=st.floats(-3.0, 4.0), y=st.floats(-3.0, 4.0), r=st.sampled_from([0.0, 0.25]))
def test_polygon_distance_is_the_colliders_distance(x: float, y: float, r: float) -> None:
    p = Polygon([(0.0, 0.0), (3.0, 0.5), (2.5, 2.0), (0.5, 2.5)], r)
    assert abs(float(polygon_distance(p, [[x, y]])[0]) - p.distance((x, y))) < 1e-12


# -- refusals -----------------------------------------------------------------------------------
def test_bad_inputs_are_refused_by_name() -> None:
    c = Circles([(0.0, 0.0)], [1.0])
    with pytest.raises(ValueError, match="a and b must hold one shape a pair"):
        collide_circles(c, [(0.0, 0.0)], [0.0], Circles(np.zeros((2, 2)), [1.0, 1.0]), 0, 0)
    with pytest.raises(ValueError, match="margin must be >= 0"):
        collide_circles(c, [(0.0, 0.0)], [0.0], c, [(0.0, 0.0)], [0.0], -1.0)
    with pytest.raises(ValueError, match=r"xb must have shape \(1, 2\)"):
        collide_circles(c, [(0.0, 0.0)], [0.0], c, [(0.0, 0.0, 0.0)], [0.0])
    with pytest.raises(ValueError, match=r"center must have shape"):
        Circles([0.0, 0.0], [1.0])
    with pytest.raises(ValueError, match=r"a and b must differ .* rows \[1\] have a == b"):
        Capsules([(0.0, 0.0), (1.0, 1.0)], [(1.0, 0.0), (1.0, 1.0)], [0.1, 0.1])
    with pytest.raises(ValueError, match="Circles: every field must have one row a shape"):
        Circles([(0.0, 0.0)], [1.0, 2.0])
    with pytest.raises(ValueError, match=r"polygons\[1\] must make a convex polygon"):
        Polygons.of([BOX, [(0, 0), (2, 0), (1, 0.5), (2, 2), (0, 2)]])
    with pytest.raises(TypeError, match="not two HalfPlanes"):
        h = HalfPlanes([(0.0, 0.0)], [(0.0, 1.0)])
        collide(h, (0, 0), 0, h, (0, 0), 0)
    with pytest.raises(TypeError, match="colliders must be Plane, Box"):
        static_shapes([object()])  # type: ignore[list-item]


def test_a_segment_shorter_than_rounding_is_its_point() -> None:
    """Nearest points with one segment of length 1e-200 (its square underflows to 0): the
    other's nearest point to it, not its start."""
    p = np.array([[0.0, 0.0], [1.5, 1.0], [0.0, 0.0]])
    q = np.array([[2.0, 0.0], [1.5, 1.0 + 1e-200], [0.0, 0.0]])
    f1, f2, c1, c2, dd = ericson(p[[0, 1, 2]], q[[0, 1, 2]], p[[1, 0, 2]], q[[1, 0, 2]])
    assert f1.tolist() == [0.75, 0.0, 0.0] and f2.tolist() == [0.0, 0.75, 0.0]
    assert dd.tolist() == [1.0, 1.0, 0.0]


def test_polygon_capsule_is_the_capsule_as_a_two_vertex_polygon() -> None:
    """A capsule lying on a box's top: two points at its ends' projections, separation the
    gap less its radius."""
    got = one(
        collide_polygon_capsule(
            Polygons.of([GROUND]),
            (0.0, 0.0),
            0.0,
            Capsules([(-1.0, 0.0)], [(1.0, 0.0)], [0.2]),
            [(3.0, 0.5 + 0.2 + 0.004)],
            [0.0],
        )
    )
    assert got["count"] == 2 and got["sep"] == pytest.approx([0.004, 0.004], abs=1e-15)
    assert sorted(p[0] for p in got["point"]) == pytest.approx([2.0, 4.0])
