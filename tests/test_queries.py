"""Queries (engine.queries): point, segment, box and shape queries with filters, against the
closed-form geometry of discs, segments and planes."""

from __future__ import annotations

import math

import pytest

from engine import Body, Box, Circle, Filter, Plane, Segment, Vector, World


def disc(world: World, x: float, y: float, r: float, **kw) -> Body:
    return world.add(Body(Vector(x, y), Vector(0, 0), Vector(0, 0), radius=r, **kw))


def test_point_query_on_a_body_gives_the_near_side_of_its_surface() -> None:
    # pymunk's testPointQuery: a disc of radius 10 at (19, 0) asked at (23, 0).
    w = World()
    b = disc(w, 19, 0, 10)
    (hit,) = w.point_query((23, 0))
    assert hit.shape is b and hit.point == Vector(29, 0) and hit.normal == Vector(1, 0)
    assert hit.distance == -6
    (hit,) = w.point_query((30, 0), 10)
    assert hit.point == Vector(29, 0) and hit.distance == 1


def test_point_query_nearest_and_filters() -> None:
    w = World()
    near = disc(w, 0, 0, 1, filter=Filter(categories=0b01))
    far = disc(w, 5, 0, 1, filter=Filter(categories=0b10))
    assert w.point_query_nearest((2.5, 0), 3).shape is near  # type: ignore[union-attr]
    hit = w.point_query_nearest((2.5, 0), 3, filter=Filter(mask=0b10))
    assert hit is not None and hit.shape is far
    assert w.point_query_nearest((2.5, 0), 1.0) is None
    assert w.point_query_nearest((2.5, 0), 1.5, filter=Filter(group=1)) is not None


def test_segment_query_lists_every_hit_in_order() -> None:
    # pymunk's testSegmentQuery: discs of radius 10 at (0, 0) and (19, 0), a ray from
    # (-13, 0) to (131, 0): hits at x = -10 (fraction 3/144) and x = 9 (22/144).
    w = World()
    s1 = disc(w, 19, 0, 10)
    s2 = disc(w, 0, 0, 10)
    hits = w.segment_query((-13, 0), (131, 0))
    assert [h.shape for h in hits] == [s2, s1]
    assert hits[0].point == Vector(-10, 0) and hits[0].normal == Vector(-1, 0)
    assert hits[1].point == Vector(9, 0) and hits[1].normal == Vector(-1, 0)
    assert hits[0].fraction == pytest.approx(3 / 144, rel=1e-14)
    assert hits[1].fraction == pytest.approx(22 / 144, rel=1e-14)
    assert w.segment_query((-13, 50), (131, 50)) == []


def test_a_ray_along_a_thin_segments_axis_meets_its_end_facing_back() -> None:
    # The end of a segment of no thickness is a point: the normal there faces the ray.
    w = World()
    wall = w.add_collider(Segment((0, 0), (2, 0)))
    for a, b, point, normal in [
        ((-1, 0), (3, 0), (0, 0), (-1, 0)),
        ((3, 0), (-1, 0), (2, 0), (1, 0)),
    ]:
        hit = w.segment_query_first(a, b)
        assert hit is not None and hit.shape is wall
        assert hit.point == Vector(*point) and hit.normal == Vector(*normal)
        assert all(math.isfinite(c) for c in hit.normal)
    # With a radius it meets the round end of the swept disc's reach.
    hit = w.segment_query_first((-1, 0), (3, 0), radius=0.5)
    assert hit is not None and hit.fraction == pytest.approx(0.125) and hit.normal == Vector(-1, 0)


def test_a_query_that_starts_inside_a_shape_meets_it_at_once_with_no_normal() -> None:
    w = World()
    peg = w.add_collider(Circle((0, 0), 1))
    hit = w.segment_query_first((0.5, 0), (5, 0))
    assert hit is not None and hit.shape is peg and hit.fraction == 0.0
    assert hit.normal == Vector(0, 0) and hit.point == Vector(0.5, 0)


def test_bb_query_finds_what_overlaps_the_box() -> None:
    w = World()
    s1 = disc(w, 19, 0, 10)
    s2 = disc(w, 0, 0, 10)
    assert w.bb_query((-7, -7, 7, 7)) == [s2]
    assert set(map(id, w.bb_query((-7, -7, 9.5, 7)))) == {id(s1), id(s2)}
    floor = w.add_collider(Plane((0, -20), (0, 1)))
    wall = w.add_collider(Segment((40, -5), (40, 5), radius=1))
    room = w.add_collider(Box((-50, -50), (50, 50)))
    assert w.bb_query((38.5, 6.5, 39.5, 7)) == []  # beyond the capsule's round end
    assert w.bb_query((38.5, 5.5, 39.5, 7)) == [wall]
    assert w.bb_query((-1, -25, 1, -21)) == [floor]
    assert w.bb_query((45, 45, 60, 60)) == [room]
    with pytest.raises(ValueError, match="bb"):
        w.bb_query((1, 0, 0, 1))


def test_shape_query_measures_each_overlap() -> None:
    w = World()
    b = disc(w, 20, 0, 10)
    wall = w.add_collider(Segment((-5, 3), (5, 3)))
    hits = w.shape_query(Circle((20, 1), 2))
    assert [h.shape for h in hits] == [b] and hits[0].distance == pytest.approx(-11)
    # A capsule across the wall's middle overlaps it by its whole radius.
    hits = w.shape_query(Segment((0, 0), (0, 6), radius=0.5))
    assert [h.shape for h in hits] == [wall] and hits[0].distance == pytest.approx(-0.5)
    assert w.shape_query(Circle((0, 10), 1)) == []
    with pytest.raises(TypeError, match="shape"):
        w.shape_query("circle")


def test_queries_see_sensors_unless_the_filter_leaves_them_out() -> None:
    w = World()
    cup = w.add_collider(Circle((0, 0), 10, sensor=True, filter=Filter(categories=0b100)))
    assert [h.shape for h in w.point_query((0, 0), 100)] == [cup]
    assert w.bb_query((0, 0, 10, 10)) == [cup]
    assert [h.shape for h in w.segment_query((-20, 0), (20, 0), 1)] == [cup]
    assert [h.shape for h in w.shape_query(Circle((0, 0), 200))] == [cup]
    solid_only = Filter(mask=0b011)
    assert w.point_query((0, 0), 100, filter=solid_only) == []
    assert w.bb_query((0, 0, 10, 10), filter=solid_only) == []
    with pytest.raises(TypeError, match="filter"):
        w.point_query((0, 0), 1, filter=3)  # type: ignore[arg-type]
