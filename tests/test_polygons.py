"""Convex polygon colliders (engine.geometry.colliders.Polygon) and the mass functions
(engine.geometry.mass).

Each checked against a closed form, a theorem or an independent computation: refusals name
the argument; area, centroid and distance against exact geometry; a ball on a static polygon
rests, rolls off and bounces as the exact contacts promise; moments against pymunk's own
numbers and the textbook's closed forms.
"""

from __future__ import annotations

import math
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import Body, Box, Circle, OverlapWarning, Plane, Segment, Vector, World
from engine.forces import Gravity
from engine.geometry import convex
from engine.geometry.colliders import Polygon
from engine.geometry.mass import (
    area_for_circle,
    area_for_polygon,
    area_for_segment,
    moment_for_box,
    moment_for_circle,
    moment_for_polygon,
    moment_for_segment,
)

G = 9.81
SQUARE = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]


# -- refusals ------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("vertices", "error", "words"),
    [
        (5, TypeError, "vertices must be a sequence"),
        ("abc", TypeError, "vertices must be a sequence"),
        ([(0, 0), (1, 0), "x"], TypeError, "vertices[2] must be a 2D point"),
        ([(0, 0), (1, 0), (0, math.nan)], ValueError, "vertices[2] must be finite"),
        ([(0, 0), (1, 0)], ValueError, "at least 3 points"),
        ([(math.cos(k / 50), math.sin(k / 50)) for k in range(315)], ValueError, "at most 256"),
        ([(0, 0), (1, 0), (1, 0), (0, 1)], ValueError, "vertices[1] and vertices[2] are the same"),
        ([(0, 0), (1, 0), (1, 1e-12), (0, 1)], ValueError, "are 1e-12 apart, the same point"),
        ([(0, 0), (1, 1), (2, 2)], ValueError, "all 3 points lie on one line"),
        ([(0, 0), (10, 10), (20, 0), (-10, 10)], ValueError, "must go in order round the"),
        ([(0, 0), (1, 0), (2, 0), (1, 1)], ValueError, "vertices[1] = (1.0, 0.0) lies on the"),
        ([(0, 0), (2, 0), (1, 0.5), (2, 2), (0, 2)], ValueError, "turns the other way"),
        ([(0, 0), (1e308, 0), (0, 1e308)], ValueError, "the area overflows"),
    ],
)
def test_a_bad_polygon_is_refused_by_the_name_of_the_argument(
    vertices: Any, error: type, words: str
) -> None:
    with pytest.raises(error) as info:
        Polygon(vertices)
    assert words in str(info.value)


def test_a_star_is_refused_though_every_turn_is_left() -> None:
    # A pentagram: its points in the order 0, 2, 4, 1, 3 of a pentagon turn left every time
    # and wind round twice.
    star = [
        (math.cos(2 * math.pi * k * 2 / 5), math.sin(2 * math.pi * k * 2 / 5)) for k in range(5)
    ]
    with pytest.raises(ValueError, match="wind round 2 times"):
        Polygon(star)


@pytest.mark.parametrize(
    ("kwargs", "error", "words"),
    [
        ({"radius": -0.1}, ValueError, "radius must be >= 0"),
        ({"radius": "1"}, TypeError, "radius must be a real number"),
        ({"restitution": 2.0}, ValueError, "restitution must be in [0, 1]"),
        ({"friction": -1.0}, ValueError, "friction must be >= 0"),
        ({"sensor": 1}, TypeError, "sensor must be True or False"),
        ({"filter": 3}, TypeError, "filter must be an engine.Filter"),
    ],
)
def test_bad_radius_and_material_are_refused_by_name(kwargs: Any, error: type, words: str) -> None:
    with pytest.raises(error) as info:
        Polygon(SQUARE, **kwargs)
    assert words in str(info.value)


@pytest.mark.parametrize(
    ("args", "kwargs", "error", "words"),
    [
        ((0.0, 1.0), {}, ValueError, "width must be > 0 (the box's full width"),
        ((2.0, -1.0), {}, ValueError, "height must be > 0 (the box's full height"),
        ((math.inf, 1.0), {}, ValueError, "width must be finite"),
        ((1.0, True), {}, TypeError, "height must be a real number"),
        ((1.0, 1.0), {"center": (1.0,)}, TypeError, "center must be a 2D point"),
        ((1.0, 1.0), {"radius": -1.0}, ValueError, "radius must be >= 0"),
        ((1e308, 1.0), {"center": (1.7e308, 0.0)}, ValueError, "within the float range"),
    ],
)
def test_polygon_box_refuses_sizes_that_are_not_positive(
    args: Any, kwargs: Any, error: type, words: str
) -> None:
    with pytest.raises(error) as info:
        Polygon.box(*args, **kwargs)
    assert words in str(info.value)


def test_a_polygon_is_fixed_once_made() -> None:
    p = Polygon(SQUARE)
    with pytest.raises(AttributeError, match="cannot change once it is made"):
        p.vertices = ()  # type: ignore[misc]
    with pytest.raises(AttributeError, match="cannot change once it is made"):
        p.radius = 1.0  # type: ignore[misc]


def test_the_room_box_points_to_polygon_box_for_a_solid_box() -> None:
    assert Box.__doc__ is not None and "Polygon.box" in Box.__doc__


# -- geometry ------------------------------------------------------------------------------------
def test_clockwise_input_runs_counter_clockwise_with_outward_normals() -> None:
    p = Polygon(list(reversed(SQUARE)))  # clockwise
    verts = [tuple(v) for v in p.vertices]
    assert set(verts) == set(SQUARE)
    # Counter-clockwise: every edge turns left, and each normal points away from the centroid.
    for i, v in enumerate(p.vertices):
        e1 = v - p.vertices[i - 1]
        e2 = p.vertices[(i + 1) % 4] - v
        assert e1.x * e2.y - e1.y * e2.x > 0
        mid = (v + p.vertices[(i + 1) % 4]) * 0.5
        n = p.normals[i]
        assert abs(n.magnitude() - 1.0) < 1e-15
        assert n.x * e2.x + n.y * e2.y == 0.0
        assert n.x * (mid - p.centroid).x + n.y * (mid - p.centroid).y > 0


@given(
    w=st.floats(0.01, 100.0),
    h=st.floats(0.01, 100.0),
    cx=st.floats(-100.0, 100.0),
    cy=st.floats(-100.0, 100.0),
    r=st.floats(0.0, 10.0),
)
def test_box_area_centroid_and_bounds_are_the_closed_forms(
    w: float, h: float, cx: float, cy: float, r: float
) -> None:
    p = Polygon.box(w, h, center=(cx, cy), radius=r)
    # A rounded box: the box, a strip r wide along each side, a quarter disc at each corner.
    want = w * h + 2.0 * r * (w + h) + math.pi * r * r
    # The corners themselves are rounded to the coordinates' precision (33 +- 0.005 is not
    # exact), so the area may be off by a few ulps of the coordinates times the size.
    scale = abs(cx) + abs(cy) + w + h + r
    assert abs(p.area - want) <= 1e-14 * (want + scale * (w + h + r))
    assert abs(p.centroid.x - cx) <= 1e-12 * scale and abs(p.centroid.y - cy) <= 1e-12 * scale
    x0, y0, x1, y1 = p.bounds()
    assert (x0, y0, x1, y1) == pytest.approx(
        (cx - w / 2 - r, cy - h / 2 - r, cx + w / 2 + r, cy + h / 2 + r), rel=1e-15, abs=1e-12
    )


def _polygonized(
    vertices: list[tuple[float, float]], r: float, k: int
) -> list[tuple[float, float]]:
    """The rounded polygon's outline with each corner's arc as k + 1 points (for a check by
    fine polygons: the arcs' chords lose O(1 / k^2) of the area)."""
    out = []
    n = len(vertices)
    for i, (vx, vy) in enumerate(vertices):
        (px, py), (qx, qy) = vertices[i - 1], vertices[(i + 1) % n]
        a0 = math.atan2(-(vx - px), vy - py)  # the previous edge's outward normal
        a1 = math.atan2(-(qx - vx), qy - vy)
        if a1 < a0:
            a1 += 2 * math.pi
        for j in range(k + 1):
            a = a0 + (a1 - a0) * j / k
            out.append((vx + r * math.cos(a), vy + r * math.sin(a)))
    return out


def test_rounded_area_and_centroid_match_a_fine_polygon() -> None:
    tri = [(0.0, 0.0), (3.0, 0.5), (1.0, 2.0)]
    r = 0.4
    outline = _polygonized(tri, r, 2000)
    rounded = Polygon(tri, r)
    # The outline has 6,000 points, past a collider's 8: its numbers come from
    # engine.geometry.convex with no radius (the core's shoelace formulas, checked against pymunk
    # below).
    assert abs(rounded.area - convex.area(outline)) < 1e-6 * rounded.area
    cx, cy = convex.centroid(outline)
    assert abs(rounded.centroid.x - cx) < 1e-6 and abs(rounded.centroid.y - cy) < 1e-6


def _brute_distance(p: Polygon, x: float, y: float) -> float:
    """Signed distance to the rounded polygon: to the nearest edge point, minus inside."""
    best = math.inf
    verts = [tuple(v) for v in p.vertices]
    inside = True
    for i, (ax, ay) in enumerate(verts):
        bx, by = verts[(i + 1) % len(verts)]
        dx, dy = bx - ax, by - ay
        if dx * (y - ay) - dy * (x - ax) < 0:
            inside = False
        u = min(1.0, max(0.0, ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)))
        best = min(best, math.hypot(x - ax - u * dx, y - ay - u * dy))
    return (-best if inside else best) - p.radius


@given(
    x=st.floats(-4.0, 6.0),
    y=st.floats(-4.0, 6.0),
    r=st.sampled_from([0.0, 0.3]),
)
def test_distance_and_closest_match_the_nearest_edge_point(x: float, y: float, r: float) -> None:
    p = Polygon([(0.0, 0.0), (3.0, 0.5), (2.5, 2.0), (0.5, 2.5), (-0.5, 1.0)], r)
    want = _brute_distance(p, x, y)
    surface, normal, d = p.closest((x, y))
    assert abs(d - want) < 1e-12
    assert abs(p.distance((x, y)) - want) < 1e-12
    assert abs(normal.magnitude() - 1.0) < 1e-12
    # The point lies d along the normal from the surface point, which is on the surface.
    assert abs(surface + normal * d - Vector(x, y)) < 1e-12
    assert abs(_brute_distance(p, surface.x, surface.y)) < 1e-12


def test_a_point_a_rounding_outside_a_corner_gets_a_surface_point_on_the_surface() -> None:
    # Found exploring the test above (its shrunk example): a point 2.2e-16 outside the corner
    # (0, 0) was taken on the outside branch of Polygon.closest, whose nearest edge point
    # rounds onto the corner, and the normal was the direction of that 2e-16 difference,
    # (-1, 0), outside the corner's cone of normals: the surface point returned, (-0.3, 0),
    # was 0.032 inside the rounded polygon (distance and depth were right). Within rounding
    # of the boundary the normal is now the face's of greatest separation.
    test_distance_and_closest_match_the_nearest_edge_point.hypothesis.inner_test(
        -2.220446049250313e-16, 0.0, 0.3
    )


def test_faces_are_the_edges_pushed_out_by_the_radius_and_the_corners() -> None:
    p = Polygon([(0.0, 0.0), (4.0, 0.0), (0.0, 3.0)], 0.5)
    lines = p.lines()
    assert len(lines) == 3 and all(two is False and rho == 0.5 for _, _, rho, two, _, _ in lines)
    for (px, py), (nx, ny), _, _, lo, hi in lines:
        # The face runs from p along the tangent (-n_y, n_x) for [lo, hi] = [0, edge length],
        # ending at the next vertex.
        end = (px - ny * hi, py + nx * hi)
        assert lo == 0.0
        assert any(abs(end[0] - v.x) < 1e-12 and abs(end[1] - v.y) < 1e-12 for v in p.vertices)
        assert abs(math.hypot(nx, ny) - 1.0) < 1e-15
    assert p.discs() == [((v.x, v.y), 0.5) for v in p.vertices]


# -- in the World --------------------------------------------------------------------------------
def test_a_body_put_inside_a_polygon_leaves_by_the_nearest_face() -> None:
    """A box 2 m x 1 m about the origin; a ball of r 0.5 at (0.3, 0.2) is 0.8 m from leaving by
    the top (y = 0.5 + r), 1.2 m by the right side: it is put on the top, and told so."""
    w = World()
    box = w.add_collider(Polygon.box(2.0, 1.0))
    with pytest.warns(OverlapWarning, match="started inside Polygon"):
        b = w.add(Body(Vector(0.3, 0.2), radius=0.5))
    assert b.pos == Vector(0.3, 1.0)
    assert box.distance(b.pos) == pytest.approx(0.5, abs=1e-12)


def _world() -> World:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    return w


@pytest.mark.parametrize("angle", [0.0, 0.5])
def test_a_ball_dropped_on_a_box_rests_on_its_top(angle: float) -> None:
    """The top face is a one-sided line y = top, pushed out by the box's radius: the ball comes
    to rest with its centre exactly r above it (rest is a state: y does not move after)."""
    r, top, radius = 0.25, 1.0, 0.1 * angle  # a rounded box too
    w = _world()
    box = w.add_collider(Polygon.box(4.0, 1.0, center=(0.0, top - 0.5), radius=radius))
    b = w.add(Body(Vector(0.3, 3.0), radius=r, restitution=0.5))
    while w.resting(b) is None:
        w.step(1 / 60)
        assert w.t < 10.0, "never came to rest"
    for _ in range(60):
        w.step(1 / 60)
    assert w.resting(b) is box
    assert b.pos.y == top + radius + r
    assert b.pos.x == 0.3
    assert b.vel.x == 0.0 and b.vel.y == 0.0


@pytest.mark.parametrize(("x0", "radius"), [(1.1, 0.0), (1.05, 0.0), (-1.15, 0.0), (1.1, 0.1)])
def test_a_ball_dropped_past_a_corner_rolls_off_it_and_lands_beside(
    x0: float, radius: float
) -> None:
    """A ball dropped at x0, d = |x0| - 1 beyond a corner of a box 2 m wide and 1 m high (d < r):
    it meets the corner, a round face of radius rho (the box's rounding) around the corner
    (+-1, 1); its centre is then R = rho + r from it, so y_hit = 1 + sqrt(R^2 - d^2), at
    t = sqrt(2 (3 - y_hit) / g), with the normal (+-d, sqrt(R^2 - d^2)) / R. It is thrown
    outward and comes to rest on the floor beside the box."""
    r = 0.2
    w = _world()
    floor = w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    box = w.add_collider(Polygon.box(2.0, 1.0, center=(0.0, 0.5), radius=radius))
    b = w.add(Body(Vector(x0, 3.0), radius=r, restitution=0.3, friction=0.5))
    while not w.began:
        w.step(1 / 60)
        assert w.t < 2.0
    (ev,) = w.began
    side = math.copysign(1.0, x0)
    R, d = radius + r, abs(x0) - 1.0
    y_hit = 1.0 + math.sqrt(R * R - d * d)
    assert ev.collider is box
    assert abs(ev.time - math.sqrt(2.0 * (3.0 - y_hit) / G)) < 1e-9
    assert abs(ev.normal - Vector(side * d / R, math.sqrt(R * R - d * d) / R)) < 1e-9
    for _ in range(300):
        w.step(1 / 60)
        assert box.distance(b.pos) >= r - 1e-9  # never inside the box
    assert w.resting(b) is floor
    assert b.pos.y == r
    assert side * b.pos.x > 1.0 + radius + r  # beside the box, on the side it fell


@pytest.mark.parametrize("arrays", [False, True])
@pytest.mark.parametrize("kind", ["box", "segment"])
def test_a_ball_sliding_off_the_top_leaves_the_edge(kind: str, arrays: bool) -> None:
    # At 2 m/s over an edge that would turn it at u^2 / r = 20 > g m/s^2 it flies on from the
    # edge (x = 1 at t = 0.25 s) on the parabola; it once met the face's own round end with
    # the face's normal (to 2.6e-8), took the two for a wedge and stopped dead there.
    r = 0.2
    w = World(integrator="auto", kernels="numpy" if arrays else None)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    if kind == "box":
        w.add_collider(Polygon.box(2.0, 1.0, center=(0.0, 0.5), friction=0.0))
    else:
        w.add_collider(Segment((-1.0, 1.0), (1.0, 1.0), friction=0.0))
    b = w.add(Body(Vector(0.5, 1.0 + r), Vector(2.0, 0.0), radius=r, friction=0.0))
    if (
        arrays
    ):  # the arrays' path (engine.exact.sweep), not one body in floats (engine.exact.sweep_one)
        assert w._contacts is not None
        w._contacts.few = w._contacts.few_resting = 0
    for _ in range(21):
        w.step(1 / 60)
    t = 21 / 60 - 0.25  # in flight since the edge
    assert b.pos.x == pytest.approx(1.0 + 2.0 * t, abs=1e-8)
    assert b.pos.y == pytest.approx(1.0 + r - 0.5 * G * t * t, abs=1e-8)
    for _ in range(99):
        w.step(1 / 60)
    assert b.pos.x > 1.0 + r and b.pos.y == r


@pytest.mark.parametrize("tilt", [math.radians(30.0), math.radians(45.0), math.radians(60.0)])
def test_a_ball_off_a_diamonds_slanted_face_leaves_by_the_mirror_law(tilt: float) -> None:
    """No gravity, e = 1, mu = 0: a ball moving straight down meets a face whose outward normal
    is n = (sin t, cos t); it leaves with v - 2 (v.n) n, at the same speed, at the moment the
    straight path puts its centre r from the face's line."""
    r, speed = 0.1, 3.0
    s, c = math.sin(tilt), math.cos(tilt)
    # A diamond whose upper right face runs from (0, 1) along (c, -s) with normal (s, c).
    right = (c * 2.0, 1.0 - s * 2.0)
    diamond = Polygon([(0.0, 1.0), (-1.0, 0.0), (0.0, -3.0), right], restitution=1.0, friction=0.0)
    assert abs(diamond.normals[-1] - Vector(s, c)) < 1e-15  # the face from `right` to the top
    w = World(integrator="auto")
    w.add_collider(diamond)
    x0 = 0.5 * c  # above the face's middle
    b = w.add(Body(Vector(x0, 3.0), Vector(0.0, -speed), radius=r, restitution=1.0, friction=0.0))
    while not w.began:
        w.step(1 / 60)
        assert w.t < 2.0
    (ev,) = w.began
    # The face's line: n.(x - (0, 1)) = 0; the centre (x0, y) touches at n.(x0, y - 1) = r.
    y_hit = 1.0 + (r - s * x0) / c
    n = Vector(s, c)
    v = Vector(0.0, -speed)
    v_after = v - n * (2.0 * (v.x * n.x + v.y * n.y))
    assert abs(ev.time - (3.0 - y_hit) / speed) < 1e-12
    assert abs(ev.normal - n) < 1e-12
    assert abs(b.vel - v_after) < 1e-12 * speed
    assert abs(b.vel.magnitude() - speed) < 1e-12 * speed


# -- mass ----------------------------------------------------------------------------------------
def _pymunk() -> Any:
    return pytest.importorskip("pymunk")


def test_moments_are_the_closed_forms() -> None:
    m = 3.0
    assert moment_for_circle(m, 0.0, 2.0) == m * 2.0**2 / 2  # a disc
    assert moment_for_circle(m, 1.0, 2.0) == m * (1.0 + 4.0) / 2  # a ring
    assert moment_for_box(m, (2.0, 5.0)) == pytest.approx(m * (4.0 + 25.0) / 12, rel=1e-15)
    assert moment_for_segment(m, (1.0, 1.0), (4.0, 5.0), 0.0) == pytest.approx(
        m * 25.0 / 12 + m * (2.5**2 + 3.0**2), rel=1e-15
    )  # a rod of length 5, its centre at (2.5, 3): m L^2 / 12 + m d^2
    square = [(-1.0, -2.5), (1.0, -2.5), (1.0, 2.5), (-1.0, 2.5)]
    assert moment_for_polygon(m, square) == pytest.approx(m * 29.0 / 12, rel=1e-14)
    off = moment_for_polygon(m, square, offset=(3.0, -4.0))
    assert off == pytest.approx(m * 29.0 / 12 + m * 25.0, rel=1e-14)  # parallel axes
    assert moment_for_circle(m, 0.0, 2.0, offset=(3.0, 4.0)) == m * (2.0 + 25.0)
    assert area_for_circle(1.0, 2.0) == math.pi * 3.0
    assert area_for_segment((0.0, 0.0), (3.0, 4.0), 0.5) == 0.5 * (math.pi * 0.5 + 10.0)
    assert area_for_polygon(square, 0.5) == pytest.approx(10.0 + 0.5 * 14.0 + math.pi * 0.25)
    assert area_for_polygon(list(reversed(square))) == pytest.approx(10.0)  # either winding


def test_every_shape_gives_its_area_centroid_and_moment_by_the_same_names() -> None:
    # pymunk's shape.area, shape.center_of_gravity and a moment for a mass, on each shape:
    # the closed forms, and the Polygon's own (its fine-polygon test is below).
    m = 3.0
    disc = Circle((1.0, 2.0), 0.5)
    assert disc.area == math.pi * 0.25 and disc.centroid == Vector(1.0, 2.0)
    assert disc.moment(m) == m * (0.5**2 / 2 + 5.0)  # m r^2 / 2, and m |c|^2 off the origin
    capsule = Segment((1.0, 1.0), (4.0, 5.0), 0.5)
    assert capsule.area == 0.5 * (math.pi * 0.5 + 10.0)  # r (pi r + 2 L), L = 5
    assert capsule.centroid == Vector(2.5, 3.0)
    assert capsule.moment(m) == moment_for_segment(m, (1.0, 1.0), (4.0, 5.0), 0.5)
    assert Segment((0.0, 0.0), (3.0, 4.0)).area == 0.0  # a bare segment: a line
    box = Polygon.box(2.0, 5.0, center=(3.0, -4.0))
    assert box.area == pytest.approx(10.0) and box.centroid == pytest.approx(Vector(3.0, -4.0))
    assert box.moment(m) == pytest.approx(m * 29.0 / 12 + m * 25.0, rel=1e-14)


def test_a_capsule_and_a_rounded_polygon_match_fine_polygons() -> None:
    """The capsule (Box2D's exact formula) and the rounded polygon (edges' rectangles and
    corners' sectors) against their outlines as polygons of 4,000+ points with no radius,
    whose moments are checked against pymunk below: agreement to O(1 / k^2)."""
    m = 2.0
    a, b, r = (0.5, -0.25), (2.5, 1.25), 0.4
    # The capsule's outline: its two half discs' arcs, k + 1 points each.
    ang = math.atan2(b[1] - a[1], b[0] - a[0])
    k = 4000
    outline = [
        (
            b[0] + r * math.cos(ang - math.pi / 2 + math.pi * j / k),
            b[1] + r * math.sin(ang - math.pi / 2 + math.pi * j / k),
        )
        for j in range(k + 1)
    ] + [
        (
            a[0] + r * math.cos(ang + math.pi / 2 + math.pi * j / k),
            a[1] + r * math.sin(ang + math.pi / 2 + math.pi * j / k),
        )
        for j in range(k + 1)
    ]
    J = convex.second_moment(outline) / convex.area(outline)
    assert moment_for_segment(m, a, b, r) == pytest.approx(m * J, rel=1e-6)
    tri = [(0.0, 0.0), (3.0, 0.5), (1.0, 2.0)]
    fine = _polygonized(tri, 0.4, 2000)
    J = convex.second_moment(fine) / convex.area(fine)
    assert moment_for_polygon(m, tri, radius=0.4) == pytest.approx(m * J, rel=1e-6)
    assert moment_for_polygon(m, tri, offset=(1.0, -2.0), radius=0.4) == pytest.approx(
        m * convex.second_moment(fine, about=(-1.0, 2.0)) / convex.area(fine), rel=1e-6
    )


@given(
    m=st.floats(0.1, 100.0),
    w=st.floats(0.1, 10.0),
    h=st.floats(0.1, 10.0),
    ox=st.floats(-5.0, 5.0),
    oy=st.floats(-5.0, 5.0),
    r1=st.floats(0.0, 2.0),
    dr=st.floats(0.0, 2.0),
)
def test_moments_and_areas_match_pymunk_where_pymunk_is_exact(
    m: float, w: float, h: float, ox: float, oy: float, r1: float, dr: float
) -> None:
    pm = _pymunk()
    rel = 1e-12
    assert moment_for_box(m, (w, h)) == pytest.approx(pm.moment_for_box(m, (w, h)), rel=rel)
    assert moment_for_circle(m, r1, r1 + dr, (ox, oy)) == pytest.approx(
        pm.moment_for_circle(m, r1, r1 + dr, (ox, oy)), rel=rel
    )
    assert area_for_circle(r1, r1 + dr) == pytest.approx(pm.area_for_circle(r1, r1 + dr), rel=rel)
    a, b = (ox, oy), (ox + w, oy - h)
    assert moment_for_segment(m, a, b, 0.0) == pytest.approx(
        pm.moment_for_segment(m, a, b, 0.0), rel=rel
    )
    assert area_for_segment(a, b, r1) == pytest.approx(pm.area_for_segment(a, b, r1), rel=rel)
    poly = [(0.0, 0.0), (w, 0.2 * h), (0.7 * w, h), (-0.3 * w, 0.6 * h)]
    assert moment_for_polygon(m, poly, (ox, oy)) == pytest.approx(
        pm.moment_for_poly(m, poly, (ox, oy)), rel=rel
    )
    assert area_for_polygon(poly, r1) == pytest.approx(pm.area_for_poly(poly, r1), rel=rel)


def test_where_pymunk_approximates_ours_is_the_larger_exact_answer() -> None:
    """pymunk takes a capsule as a box L + 2r long (its moment is too large) and leaves a
    polygon's radius out (too small): ours lies on the exact side of each."""
    pm = _pymunk()
    a, b, r = (0.0, 0.0), (2.0, 0.0), 0.5
    exact = moment_for_segment(1.0, a, b, r)
    assert exact < pm.moment_for_segment(1.0, a, b, r)
    sq = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
    assert moment_for_polygon(1.0, sq, radius=r) > pm.moment_for_poly(1.0, sq, (0, 0), r)


@pytest.mark.parametrize(
    ("call", "error", "words"),
    [
        (lambda: moment_for_circle(0.0, 0.0, 1.0), ValueError, "mass must be positive"),
        (lambda: moment_for_circle(1.0, 2.0, 1.0), ValueError, "inner_radius must be <="),
        (lambda: moment_for_circle(1.0, -1.0, 1.0), ValueError, "inner_radius must be >= 0"),
        (lambda: moment_for_box(1.0, (0.0, 1.0)), ValueError, "size must be (width, height)"),
        (lambda: moment_for_box(1.0, 3.0), TypeError, "size must be a 2D point"),
        (lambda: moment_for_segment(1.0, (0, 0), "b", 0.0), TypeError, "b must be a 2D point"),
        (lambda: moment_for_polygon(1.0, [(0, 0), (1, 0)]), ValueError, "at least 3 points"),
        (lambda: moment_for_polygon(1.0, SQUARE, radius=-1), ValueError, "radius must be >= 0"),
        (lambda: area_for_polygon(3), TypeError, "vertices must be a sequence"),
    ],
)
def test_mass_functions_refuse_bad_arguments_by_name(call: Any, error: type, words: str) -> None:
    with pytest.raises(error) as info:
        call()
    assert words in str(info.value)


@pytest.mark.parametrize("thickness", [0.2, 1.0])
@pytest.mark.parametrize("e", [0.0, 0.5])
def test_a_ball_thrown_up_into_a_slab_bounces_off_its_underside(thickness: float, e: float) -> None:
    """A ball thrown up at 88 m/s under gravity meets the underside of a solid slab within one
    step of 1/60 s (it would go 1.46 m, through the slab): it bounces there by the closed
    form. Its top face is one-sided and faces away; once the ball touches the underside its
    centre is behind the top face, which is no contact of it (before, the pull toward that
    face met it at once and the ball ended the step on the slab's top). Frictionless: it
    keeps its speed along the face."""
    r, g, dt = 0.05, 9.81, 1.0 / 60.0
    under = 7.3295
    w = _world()
    w.add_collider(
        Polygon(
            [(-6.6, under), (6.6, under), (6.6, under + thickness), (-6.6, under + thickness)],
            restitution=e,
            friction=0.0,
        )  # fmt: skip
    )
    y0, vy, vx = 7.0, 87.86, -27.6
    b = w.add(Body(Vector(3.9, y0), Vector(vx, vy), radius=r, restitution=1.0, friction=0.0))
    w.step(dt)
    # y0 + vy t - g t^2 / 2 = under - r: the smaller root.
    c = under - r - y0
    t = (vy - math.sqrt(vy * vy - 2.0 * g * c)) / g
    v_after = -e * (vy - g * t)
    rest = dt - t
    assert b.pos.y == pytest.approx(under - r + v_after * rest - 0.5 * g * rest**2, abs=1e-9)
    assert b.vel.y == pytest.approx(v_after - g * rest, abs=1e-9)
    assert b.pos.x == pytest.approx(3.9 + vx * dt, abs=1e-9)
    assert b.pos.y < under - r + 1e-9  # below the slab, never on or in it
