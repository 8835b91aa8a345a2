"""Queries (engine.pipeline.queries): point, segment, box and shape queries with filters, against
the closed-form geometry of discs, segments and planes."""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Body, Box, Circle, Filter, Plane, Polygon, Segment, Vector, World
from engine.filters import DEFAULT
from engine.geometry.query_grid import BodyBins, BodyTable, ColliderGrid, QueryIndex
from engine.pipeline.queries import (
    QueryHit,
    _collider_depth,
    _collider_overlaps_box,
    _Frame,
    _nearest_on_segment,
)


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


# -- the index finds what testing everything finds ----------------------------------------------
# The queries before their index (engine.geometry.query_grid): every body and every collider tested,
# kept here as the reference the indexed queries must match exactly (same hits, same order,
# same points, normals, fractions and distances). The exact tests they share (a collider's
# overlap with a box, a capsule's depth in a shape, a body's frame) are engine.pipeline.queries'
# own.


def _ref_bodies(state: Any, f: Filter) -> tuple[np.ndarray, list[tuple[int, Any]]]:
    """Rows of the 2D bodies the filter sees: (discs and points, [(row, shape)])."""
    store = state.store
    if store is None or store.dim != 2 or not len(store):
        return np.zeros(0, dtype=np.intp), []
    rows = np.arange(len(store))
    if f is not DEFAULT:
        g, c, m = store.group, store.categories, store.mask
        ok = ((c & f.mask) != 0) & ((f.categories & m) != 0)
        if f.group:
            ok &= g != f.group
        rows = rows[ok]
    shapes = store.shapes
    shaped = [
        (k, s) for k in rows.tolist() if (s := shapes[k]) is not None and not isinstance(s, Circle)
    ]
    out = {k for k, _ in shaped}
    return np.array([k for k in rows.tolist() if k not in out], dtype=np.intp), shaped


def _ref_colliders(state: Any, f: Filter) -> list[Any]:
    return [c for c in state.colliders if f is DEFAULT or f.collides(c.filter)]


def _ref_unit_or_zero(x: float, y: float) -> Vector:
    m = max(abs(x), abs(y))
    if m == 0.0:
        return Vector(0.0, 0.0)
    x, y = x / m, y / m
    length = math.hypot(x, y)
    return Vector(x / length, y / length)


def _ref_ray_disc(a: Any, v: Any, c: np.ndarray, R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    dx, dy = a[0] - c[:, 0], a[1] - c[:, 1]
    vv = v[0] * v[0] + v[1] * v[1]
    b = dx * v[0] + dy * v[1]
    k = np.hypot(dx, dy)
    inside = k <= R
    cc = (k - R) * (k + R)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        disc = b * b - vv * cc
        root = np.sqrt(np.maximum(disc, 0.0))
        t = cc / (root - b)
    ok = (disc >= 0.0) & (b < 0.0) & (t >= 0.0) & (t <= 1.0) & ~inside
    return np.where(ok, t, np.inf), inside


def _ref_collider_hit(c: Any, a: Any, v: Any, q: float, back: Vector) -> Any:
    if c.distance(a) < q:
        return 0.0, Vector(0.0, 0.0)
    best = None
    for p, n, rho, two, lo, hi in c.lines():
        d0 = (a[0] - p[0]) * n[0] + (a[1] - p[1]) * n[1]
        s = -1.0 if two and d0 < 0.0 else 1.0
        g0 = s * d0 - rho - q
        g1 = s * (v[0] * n[0] + v[1] * n[1])
        if g1 >= 0.0 or g0 < 0.0:
            continue
        t = -g0 / g1
        if t > 1.0:
            continue
        x = (a[0] + v[0] * t - p[0], a[1] + v[1] * t - p[1])
        u = -x[0] * n[1] + x[1] * n[0]
        if lo <= u <= hi and (best is None or t < best[0]):
            best = (t, Vector(s * n[0], s * n[1]))
    for centre, rho in c.discs():
        t_arr, _ = _ref_ray_disc(a, v, np.array([centre], dtype=float), np.array([rho + q]))
        t = float(t_arr[0])
        if math.isfinite(t) and (best is None or t < best[0]):
            x = (a[0] + v[0] * t - centre[0], a[1] + v[1] * t - centre[1])
            n = _ref_unit_or_zero(*x)
            best = (t, n if n != Vector(0.0, 0.0) else back)
    return best


def ref_segment_query(w: World, start: Any, end: Any, q: float = 0.0, f: Any = None) -> list:
    state, f = w._s, DEFAULT if f is None else f
    a, b = (float(start[0]), float(start[1])), (float(end[0]), float(end[1]))
    v = (b[0] - a[0], b[1] - a[1])
    back = _ref_unit_or_zero(-v[0], -v[1])
    hits: list[QueryHit] = []

    def hit_at(shape: Any, t: float, normal: Vector) -> None:
        point = Vector(a[0] + v[0] * t, a[1] + v[1] * t) if t > 0.0 else Vector(*a)
        hits.append(QueryHit(shape, point, normal, fraction=t))

    rows, shaped = _ref_bodies(state, f)
    store = state.store
    for k, shape in shaped:
        fr = _Frame(store, k)
        bk = fr.turn_in((back.x, back.y))
        found = _ref_collider_hit(shape, fr.into(a), fr.turn_in(v), q, Vector(*bk))
        if found is not None:
            hit_at(state.bodies[k], found[0], fr.turn_out(found[1]))
    if len(rows):
        c, R = store.x[rows], store.radius[rows] + q
        t, inside = _ref_ray_disc(a, v, c, R)
        for k in np.flatnonzero(inside).tolist():
            hit_at(state.bodies[int(rows[k])], 0.0, Vector(0.0, 0.0))
        for k in np.flatnonzero(np.isfinite(t)).tolist():
            tk = float(t[k])
            x = (a[0] + v[0] * tk - float(c[k, 0]), a[1] + v[1] * tk - float(c[k, 1]))
            n = _ref_unit_or_zero(*x)
            hit_at(state.bodies[int(rows[k])], tk, n if n != Vector(0.0, 0.0) else back)
    for col in _ref_colliders(state, f):
        found = _ref_collider_hit(col, a, v, q, back)
        if found is not None:
            hit_at(col, *found)
    hits.sort(key=lambda h: h.fraction)
    return hits


def ref_point_query(w: World, point: Any, reach: float, f: Any = None) -> list:
    state, f = w._s, DEFAULT if f is None else f
    px, py = float(point[0]), float(point[1])
    store = state.store
    hits: list[QueryHit] = []
    rows, shaped = _ref_bodies(state, f)
    for k, shape in shaped:
        fr = _Frame(store, k)
        surface, n, d = shape.closest(fr.into((px, py)))
        if d <= reach:
            hits.append(QueryHit(state.bodies[k], fr.out(surface), fr.turn_out(n), 0.0, d))
    if len(rows):
        x, r = store.x[rows], store.radius[rows]
        dx, dy = px - x[:, 0], py - x[:, 1]
        gap = np.hypot(dx, dy) - r
        for k in np.flatnonzero(gap <= reach).tolist():
            n = _ref_unit_or_zero(float(dx[k]), float(dy[k]))
            if n == Vector(0.0, 0.0):
                n = Vector(0.0, 1.0)
            cx, cy = float(x[k, 0]), float(x[k, 1])
            surface = Vector(cx + n.x * float(r[k]), cy + n.y * float(r[k]))
            hits.append(QueryHit(state.bodies[int(rows[k])], surface, n, 0.0, float(gap[k])))
    for c in _ref_colliders(state, f):
        surface, n, d = c.closest((px, py))
        if d <= reach:
            hits.append(QueryHit(c, surface, n, 0.0, d))
    hits.sort(key=lambda h: h.distance)
    return hits


def ref_bb_query(w: World, box: Any, f: Any = None) -> list:
    state, f = w._s, DEFAULT if f is None else f
    out: list[Any] = []
    seen, shaped = _ref_bodies(state, f)
    store = state.store
    found = np.zeros(0, dtype=np.intp)
    if len(seen):
        x, r = store.x[seen], store.radius[seen]
        x0, y0, x1, y1 = box
        dx = np.maximum(np.maximum(x0 - x[:, 0], x[:, 0] - x1), 0.0)
        dy = np.maximum(np.maximum(y0 - x[:, 1], x[:, 1] - y1), 0.0)
        found = seen[np.hypot(dx, dy) <= r]
    if shaped:
        more = []
        for k, shape in shaped:
            fr = _Frame(store, k)
            if fr.s != 0.0:
                if _collider_overlaps_box(fr.placed(shape), box):
                    more.append(k)
                continue
            cx, cy = fr.cx, fr.cy
            if _collider_overlaps_box(shape, (box[0] - cx, box[1] - cy, box[2] - cx, box[3] - cy)):
                more.append(k)
        found = np.sort(np.concatenate([found, np.array(more, dtype=np.intp)]))
    out += [state.bodies[int(k)] for k in found]
    out += [c for c in _ref_colliders(state, f) if _collider_overlaps_box(c, box)]
    return out


def ref_shape_query(w: World, shape: Any, f: Any = None) -> list:
    state, f = w._s, DEFAULT if f is None else f
    if isinstance(shape, Circle):
        a = b = (shape.center.x, shape.center.y)
    else:
        a, b = (shape.a.x, shape.a.y), (shape.b.x, shape.b.y)
    q = shape.radius
    hits: list[QueryHit] = []
    rows, shaped = _ref_bodies(state, f)
    store = state.store
    for k, body_shape in shaped:
        fr = _Frame(store, k)
        found = _collider_depth(body_shape, fr.into(a), fr.into(b), q)
        if found is not None:
            hits.append(
                QueryHit(state.bodies[k], fr.out(found[0]), fr.turn_out(found[1]), 0.0, found[2])
            )
    for k in rows.tolist():
        cx, cy = float(store.x[k, 0]), float(store.x[k, 1])
        r = float(store.radius[k])
        near = _nearest_on_segment((cx, cy), a, b)
        n = _ref_unit_or_zero(near[0] - cx, near[1] - cy)
        if n == Vector(0.0, 0.0):
            n = Vector(0.0, 1.0)
        gap = math.hypot(near[0] - cx, near[1] - cy) - r - q
        if gap < 0.0:
            hits.append(QueryHit(state.bodies[k], Vector(cx + n.x * r, cy + n.y * r), n, 0.0, gap))
    for c in _ref_colliders(state, f):
        found = _collider_depth(c, a, b, q)
        if found is not None:
            hits.append(QueryHit(c, found[0], found[1], 0.0, found[2]))
    hits.sort(key=lambda h: h.distance)
    return hits


def same_hits(got: list, want: list) -> None:
    """The same hits in the same order: the same objects, and every number to the last bit
    (a normal's -0.0 and 0.0 told apart)."""
    assert [id(h.shape) for h in got] == [id(h.shape) for h in want]
    for g, h in zip(got, want, strict=True):
        for name in ("point", "normal"):
            gv, hv = getattr(g, name), getattr(h, name)
            assert [c.hex() for c in gv] == [c.hex() for c in hv], (name, g, h)
        assert g.fraction.hex() == h.fraction.hex() and g.distance.hex() == h.distance.hex()


# -- random scenes -------------------------------------------------------------------------------
_coord = st.floats(-12.0, 12.0, allow_nan=False, allow_infinity=False)
_size = st.floats(0.05, 3.0)
_FILTERS = [
    DEFAULT,
    Filter(categories=0b01),
    Filter(categories=0b10, mask=0b01),
    Filter(group=1),
    Filter(group=2, categories=0b11, mask=0b10),
]
_filters = st.sampled_from(_FILTERS)


@st.composite
def colliders(draw: st.DrawFn) -> Any:
    kind = draw(
        st.sampled_from(["segment", "capsule", "circle", "polygon", "box", "plane", "room"])
    )
    extra = {"filter": draw(_filters), "sensor": draw(st.booleans())}
    x, y = draw(_coord), draw(_coord)
    if kind in ("segment", "capsule"):
        length = draw(st.sampled_from([0.5, 2.0, 30.0])) * draw(st.floats(0.2, 1.0))
        turn = draw(st.floats(0.0, math.pi))
        b = (x + length * math.cos(turn), y + length * math.sin(turn))
        r = 0.0 if kind == "segment" else draw(_size) / 4
        return Segment((x, y), b, r, **extra)
    if kind == "circle":
        return Circle((x, y), draw(_size), **extra)
    if kind == "polygon":
        n = draw(st.integers(3, 8))
        size, turn = draw(_size), draw(st.floats(0.0, math.pi))
        angles = [turn + 2 * math.pi * i / n for i in range(n)]
        pts = [(x + size * math.cos(t), y + size * math.sin(t)) for t in angles]
        return Polygon(pts, draw(st.sampled_from([0.0, 0.1])), **extra)
    if kind == "box":
        return Polygon.box(draw(_size) * 4, draw(_size), center=(x, y), **extra)
    if kind == "plane":
        turn = draw(st.sampled_from([0.5 * math.pi, draw(st.floats(0.0, 2 * math.pi))]))
        return Plane((x, y - 15.0), (math.cos(turn), math.sin(turn)), **extra)
    return Box((-14.0, -14.0), (14.0, 14.0), **extra)


@st.composite
def body_specs(draw: st.DrawFn) -> dict[str, Any]:
    kind = draw(st.sampled_from(["disc", "point", "box", "capsule", "polygon", "circle"]))
    return {
        "kind": kind,
        "at": (draw(_coord), draw(_coord)),
        "size": draw(_size),
        "angle": draw(st.sampled_from([0.0, draw(st.floats(-math.pi, math.pi))])),
        "filter": draw(_filters),
    }


def make_body(spec: dict[str, Any]) -> Body:
    kind, size = spec["kind"], spec["size"]
    extra: dict[str, Any] = {"filter": spec["filter"]}
    if kind == "disc":
        extra["radius"] = size
    elif kind == "circle":
        extra["shape"] = Circle((0, 0), size)
    elif kind == "box":
        extra["shape"] = Polygon.box(size * 2, size)
    elif kind == "capsule":
        extra["shape"] = Segment((-size, 0.0), (size, 0.0), size / 3)
    elif kind == "polygon":
        extra["shape"] = Polygon([(0.0, 0.0), (size, 0.0), (0.0, 2 * size)])
    if kind in ("box", "capsule", "polygon"):
        extra["angle"] = spec["angle"]
    return Body(Vector(*spec["at"]), **extra)


@contextmanager
def binned_from(count: int) -> Iterator[None]:
    """Bodies binned in cells from ``count`` of them (QueryIndex.FEW_BODIES; 0: always, so
    the random scenes' few bodies take the cells' path too)."""
    kept = QueryIndex.FEW_BODIES
    QueryIndex.FEW_BODIES = count
    try:
        yield
    finally:
        QueryIndex.FEW_BODIES = kept


def make_scene(shapes: list[Any], bodies: list[dict[str, Any]]) -> World:
    w = World()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a body put inside a collider is pushed out
        for c in shapes:
            w.add_collider(c)
        for spec in bodies:
            w.add(make_body(spec))
    return w


@st.composite
def segments(draw: st.DrawFn, w: World | None = None) -> tuple[Any, Any, float]:
    """A query segment: short, long, of no length, or starting at a shape's centre."""
    a = (draw(_coord), draw(_coord))
    how = draw(st.sampled_from(["short", "long", "none", "inside"]))
    if how == "inside" and w is not None and w.bodies:
        a = tuple(draw(st.sampled_from(w.bodies)).pos)
    if how == "none":
        b = a
    else:
        length = 0.13 if how == "short" else draw(st.floats(0.0, 40.0))
        turn = draw(st.floats(0.0, 2 * math.pi))
        b = (a[0] + length * math.cos(turn), a[1] + length * math.sin(turn))
    radius = draw(st.sampled_from([0.0, 0.0, 0.05, draw(_size)]))
    return a, b, radius


def check_every_query(w: World, data: st.DataObject) -> None:
    for _ in range(6):
        a, b, q = data.draw(segments(w))
        f = data.draw(st.sampled_from([None, *_FILTERS]))
        same_hits(w.segment_query(a, b, q, f), ref_segment_query(w, a, b, q, f))
        first = w.segment_query_first(a, b, q, f)
        want = ref_segment_query(w, a, b, q, f)
        same_hits([] if first is None else [first], want[:1])
        p = (data.draw(_coord), data.draw(_coord))
        reach = data.draw(st.sampled_from([0.0, 0.3, 5.0]))
        same_hits(w.point_query(p, reach, f), ref_point_query(w, p, reach, f))
        x0, y0 = data.draw(_coord), data.draw(_coord)
        box = (x0, y0, x0 + data.draw(st.floats(0.0, 10.0)), y0 + data.draw(st.floats(0.0, 3.0)))
        assert [id(s) for s in w.bb_query(box, f)] == [id(s) for s in ref_bb_query(w, box, f)]
        long = math.dist(a, b) > 1e-3
        shape = Segment(a, b, max(q, 0.01)) if long else Circle(a, max(q, 0.01))
        same_hits(w.shape_query(shape, f), ref_shape_query(w, shape, f))


@settings(max_examples=60, deadline=None)
@given(
    shapes=st.lists(colliders(), max_size=14),
    bodies=st.lists(body_specs(), max_size=14),
    data=st.data(),
)
def test_indexed_queries_find_exactly_what_testing_every_shape_finds(
    shapes: list[Any], bodies: list[dict[str, Any]], data: st.DataObject
) -> None:
    # Each scene is asked twice over: the bodies in no cells (a few), then in cells (the
    # first query at their positions tests them all in numpy, the later ones use the cells).
    w = make_scene(shapes, bodies)
    check_every_query(w, data)
    with binned_from(0):
        w._queries = QueryIndex()
        check_every_query(w, data)


@settings(max_examples=15, deadline=None)
@given(
    shapes=st.lists(colliders(), min_size=1, max_size=10),
    bodies=st.lists(body_specs(), min_size=1, max_size=10),
    more=st.lists(colliders(), min_size=1, max_size=4),
    data=st.data(),
)
def test_the_index_follows_colliders_added_and_removed_and_bodies_moved(
    shapes: list[Any],
    bodies: list[dict[str, Any]],
    more: list[Any],
    data: st.DataObject,
) -> None:
    w = make_scene(shapes, bodies)
    with warnings.catch_warnings(), binned_from(data.draw(st.sampled_from([0, 32]))):
        check_every_query(w, data)  # the index is made
        warnings.simplefilter("ignore")
        for c in more:
            w.add_collider(c)
        check_every_query(w, data)
        w.remove_collider(data.draw(st.sampled_from(list(w.colliders))))
        check_every_query(w, data)
        w.bodies[0].pos = Vector(data.draw(_coord), data.draw(_coord))  # moved by hand
        check_every_query(w, data)
        w.add(make_body(data.draw(body_specs())))
        w.remove(w.bodies[0])
        check_every_query(w, data)
        w.step(1 / 60)
        check_every_query(w, data)


@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_a_ray_that_grazes_a_round_face_is_met_as_testing_everything_meets_it(
    data: st.DataObject,
) -> None:
    # A ray passing within rounding of a disc or a thin segment's end: the root of a
    # discriminant that cancels may call it a hit up to ~1e-8 of the ray's length away, and
    # the index must not leave out what the exact test would meet.
    cx, cy = data.draw(_coord), data.draw(_coord)
    r = data.draw(st.sampled_from([0.0, 1e-9, 0.3]))
    w = World()
    if r == 0.0:
        turn = data.draw(st.floats(0.0, 2 * math.pi))
        w.add_collider(Segment((cx, cy), (cx + math.cos(turn), cy + math.sin(turn))))
    else:
        w.add_collider(Circle((cx, cy), r))
        disc(w, cx + 3.0, cy, r)
    turn = data.draw(st.floats(0.0, 2 * math.pi))
    ux, uy = math.cos(turn), math.sin(turn)
    off = r + data.draw(st.sampled_from([0.0, 1e-12, 1e-9, 1e-7, -1e-9]))
    length = data.draw(st.floats(1.0, 50.0))
    for centre in ((cx, cy), (cx + 3.0, cy)):
        # The point of closest approach at the face's edge, the ray from far before it.
        px, py = centre[0] - uy * off, centre[1] + ux * off
        a = (px - ux * length * 0.6, py - uy * length * 0.6)
        b = (px + ux * length * 0.4, py + uy * length * 0.4)
        same_hits(w.segment_query(a, b), ref_segment_query(w, a, b))


def test_a_ray_passing_a_hair_above_a_thin_segments_end_is_met_as_before() -> None:
    # Worked out: the ray from (-10, 1e-7) to (10, 1e-7) over the end (0, 0) of a thin wall
    # down from it has |a - c| = 10 to rounding, so its discriminant is exactly 0: a hit at
    # fraction 0.5, 1e-7 from the wall, that testing everything reports and the index must
    # not lose (its region is grown by 1e-6 of the ray's size for such roots).
    w = World()
    wall = w.add_collider(Segment((0.0, -1.0), (0.0, 0.0)))
    want = ref_segment_query(w, (-10.0, 1e-7), (10.0, 1e-7))
    assert [h.shape for h in want] == [wall] and want[0].fraction == 0.5
    same_hits(w.segment_query((-10.0, 1e-7), (10.0, 1e-7)), want)


def test_a_query_looks_at_the_colliders_and_bodies_near_it_only() -> None:
    # 2,500 pegs in a 50 x 50 m square and as many balls: a 13 cm ray meets one cell's few.
    pegs = [Circle((float(i), float(j)), 0.1) for i in range(50) for j in range(50)]
    grid = ColliderGrid(pegs)
    near = grid.near_segment(20.5, 20.2, 20.5, 20.07, 1e-5)
    assert near == []  # between the pegs
    near = grid.near_segment(20.0, 20.2, 20.0, 20.07, 1e-5)
    assert [pegs[k] for k in near] == [pegs[20 * 50 + 20]]
    # A long diagonal lists the cells along it, not the whole square.
    along = grid.near_segment(0.0, 0.0, 49.0, 49.0, 1e-5)
    assert [pegs[k].center for k in along] == [Vector(i, i) for i in range(50)]
    w = World()
    for i in range(50):
        for j in range(50):
            disc(w, i + 0.5, j + 0.5, 0.1)
    store = w._s.store
    bins = BodyBins(store, BodyTable(store), store.x.tobytes())
    assert bins.near((20.4, 20.3, 20.6, 20.45)) == [20 * 50 + 20]
    assert bins.near((20.0, 20.0, 20.2, 20.2)) == []


@settings(max_examples=200, deadline=None)
@given(
    a=st.tuples(_coord, _coord),
    b=st.tuples(_coord, _coord),
    w=st.sampled_from([0.0, 1e-5, 0.3, 2.0]),
    along=st.floats(0.0, 1.0),
    off=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
)
def test_the_cells_along_a_segment_hold_every_point_near_it(
    a: tuple[float, float],
    b: tuple[float, float],
    w: float,
    along: float,
    off: tuple[float, float],
) -> None:
    # A grid of small cells (pegs 0.5 m apart, h = their size) so that a long segment is
    # taken column by column: a point within w of it, in x and in y, is in a cell listed.
    grid = ColliderGrid(
        [Circle((i * 0.5, j * 0.5), 0.1) for i in range(-30, 31, 3) for j in (-30, 30)]
    )
    px = a[0] + (b[0] - a[0]) * along + w * off[0]
    py = a[1] + (b[1] - a[1]) * along + w * off[1]
    i = math.floor((px - grid.ox) / grid.h)
    j = math.floor((py - grid.oy) / grid.h)
    if 0 <= i < grid.columns and 0 <= j < grid.rows:
        assert i * grid.rows + j in grid.cells_along(*a, *b, w)
