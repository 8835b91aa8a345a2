"""Queries: what lies at a point, along a segment, in a box, or under a shape (pymunk's
``point_query``, ``segment_query``, ``bb_query`` and ``shape_query``).

Every query looks at the World's bodies (discs of their radius, points of radius 0, or the
shape a body was given, placed at its position) and
its colliders, sensors included (as pymunk 7's do), and takes an optional
:class:`engine.Filter`: a shape is seen only when the query's filter and the shape's collide
(the same group, or categories outside the other's mask, hide it).

A segment query sweeps a disc of ``radius`` (0: a ray) from ``start`` to ``end``. Against a
disc of radius R at c, the swept centre x(t) = a + (b - a) t touches it when
|x(t) - c| = R + radius, the smaller root of

    |b - a|^2 t^2 + 2 (a - c).(b - a) t + |a - c|^2 - (R + radius)^2 = 0,

and against a flat face at distance rho from its line (normal n), where
n.(x(t) - p) = rho + radius, a linear equation. A query that starts inside a shape meets it
at fraction 0 with a zero normal (as pymunk's does). ``QueryHit.point`` is the swept centre
at the hit (for a ray, the point on the surface).

>>> from engine import Circle, World
>>> world = World()
>>> peg = world.add_collider(Circle((10, 0), 1))
>>> hit = world.segment_query_first((0, 0), (20, 0))
>>> hit.point, hit.normal, hit.fraction
(Vector(9.0, 0.0), Vector(-1.0, 0.0), 0.45)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from . import checks
from .colliders import Box, Circle, Collider, Plane, Polygon, Segment, point_of
from .filters import DEFAULT, Filter
from .vector import Vector

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = [
    "QueryHit",
    "point_query",
    "segment_query",
    "bb_query",
    "shape_query",
]


@dataclass(frozen=True)
class QueryHit:
    """What a query found: the shape (a Body or a Collider), the point, the normal there,
    and ``fraction`` (0 to 1 along a segment query) or ``distance`` (a point or shape query:
    length units from the shape's surface, < 0 inside, the depth of an overlap)."""

    shape: Any
    point: Vector
    normal: Vector
    fraction: float = 0.0
    distance: float = 0.0


def _filter(value: Any) -> Filter:
    if value is None:
        return DEFAULT
    if not isinstance(value, Filter):
        raise TypeError(
            f"filter must be an engine.Filter (group, categories, mask) or None, got "
            f"{type(value).__name__} {value!r}"
        )
    return value


def _bodies_seen(state: WorldState, f: Filter) -> np.ndarray:
    """Rows of the World's 2D bodies that the filter f sees."""
    store = state.store
    if store is None or store.dim != 2 or not len(store):
        return np.zeros(0, dtype=np.intp)
    rows = np.arange(len(store))
    if f is DEFAULT:
        return rows
    g, c, m = store.group, store.categories, store.mask
    ok = ((c & f.mask) != 0) & ((f.categories & m) != 0)
    if f.group:
        ok &= g != f.group
    return rows[ok]


def _shaped(state: WorldState, rows: np.ndarray) -> tuple[np.ndarray, list[tuple[int, Any]]]:
    """Split body rows into those that are discs (or points) and [(row, shape)] of bodies
    with a shape other than a circle about their position (a box, a polygon, a capsule),
    which a query meets as that shape placed at the body's position."""
    store = state.store
    shapes = [] if store is None else store.shapes
    if not any(s is not None for s in shapes):  # only discs and points: the usual World
        return rows, []
    shaped = [
        (k, shape)
        for k in rows.tolist()
        if (shape := shapes[k]) is not None and not isinstance(shape, Circle)
    ]
    if not shaped:
        return rows, []
    out = {k for k, _ in shaped}
    return np.array([k for k in rows.tolist() if k not in out], dtype=np.intp), shaped


class _Frame:
    """A body's frame (``engine.body.CORNERS_TURN``: a box that turned): its position and
    angle, to take a query into the frame its shape is given in and the answers back out."""

    def __init__(self, store: Any, k: int) -> None:
        self.cx, self.cy = float(store.x[k, 0]), float(store.x[k, 1])
        angle = float(store.angle[k]) if len(store.angle) > k else 0.0
        self.c, self.s = math.cos(angle), math.sin(angle)

    def into(self, p: tuple[float, float]) -> tuple[float, float]:
        """A world point in the body's frame."""
        dx, dy = p[0] - self.cx, p[1] - self.cy
        if self.s == 0.0:
            return dx, dy
        return self.c * dx + self.s * dy, -self.s * dx + self.c * dy

    def turn_in(self, v: tuple[float, float]) -> tuple[float, float]:
        """A world direction in the body's frame."""
        if self.s == 0.0:
            return v
        return self.c * v[0] + self.s * v[1], -self.s * v[0] + self.c * v[1]

    def turn_out(self, v: Vector) -> Vector:
        """A direction of the body's frame in the world's."""
        if self.s == 0.0:
            return v
        return Vector(self.c * v.x - self.s * v.y, self.s * v.x + self.c * v.y)

    def out(self, p: Vector) -> Vector:
        """A point of the body's frame in the world's."""
        return self.turn_out(p) + Vector(self.cx, self.cy)

    def placed(self, shape: Any) -> Collider:
        """The body's shape (a Polygon or a Segment) placed in the world as it stands."""
        if isinstance(shape, Segment):
            return Segment(tuple(self.out(shape.a)), tuple(self.out(shape.b)), shape.radius)
        return Polygon([tuple(self.out(v)) for v in shape.vertices], shape.radius)


def _colliders_seen(state: WorldState, f: Filter) -> list[Collider]:
    return [c for c in state.colliders if f is DEFAULT or f.collides(c.filter)]


def _unit_or_zero(x: float, y: float) -> Vector:
    m = max(abs(x), abs(y))
    if m == 0.0:
        return Vector(0.0, 0.0)
    x, y = x / m, y / m
    length = math.hypot(x, y)
    return Vector(x / length, y / length)


# -- point queries -----------------------------------------------------------------------------
def point_query(state: WorldState, point: Any, max_distance: Any, filter: Any) -> list[QueryHit]:  # noqa: A002
    """Shapes whose surface lies within ``max_distance`` of ``point``, nearest first: each
    hit's ``point`` is the nearest point of the shape's surface, ``normal`` the unit normal
    there pointing away from the shape's solid (toward ``point`` when outside), ``distance``
    from the surface (< 0 inside)."""
    px, py = point_of(point, "point")
    reach = checks.real(max_distance, "max_distance", nonneg=True)
    f = _filter(filter)
    store = state.store
    hits: list[QueryHit] = []
    rows, shaped = _shaped(state, _bodies_seen(state, f))
    for k, shape in shaped:
        assert store is not None
        fr = _Frame(store, k)
        surface, n, d = shape.closest(fr.into((px, py)))  # in the body's frame
        if d <= reach:
            hits.append(QueryHit(state.bodies[k], fr.out(surface), fr.turn_out(n), 0.0, d))
    if len(rows):
        assert store is not None
        x, r = store.x[rows], store.radius[rows]
        dx, dy = px - x[:, 0], py - x[:, 1]
        dist = np.hypot(dx, dy)
        gap = dist - r
        for k in np.flatnonzero(gap <= reach).tolist():
            n = _unit_or_zero(float(dx[k]), float(dy[k]))
            if n == Vector(0.0, 0.0):
                n = Vector(0.0, 1.0)  # at the centre itself: up, as pymunk
            cx, cy = float(x[k, 0]), float(x[k, 1])
            surface = Vector(cx + n.x * float(r[k]), cy + n.y * float(r[k]))
            hits.append(QueryHit(state.bodies[int(rows[k])], surface, n, 0.0, float(gap[k])))
    for c in _colliders_seen(state, f):
        surface, n, d = c.closest((px, py))
        if d <= reach:
            hits.append(QueryHit(c, surface, n, 0.0, d))
    hits.sort(key=lambda h: h.distance)
    return hits


# -- segment queries ---------------------------------------------------------------------------
def _ray_disc(a: tuple[float, float], v: tuple[float, float], c: np.ndarray, R: np.ndarray):
    """First fraction t in [0, 1] at which a + v t comes within R of each centre c (N, 2):
    (t or inf, inside at the start)."""
    dx, dy = a[0] - c[:, 0], a[1] - c[:, 1]
    vv = v[0] * v[0] + v[1] * v[1]
    b = dx * v[0] + dy * v[1]  # half the linear coefficient
    k = np.hypot(dx, dy)
    inside = k <= R
    cc = (k - R) * (k + R)  # |a - c|^2 - R^2 without squaring huge or tiny numbers first
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        disc = b * b - vv * cc
        root = np.sqrt(np.maximum(disc, 0.0))
        # The smaller root, in the form that does not cancel: t = cc / (-b + sqrt(disc)).
        t = cc / (root - b)
    ok = (disc >= 0.0) & (b < 0.0) & (t >= 0.0) & (t <= 1.0) & ~inside
    return np.where(ok, t, np.inf), inside


def segment_query(
    state: WorldState,
    start: Any,
    end: Any,
    radius: Any,
    filter: Any,  # noqa: A002
) -> list[QueryHit]:
    """Every shape a segment from ``start`` to ``end`` meets (a disc of ``radius`` swept
    along it), each at its first touch, in the order met (``fraction`` 0 to 1)."""
    a = point_of(start, "start")
    b = point_of(end, "end")
    q = checks.real(radius, "radius", nonneg=True)
    f = _filter(filter)
    v = (b[0] - a[0], b[1] - a[1])
    back = _unit_or_zero(-v[0], -v[1])
    hits: list[QueryHit] = []

    def hit_at(shape: Any, t: float, normal: Vector) -> None:
        point = Vector(a[0] + v[0] * t, a[1] + v[1] * t) if t > 0.0 else Vector(*a)
        hits.append(QueryHit(shape, point, normal, fraction=t))

    rows, shaped = _shaped(state, _bodies_seen(state, f))
    for k, shape in shaped:
        store = state.store
        assert store is not None
        fr = _Frame(store, k)
        bk = fr.turn_in((back.x, back.y))
        found = _collider_hit(shape, fr.into(a), fr.turn_in(v), q, Vector(*bk))  # body's frame
        if found is not None:
            hit_at(state.bodies[k], found[0], fr.turn_out(found[1]))
    if len(rows):
        store = state.store
        assert store is not None
        c, R = store.x[rows], store.radius[rows] + q
        t, inside = _ray_disc(a, v, c, R)
        for k in np.flatnonzero(inside).tolist():
            hit_at(state.bodies[int(rows[k])], 0.0, Vector(0.0, 0.0))
        for k in np.flatnonzero(np.isfinite(t)).tolist():
            tk = float(t[k])
            x = (a[0] + v[0] * tk - float(c[k, 0]), a[1] + v[1] * tk - float(c[k, 1]))
            n = _unit_or_zero(*x)
            hit_at(state.bodies[int(rows[k])], tk, n if n != Vector(0.0, 0.0) else back)
    for col in _colliders_seen(state, f):
        found = _collider_hit(col, a, v, q, back)
        if found is not None:
            hit_at(col, *found)
    hits.sort(key=lambda h: h.fraction)
    return hits


def _collider_hit(
    c: Collider, a: tuple[float, float], v: tuple[float, float], q: float, back: Vector
) -> tuple[float, Vector] | None:
    """(fraction, normal) where a disc of radius q swept from a along v first touches the
    collider c, or None; (0, zero) when it starts overlapping c's solid."""
    if c.distance(a) < q:
        return 0.0, Vector(0.0, 0.0)
    best: tuple[float, Vector] | None = None
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
        u = -x[0] * n[1] + x[1] * n[0]  # along the tangent (-n_y, n_x)
        if lo <= u <= hi and (best is None or t < best[0]):
            best = (t, Vector(s * n[0], s * n[1]))
    for centre, rho in c.discs():
        t_arr, _ = _ray_disc(a, v, np.array([centre], dtype=float), np.array([rho + q]))
        t = float(t_arr[0])
        if math.isfinite(t) and (best is None or t < best[0]):
            x = (a[0] + v[0] * t - centre[0], a[1] + v[1] * t - centre[1])
            n = _unit_or_zero(*x)
            best = (t, n if n != Vector(0.0, 0.0) else back)  # a ray onto a point: face back
    return best


# -- box and shape queries -----------------------------------------------------------------------
def _bb(value: Any) -> tuple[float, float, float, float]:
    try:
        x0, y0, x1, y1 = (float(c) for c in value)
    except (TypeError, ValueError):
        raise TypeError(
            f"bb must be (left, bottom, right, top), four numbers, got {value!r}"
        ) from None
    if not all(math.isfinite(c) for c in (x0, y0, x1, y1)):
        raise ValueError(f"bb must be finite (no nan or inf), got {value!r}")
    if not (x0 <= x1 and y0 <= y1):
        raise ValueError(f"bb must have left <= right and bottom <= top, got {value!r}")
    return x0, y0, x1, y1


def _box_distance(bb: tuple[float, float, float, float], x: float, y: float) -> float:
    """Distance from (x, y) to the rectangle bb (0 inside)."""
    x0, y0, x1, y1 = bb
    return math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1))


def bb_query(state: WorldState, bb: Any, filter: Any) -> list[Any]:  # noqa: A002
    """The shapes (Bodies and colliders) that overlap the box ``bb`` = (left, bottom, right,
    top), in the World's order: bodies first, then colliders."""
    box = _bb(bb)
    f = _filter(filter)
    out: list[Any] = []
    seen, shaped = _shaped(state, _bodies_seen(state, f))
    store = state.store
    found = np.zeros(0, dtype=np.intp)
    if len(seen):
        assert store is not None
        x, r = store.x[seen], store.radius[seen]
        x0, y0, x1, y1 = box
        dx = np.maximum(np.maximum(x0 - x[:, 0], x[:, 0] - x1), 0.0)
        dy = np.maximum(np.maximum(y0 - x[:, 1], x[:, 1] - y1), 0.0)
        found = seen[np.hypot(dx, dy) <= r]
    if shaped:
        assert store is not None
        more = []
        for k, shape in shaped:
            fr = _Frame(store, k)
            if fr.s != 0.0:
                # A shape that turned: placed in the world as it stands, then met as a collider.
                if _collider_overlaps_box(fr.placed(shape), box):
                    more.append(k)
                continue
            cx, cy = fr.cx, fr.cy
            if _collider_overlaps_box(shape, (box[0] - cx, box[1] - cy, box[2] - cx, box[3] - cy)):
                more.append(k)
        found = np.sort(np.concatenate([found, np.array(more, dtype=np.intp)]))
    out += [state.bodies[int(k)] for k in found]
    for c in _colliders_seen(state, f):
        if _collider_overlaps_box(c, box):
            out.append(c)
    return out


def _collider_overlaps_box(c: Collider, bb: tuple[float, float, float, float]) -> bool:
    x0, y0, x1, y1 = bb
    corners = ((x0, y0), (x1, y0), (x1, y1), (x0, y1))
    if isinstance(c, Circle):
        return _box_distance(bb, c.center.x, c.center.y) <= c.radius
    if isinstance(c, Plane):
        return min(c.distance(p) for p in corners) <= 0.0
    if isinstance(c, Box):
        return min(c.distance(p) for p in corners) <= 0.0  # a corner in the walls' solid
    if isinstance(c, Segment):
        # The capsule meets the box when the segment comes within its radius of it.
        return _segment_box_distance(c.a, c.b, bb) <= c.radius
    if isinstance(c, Polygon):
        # Two convex shapes meet when an edge of one comes within the rounding of the other,
        # or when one holds the other whole (then a corner of the box is inside).
        verts = c.vertices
        edges = zip(verts, verts[1:] + verts[:1], strict=True)
        if any(_segment_box_distance(p, q, bb) <= c.radius for p, q in edges):
            return True
        return min(c.distance(p) for p in corners) <= 0.0
    return False


def _segment_box_distance(a: Vector, b: Vector, bb: tuple[float, float, float, float]) -> float:
    """Distance between the segment a-b and the rectangle bb (0 when they meet)."""
    x0, y0, x1, y1 = bb
    if _box_distance(bb, a.x, a.y) == 0.0 or _box_distance(bb, b.x, b.y) == 0.0:
        return 0.0
    edges = (((x0, y0), (x1, y0)), ((x1, y0), (x1, y1)), ((x1, y1), (x0, y1)), ((x0, y1), (x0, y0)))
    return min(_segment_distance((a.x, a.y), (b.x, b.y), p, q) for p, q in edges)


def _segment_distance(
    a: tuple[float, float], b: tuple[float, float], c: tuple[float, float], d: tuple[float, float]
) -> float:
    """Distance between the segments a-b and c-d (0 when they cross)."""

    def cross(o: tuple[float, float], p: tuple[float, float], q: tuple[float, float]) -> float:
        return (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])

    d1, d2 = cross(c, d, a), cross(c, d, b)
    d3, d4 = cross(a, b, c), cross(a, b, d)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and d1 and d2 and d3 and d4:
        return 0.0
    return min(
        _point_segment(a, c, d),
        _point_segment(b, c, d),
        _point_segment(c, a, b),
        _point_segment(d, a, b),
    )


def _point_segment(p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    ll = dx * dx + dy * dy
    u = 0.0 if ll == 0.0 else min(1.0, max(0.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll))
    return math.hypot(p[0] - a[0] - u * dx, p[1] - a[1] - u * dy)


def shape_query(state: WorldState, shape: Any, filter: Any) -> list[QueryHit]:  # noqa: A002
    """The shapes that a query shape overlaps, deepest first: ``shape`` is a ``Circle`` or a
    ``Segment`` (a capsule) placed where it is asked about, not added to the World. Each hit:
    the shape found, the deepest point of its surface toward the query shape, the unit normal
    there (out of the shape found, toward the query shape), and ``distance`` < 0, the depth."""
    if not isinstance(shape, (Circle, Segment)):
        raise TypeError(
            f"shape must be an engine.Circle or engine.Segment to query with, got "
            f"{type(shape).__name__} {shape!r}"
        )
    f = _filter(filter)
    if isinstance(shape, Circle):
        a = b = (shape.center.x, shape.center.y)
    else:
        a, b = (shape.a.x, shape.a.y), (shape.b.x, shape.b.y)
    q = shape.radius
    hits: list[QueryHit] = []
    rows, shaped = _shaped(state, _bodies_seen(state, f))
    store = state.store
    for k, body_shape in shaped:
        assert store is not None
        fr = _Frame(store, k)
        found = _collider_depth(body_shape, fr.into(a), fr.into(b), q)  # the body's frame
        if found is not None:
            point = fr.out(found[0])
            hits.append(QueryHit(state.bodies[k], point, fr.turn_out(found[1]), 0.0, found[2]))
    for k in rows.tolist():
        assert store is not None
        cx, cy = float(store.x[k, 0]), float(store.x[k, 1])
        r = float(store.radius[k])
        # The query shape's core point nearest the centre, then the gap between the discs.
        near = _nearest_on_segment((cx, cy), a, b)
        n = _unit_or_zero(near[0] - cx, near[1] - cy)
        if n == Vector(0.0, 0.0):
            n = Vector(0.0, 1.0)
        gap = math.hypot(near[0] - cx, near[1] - cy) - r - q
        if gap < 0.0:
            hits.append(QueryHit(state.bodies[k], Vector(cx + n.x * r, cy + n.y * r), n, 0.0, gap))
    for c in _colliders_seen(state, f):
        found = _collider_depth(c, a, b, q)
        if found is not None:
            hits.append(QueryHit(c, found[0], found[1], 0.0, found[2]))
    hits.sort(key=lambda h: h.distance)
    return hits


def _nearest_on_segment(
    p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]
) -> tuple[float, float]:
    dx, dy = b[0] - a[0], b[1] - a[1]
    ll = dx * dx + dy * dy
    u = 0.0 if ll == 0.0 else min(1.0, max(0.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll))
    return a[0] + u * dx, a[1] + u * dy


def _collider_depth(
    c: Collider, a: tuple[float, float], b: tuple[float, float], q: float
) -> tuple[Vector, Vector, float] | None:
    """(surface point, normal, signed gap < 0) of the deepest overlap between the capsule
    a-b of radius q and the collider c, or None when they do not overlap.

    The collider's distance along the capsule's core is smallest at one of a few points: an
    end of the core (a plane's distance is linear along it, a room's the least of four
    linear ones), the core point nearest a circle's centre, or the core point nearest a
    segment (where the two cross, if they do)."""
    samples = [a, b]
    if isinstance(c, Circle):
        samples.append(_nearest_on_segment((c.center.x, c.center.y), a, b))
    elif isinstance(c, Segment):
        samples.append(_closest_on_first(a, b, (c.a.x, c.a.y), (c.b.x, c.b.y)))
    elif isinstance(c, Polygon):
        samples.append(_deepest_on_core(c, a, b))
    best: tuple[Vector, Vector, float] | None = None
    for s in samples:
        surface, normal, d = c.closest(s)
        gap = d - q
        if gap < 0.0 and (best is None or gap < best[2]):
            best = (surface, normal, gap)
    return best


def _deepest_on_core(
    c: Collider, a: tuple[float, float], b: tuple[float, float]
) -> tuple[float, float]:
    """The point of the core a-b where a convex collider's signed distance is least.

    The signed distance to a convex solid is a convex function of the point, so along the
    core it has one minimum: golden-section search finds it (each round keeps 0.618 of the
    interval; 80 rounds shrink it below 1e-16 of the core's length)."""
    dx, dy = b[0] - a[0], b[1] - a[1]

    def at(u: float) -> float:
        return c.distance((a[0] + u * dx, a[1] + u * dy))

    lo, hi = 0.0, 1.0
    g = (math.sqrt(5.0) - 1.0) / 2.0
    u1, u2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = at(u1), at(u2)
    for _ in range(80):
        if f1 <= f2:
            hi, u2, f2 = u2, u1, f1
            u1 = hi - g * (hi - lo)
            f1 = at(u1)
        else:
            lo, u1, f1 = u1, u2, f2
            u2 = lo + g * (hi - lo)
            f2 = at(u2)
    u = 0.5 * (lo + hi)
    return a[0] + u * dx, a[1] + u * dy


def _closest_on_first(
    a: tuple[float, float], b: tuple[float, float], c: tuple[float, float], d: tuple[float, float]
) -> tuple[float, float]:
    """The point of segment a-b nearest segment c-d (where they cross, if they do)."""
    ux, uy = b[0] - a[0], b[1] - a[1]
    vx, vy = d[0] - c[0], d[1] - c[1]
    den = ux * vy - uy * vx
    if den != 0.0:
        # Where the lines cross: a + u s = c + v t.
        wx, wy = c[0] - a[0], c[1] - a[1]
        s = (wx * vy - wy * vx) / den
        t = (wx * uy - wy * ux) / den
        if 0.0 <= s <= 1.0 and 0.0 <= t <= 1.0:
            return a[0] + ux * s, a[1] + uy * s
    # Else the nearest pair has an end of one of them: try the four.
    options = [a, b, _nearest_on_segment(c, a, b), _nearest_on_segment(d, a, b)]
    return min(options, key=lambda p: _point_segment(p, c, d))
