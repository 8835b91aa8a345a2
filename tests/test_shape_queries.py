"""Queries meet a body's shape (a box, a polygon, a capsule) where it is, not its bounding circle.

Each expected number is worked out by hand from the shape's geometry: a 2 m box at (3, 1)
spans x 2..4, y 0..2; a capsule from (-1, 0) to (1, 0) with radius 0.25 at (0, 5).
"""

from __future__ import annotations

import math

import pytest

from engine import Body, Circle, Filter, Polygon, Segment, Vector, World


@pytest.fixture
def world() -> tuple[World, Body, Body, Body]:
    w = World()
    box = w.add(Body(Vector(3.0, 1.0), shape=Polygon.box(2.0, 2.0)))
    capsule = w.add(Body(Vector(0.0, 5.0), shape=Segment((-1.0, 0.0), (1.0, 0.0), 0.25)))
    ball = w.add(Body(Vector(-4.0, 1.0), radius=0.5))
    return w, box, capsule, ball


def test_a_point_query_measures_from_the_shapes_surface(world) -> None:
    w, box, capsule, _ = world
    # Beside the box's corner circle of radius sqrt(2) (it reaches x = 4.41) but outside
    # the box: 0.3 m from its right face.
    assert w.point_query((4.3, 1.0), 0.0, Filter()) == []
    (hit,) = w.point_query((4.3, 1.0), 0.5, Filter())
    assert hit.shape is box and hit.point == Vector(4.0, 1.0) and hit.normal == Vector(1.0, 0.0)
    assert hit.distance == pytest.approx(0.3, abs=1e-12)
    # Inside, 0.25 m under its top face: the nearest surface point is on that face.
    (hit,) = w.point_query((3.1, 1.75), 0.0, Filter())
    assert hit.point == Vector(3.1, 2.0) and hit.distance == pytest.approx(-0.25, abs=1e-12)
    # Above the capsule's core: 0.25 m over its round top.
    (hit,) = w.point_query((0.5, 5.5), 0.3, Filter())
    assert hit.shape is capsule and hit.point == Vector(0.5, 5.25)
    assert hit.distance == pytest.approx(0.25, abs=1e-12)


def test_a_segment_query_meets_the_shapes_faces_in_order(world) -> None:
    w, box, capsule, ball = world
    hits = w.segment_query((-10.0, 1.4), (10.0, 1.4))
    assert [h.shape for h in hits] == [ball, box]
    # The ball's circle at y = 1.4: x = -4 - sqrt(0.5^2 - 0.4^2) = -4.3, fraction 5.7 / 20;
    # the box's left face at x = 2: fraction 12 / 20.
    assert hits[0].fraction == pytest.approx(0.285, abs=1e-12)
    assert hits[1].point == Vector(2.0, 1.4) and hits[1].normal == Vector(-1.0, 0.0)
    assert hits[1].fraction == pytest.approx(0.6, abs=1e-12)
    # Straight down through the capsule's end cap at x = 1.1: its round end, radius 0.25
    # about (1, 5), met at y = 5 + sqrt(0.25^2 - 0.1^2).
    first = w.segment_query_first((1.1, 9.0), (1.1, 3.0))
    assert first is not None and first.shape is capsule
    assert first.point.y == pytest.approx(5.0 + math.sqrt(0.25**2 - 0.1**2), abs=1e-12)
    # Past the box's corner, inside its bounding circle: nothing.
    assert w.segment_query((4.2, -1.0), (4.2, 3.0)) == []


def test_box_and_shape_queries_see_the_shape(world) -> None:
    w, box, capsule, _ = world
    assert w.bb_query((4.1, 0.0, 5.0, 2.0)) == []  # right of the box, inside its circle
    assert w.bb_query((3.9, 0.0, 5.0, 2.0)) == [box]
    assert w.bb_query((2.5, 0.5, 3.5, 1.5)) == [box]  # wholly inside it
    assert w.bb_query((-0.5, 5.3, 0.5, 6.0)) == []  # over the capsule, past its radius
    assert w.bb_query((-0.5, 5.2, 0.5, 6.0)) == [capsule]
    # A circle of radius 0.5 at (3, 2.3): 0.2 m deep into the box's top face.
    (hit,) = w.shape_query(Circle((3.0, 2.3), 0.5))
    assert hit.shape is box and hit.normal == Vector(0.0, 1.0)
    assert hit.distance == pytest.approx(-0.2, abs=1e-12) and hit.point == Vector(3.0, 2.0)
    # A thin capsule along y = 1 through the box: deepest at its middle, 1 m in (+ 0.1).
    (hit,) = w.shape_query(Segment((2.5, 1.0), (3.5, 1.0), 0.1))
    assert hit.shape is box and hit.distance == pytest.approx(-1.1, abs=1e-9)
    assert w.shape_query(Circle((4.3, 2.3), 0.1)) == []  # beside the corner


def test_a_box_query_finds_a_polygon_collider() -> None:
    # A static triangle (0, 0), (4, 0), (0, 3): its long edge runs x/4 + y/3 = 1.
    w = World()
    tri = w.add_collider(Polygon([(0.0, 0.0), (4.0, 0.0), (0.0, 3.0)]))
    assert w.bb_query((2.1, 1.6, 3.0, 2.5)) == []  # past the long edge, inside the bounds
    assert w.bb_query((1.9, 1.4, 3.0, 2.5)) == [tri]  # its corner over the edge
    assert w.bb_query((0.5, 0.5, 1.0, 1.0)) == [tri]  # inside
    assert w.bb_query((-5.0, -5.0, 10.0, 10.0)) == [tri]  # around it
