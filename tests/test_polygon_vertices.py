"""Convex polygons of many vertices (up to ``engine.geometry.convex.MAX_VERTICES`` = 256), as
colliders and as bodies' shapes, on both paths.

Each checked against a closed form: a regular n-gon's area n R^2 sin(2 pi / n) / 2 and moment
m R^2 (1 + 2 cos^2(pi / n)) / 6; a ball dropped on a 20-gon meets the face the geometry says,
at the moment the parabola says, and leaves by the mirror law; a 12-gon and a 32-gon dropped
on the ground rest on their bottom face, not in it, and stay there; the loop kernels give the
numpy twins' manifolds and a whole scene's numbers to rounding.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_kernels_manifold import agree

from engine import Body, Plane, Vector, World, kernels
from engine.forces import Gravity
from engine.geometry.colliders import Polygon
from engine.geometry.convex import MAX_VERTICES
from engine.geometry.manifold import (
    HalfPlanes,
    Polygons,
    collide_half_plane_polygon,
    collide_polygons,
)
from engine.geometry.mass import area_for_polygon, moment_for_polygon

G = 9.81
COMPILED = kernels.available()


def ngon(
    n: int, radius: float, center: tuple[float, float] = (0.0, 0.0)
) -> list[tuple[float, float]]:
    """A regular n-gon of circumradius ``radius`` with its bottom edge level (its vertices at
    -pi/2 + pi/n + 2 pi k / n): the edge from vertex 0 to vertex 1 faces straight down."""
    return [
        (
            center[0] + radius * math.cos(-math.pi / 2 + math.pi / n + 2 * math.pi * k / n),
            center[1] + radius * math.sin(-math.pi / 2 + math.pi / n + 2 * math.pi * k / n),
        )
        for k in range(n)
    ]


# -- how many ------------------------------------------------------------------------------------
def test_a_polygon_takes_up_to_max_vertices_and_the_refusal_says_why() -> None:
    """256 vertices are a polygon; 257 are refused, naming the limit and its reason (a
    contact's feature id holds each shape's vertex index in 8 bits)."""
    assert MAX_VERTICES == 256
    assert len(Polygon(ngon(MAX_VERTICES, 1.0)).vertices) == MAX_VERTICES
    with pytest.raises(ValueError) as info:
        Polygon(ngon(MAX_VERTICES + 1, 1.0))
    words = str(info.value)
    assert "at most 256 points" in words and "got 257" in words
    assert "8 bits" in words and "engine.geometry.convex.MAX_VERTICES" in words
    with pytest.raises(ValueError, match="at most 256 points"):
        Body(Vector(0.0, 0.0), shape=Polygon(ngon(300, 1.0)))


# -- mass ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [9, 12, 20, 32, 64, 256])
def test_a_regular_ngons_area_centroid_and_moment_are_the_closed_forms(n: int) -> None:
    """A regular n-gon of circumradius R is n triangles of apex angle 2 pi / n: area
    n R^2 sin(2 pi / n) / 2; each triangle's polar moment about the apex, per unit mass, is
    R^2 (1 + 2 cos^2(pi / n)) / 6 (the square's m s^2 / 6 at n = 4, s = R sqrt 2), and so is
    the whole's, about its centre, which is its centroid."""
    R, m, c = 0.7, 2.5, (0.3, -0.2)
    area = n * R * R * math.sin(2 * math.pi / n) / 2
    per_mass = R * R * (1 + 2 * math.cos(math.pi / n) ** 2) / 6
    shape = Polygon(ngon(n, R, c))
    assert shape.area == pytest.approx(area, rel=1e-12)
    assert area_for_polygon(ngon(n, R)) == pytest.approx(area, rel=1e-12)
    assert abs(shape.centroid - Vector(*c)) < 1e-12
    body = Body(Vector(1.0, 2.0), shape=Polygon(ngon(n, R)), mass=m)
    assert body.moment == pytest.approx(m * per_mass, rel=1e-12)
    assert moment_for_polygon(m, ngon(n, R)) == pytest.approx(m * per_mass, rel=1e-12)


# -- a ball on a 20-gon collider ------------------------------------------------------------------
@pytest.mark.parametrize("face", [3, 4, 6, 9])
def test_a_ball_dropped_on_a_20gon_bounces_off_the_face_below_it(face: int) -> None:
    """A 20-gon of circumradius R about the origin, vertices at 2 pi k / 20: face k (vertex k
    to k + 1) has outward normal n at (k + 1/2) 2 pi / 20 and lies a = R cos(pi / 20) from the
    centre. A ball of radius r let go at rest above the point (a + r) n (moved 2 cm along the
    face) meets that face when its centre gets there, after falling h: at t = sqrt(2 h / g),
    with normal n, and leaves with v - (1 + e) (v.n) n (frictionless), then falls on."""
    n, R, r, e, h = 20, 1.0, 0.1, 0.5, 0.8
    theta = (face + 0.5) * 2 * math.pi / n
    normal = Vector(math.cos(theta), math.sin(theta))
    along = Vector(-normal.y, normal.x)
    hit = normal * (R * math.cos(math.pi / n) + r) + along * 0.02
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    disc = [
        (R * math.cos(2 * math.pi * k / n), R * math.sin(2 * math.pi * k / n)) for k in range(n)
    ]
    w.add_collider(Polygon(disc, restitution=1.0, friction=0.0))
    ball = w.add(Body(Vector(hit.x, hit.y + h), radius=r, restitution=e, friction=0.0))
    while not w.began:
        w.step(1 / 60)
        assert w.t < 1.0, "never met the polygon"
    (ev,) = w.began
    t = math.sqrt(2 * h / G)
    v = Vector(0.0, -G * t)
    v_after = v - normal * ((1 + e) * (v.x * normal.x + v.y * normal.y))
    assert abs(ev.time - t) < 1e-12
    assert abs(ev.normal - normal) < 1e-12
    assert abs(ball.vel - (v_after + Vector(0.0, -G * (w.t - ev.time)))) < 1e-12 * abs(v)


# -- many-sided bodies at rest --------------------------------------------------------------------
@pytest.mark.parametrize("ground", ["plane", "polygon"])
@pytest.mark.parametrize("n", [12, 32])
def test_an_ngon_dropped_on_the_ground_rests_on_its_bottom_face(n: int, ground: str) -> None:
    """A regular n-gon (R = 0.5 m) let go 1 cm above the ground, its bottom face level, lands
    on that face: its lowest point stays within 0.1 mm of the ground (the floor holds a body's
    whole load: engine.exact.soft, HELD_CORNER_STATIC), its centre is then the apothem
    R cos(pi / n) up, to 0.1 mm, and it does not sink or creep: still from 1 s to 3 s."""
    R = 0.5
    apothem = R * math.cos(math.pi / n)
    w = World()
    w.add_force(Gravity((0.0, -G)))
    if ground == "plane":
        w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    else:
        w.add_collider(Polygon.box(8.0, 1.0, center=(0.0, -0.5)))
    body = w.add(
        Body(Vector(0.0, apothem + 0.01), shape=Polygon(ngon(n, R)), mass=2.0, restitution=0.0)
    )

    def lowest() -> float:
        c, s = math.cos(body.angle), math.sin(body.angle)
        return body.pos.y + min(s * v.x + c * v.y for v in body.shape.vertices)

    held = None
    for step in range(180):
        w.step(1 / 60)
        if step >= 15:  # landed (it falls 1 cm in 0.045 s)
            assert abs(lowest()) < 1e-4, f"t = {w.t:.3f}: lowest point at {lowest():.3g} m"
            assert abs(body.pos.y - apothem) < 1e-4
        if step == 59:
            held = (body.pos.x, body.pos.y, body.angle)
    assert held is not None
    assert abs(body.pos.x - held[0]) < 1e-9 and abs(body.pos.y - held[1]) < 1e-9
    assert abs(body.angle - held[2]) < 1e-9
    assert abs(body.angle) < math.pi / n / 10  # on its bottom face, not on an edge's end


# -- the two paths -------------------------------------------------------------------------------
def _random_ngons(rng: np.random.Generator, count: int) -> Polygons:
    """``count`` polygons of 9 to 64 vertices on ellipses (a box among them now and then), at
    uneven angles no nearer than a third of an even share."""
    shapes = []
    for _ in range(count):
        w, h = rng.uniform(0.2, 1.5, 2)
        if rng.random() < 0.2:
            shapes.append([(-w, -h), (w, -h), (w, h), (-w, h)])
            continue
        k = int(rng.integers(9, 65))
        gaps = rng.uniform(1.0, 3.0, k)
        t = rng.uniform(0, 2 * math.pi) + np.cumsum(gaps) / gaps.sum() * 2 * math.pi
        shapes.append([(float(w * math.cos(a)), float(h * math.sin(a))) for a in t])
    return Polygons.of(shapes, rng.choice([0.0, 0.05], count))


@pytest.mark.skipif(not COMPILED, reason="the fast path needs numba (the fast extra)")
@pytest.mark.parametrize("seed", range(4))
def test_many_sided_manifolds_are_the_same_on_both_paths(seed: int) -> None:
    """The loop kernels (polygon_loop, half_plane_polygon_loop) give the numpy twins'
    manifolds for polygons of up to 64 vertices against each other and a floor: counts and
    feature ids exactly, numbers to 1e-12."""
    rng = np.random.default_rng(seed)
    pairs = 60
    a, b = _random_ngons(rng, pairs), _random_ngons(rng, pairs)
    xa = rng.uniform(-1, 1, (pairs, 2))
    xb = xa + rng.uniform(-2.5, 2.5, (pairs, 2))
    qa, qb = rng.uniform(-7, 7, pairs), rng.uniform(-7, 7, pairs)
    want = collide_polygons(a, xa, qa, b, xb, qb, 0.1)
    assert (want.count > 0).sum() > pairs // 4  # many pairs touch
    agree(collide_polygons(a, xa, qa, b, xb, qb, 0.1, fast=True), want)
    floor = HalfPlanes(np.zeros((pairs, 2)), np.tile([0.0, 1.0], (pairs, 1)))
    xb[:, 1] = rng.uniform(0.0, 1.6, pairs)
    want = collide_half_plane_polygon(floor, (0.0, 0.0), 0.0, b, xb, qb, 0.1)
    agree(collide_half_plane_polygon(floor, (0.0, 0.0), 0.0, b, xb, qb, 0.1, fast=True), want)


def _scene(path: str) -> tuple[World, list[Body]]:
    """A 32-gon, a 12-gon, a 64-gon, two boxes and a ball dropped together on a floor beside
    a 20-gon collider, some onto it."""
    w = World(kernels=path)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    w.add_collider(Polygon(ngon(20, 1.0, (3.0, 0.5))))
    bodies = [
        Body(Vector(0.0, 1.0), shape=Polygon(ngon(32, 0.5)), angle=0.3, restitution=0.2),
        Body(Vector(1.2, 1.6), shape=Polygon(ngon(12, 0.4)), mass=0.5, restitution=0.2),
        Body(Vector(3.3, 2.5), shape=Polygon(ngon(64, 0.3)), angle=0.1, restitution=0.2),
        Body(Vector(-1.2, 0.8), shape=Polygon.box(0.6, 0.4), angle=0.5, restitution=0.2),
        Body(Vector(0.1, 2.4), shape=Polygon.box(0.5, 0.5), restitution=0.2),
        Body(Vector(2.6, 3.5), radius=0.2, restitution=0.2),
    ]
    return w, w.add_all(bodies)


@pytest.mark.skipif(not COMPILED, reason="the fast path needs numba (the fast extra)")
def test_a_scene_of_many_sided_bodies_is_the_same_on_both_paths() -> None:
    """A second and a half of the scene on numpy and on the loop kernels: every position, angle and
    velocity the same to 1e-12 (the kernels' promise: engine.kernels)."""
    (wn, numpy_bodies), (wf, fast_bodies) = _scene("numpy"), _scene("fast")
    for _ in range(90):
        wn.step(1 / 60)
        wf.step(1 / 60)
    for p, q in zip(numpy_bodies, fast_bodies, strict=True):
        assert abs(p.pos - q.pos) < 1e-12 and abs(p.vel - q.vel) < 1e-12
        assert abs(p.angle - q.angle) < 1e-12
        assert abs(p.angular_velocity - q.angular_velocity) < 1e-12
    # the scene did something: the bodies fell and met each other and the 20-gon
    assert all(p.pos.y < 1.0 for p in numpy_bodies[1:3])


# -- the numpy path's cost ------------------------------------------------------------------------
def test_boxes_taken_beside_a_32gon_are_padded_only_to_four() -> None:
    """A table that holds a 32-gon pads every row to 32 vertices; the rows of a batch are
    taken padded to their own largest count, so a batch of boxes costs what boxes do, and
    the manifolds are the same as from the 32-wide rows."""
    table = Polygons.of([ngon(4, 0.7), ngon(32, 0.5), ngon(4, 0.4)])
    assert table.vertices.shape[1] == 32
    boxes = table.take(np.array([0, 2]))
    assert boxes.vertices.shape == (2, 4, 2) and boxes.normals.shape == (2, 4, 2)
    assert table.take(np.array([2, 1])).vertices.shape[1] == 32

    def wide(rows: list[int]) -> Polygons:  # the rows as the table holds them, 32 wide
        return Polygons(
            table.vertices[rows], table.normals[rows], table.count[rows], table.radius[rows]
        )

    x, q = np.array([[0.0, 0.0], [0.7, 0.3]]), np.array([0.0, 0.2])
    got = collide_polygons(boxes, x[0], q[0], table.take(np.array([2, 0])), x[1], q[1])
    want = collide_polygons(wide([0, 2]), x[0], q[0], wide([2, 0]), x[1], q[1])
    assert wide([0, 2]).vertices.shape[1] == 32
    assert np.array_equal(got.count, want.count) and got.count.sum() > 0
    assert np.array_equal(got.separation, want.separation)
    assert np.array_equal(got.point, want.point)
