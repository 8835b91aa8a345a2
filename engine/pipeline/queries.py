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

Each query tests exactly only the colliders and bodies near it (``engine.geometry.query_grid``: a
grid of cells over the colliders, made again when they change, and the bodies in cells by
where they are), in the World's order: the answers are those of testing every shape, to the
last bit (tests/test_queries.py keeps the test of every shape as its reference). A query's
few candidates are tested in plain floats (numpy's fixed cost a call, a microsecond or more,
would be most of its time), rounded as numpy rounds them (``_hypot``); more than ``_FEW``
discs in numpy.

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

from .. import checks
from ..filters import DEFAULT, Filter
from ..geometry.colliders import Box, Circle, Collider, Plane, Polygon, Segment, point_of
from ..geometry.query_grid import GROW, ColliderGrid, QueryIndex, bodies_near, margin
from ..vector import Vector, new_unchecked

_new = new_unchecked  # a Vector of two floats, made at C speed

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


#: At most this many candidate discs are tested in plain floats, more in numpy.
_FEW = 8
#: More candidate bodies than this are filtered in numpy.
_MANY = 64

Region = tuple[float, float, float, float]


#: The bodies a query may meet (``_bodies``): [(row, x, y, radius)] of discs and points,
#: and [(row, shape, [x, y])] of bodies with a shape other than a circle about their position
#: (a box, a polygon, a capsule), which a query meets as that shape placed at the body's
#: position; each ascending by row.
Discs = list[tuple[int, float, float, float]]
Shaped = list[tuple[int, Any, list[float]]]


def _bodies(
    state: WorldState, f: Filter, box: Region, index: QueryIndex | None
) -> tuple[Discs, Shaped]:
    """The World's 2D bodies that the filter f sees and whose boxes overlap ``box``
    (``engine.geometry.query_grid``): every body that can meet a query there."""
    store = state.store
    if store is None or store.dim != 2 or not len(store.radius):
        return [], []
    index = QueryIndex() if index is None else index
    table = index.table(store)
    bins = index.bodies(store, table)
    rows = None if bins is None else bins.near(box)
    if bins is None or rows is None:  # unbinned, or a region of many cells: all in numpy
        at = bodies_near(store.x, table.reach_array, box)
        if f is not DEFAULT and len(at):
            ok = ((store.categories[at] & f.mask) != 0) & ((f.categories & store.mask[at]) != 0)
            if f.group:
                ok &= store.group[at] != f.group
            at = at[ok]
        rows = at.tolist()
        if not rows:
            return [], []
        xy = store.x[at].tolist()
    else:
        if not rows:
            return [], []
        if f is not DEFAULT:
            fg, fc, fm = f.group, f.categories, f.mask
            g, c, m = table.group, table.categories, table.mask
            rows = [k for k in rows if c[k] & fm and fc & m[k] and not (fg and g[k] == fg)]
        xy = [bins.xy[k] for k in rows]
    radius = [table.r[k] for k in rows]
    shaped_rows = table.shaped
    if not shaped_rows:
        return [(k, p[0], p[1], r) for k, p, r in zip(rows, xy, radius, strict=True)], []
    shapes = store.shapes
    discs = [
        (k, p[0], p[1], r) for k, p, r in zip(rows, xy, radius, strict=True) if k not in shaped_rows
    ]
    # A body of several shapes (engine.body_shapes) is met part by part: one entry a part,
    # which each query keeps the nearest (deepest, first) of for the body.
    return discs, [
        (k, part, p)
        for k, p in zip(rows, xy, strict=True)
        if k in shaped_rows
        for part in getattr(shapes[k], "parts", (shapes[k],))
    ]


class _Frame:
    """A body's frame (``engine.body.CORNERS_TURN``: a box that turned): its position and
    angle, to take a query into the frame its shape is given in and the answers back out."""

    def __init__(self, store: Any, k: int, at: list[float] | None = None) -> None:
        """The frame of the body in row k of ``store``; ``at``: its position, if known."""
        self.cx, self.cy = (float(store.x[k, 0]), float(store.x[k, 1])) if at is None else at
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
        """The body's shape (a Polygon, a Segment, or a Circle part) placed in the world as it
        stands."""
        if isinstance(shape, Segment):
            return Segment(tuple(self.out(shape.a)), tuple(self.out(shape.b)), shape.radius)
        if isinstance(shape, Circle):  # (a part of a body of several shapes)
            return Circle(tuple(self.out(shape.center)), shape.radius)
        return Polygon([tuple(self.out(v)) for v in shape.vertices], shape.radius)


def _grid(state: WorldState, index: QueryIndex | None) -> ColliderGrid | None:
    """The World's colliders by cell (None: it has none), from ``index`` (None: made now)."""
    contacts = state.contacts
    if contacts is None or not contacts.colliders:
        return None
    if index is None:
        return ColliderGrid(contacts.colliders)
    return index.colliders(contacts.colliders)


def _colliders_seen(grid: ColliderGrid, ks: list[int], f: Filter) -> list[int]:
    """Of the colliders ``ks`` (indices in ``grid``), those the filter f sees."""
    if f is DEFAULT:
        return ks
    cs = grid.colliders
    return [k for k in ks if f.collides(cs[k].filter)]


def _hypot(x: float, y: float) -> float:
    """sqrt(x^2 + y^2) rounded as numpy's ``np.hypot`` rounds it: the C library's hypot,
    which Python's complex ``abs`` calls too (``math.hypot`` rounds otherwise in about one
    case in 700), so a query's answers do not depend on whether numpy or plain floats
    tested its candidates."""
    try:
        return abs(complex(x, y))
    except OverflowError:
        return math.inf


#: The zero vector: the normal of a segment query that starts inside what it meets.
_ZERO = Vector(0.0, 0.0)
#: Up: the normal of a point query at a disc's very centre.
_UP = Vector(0.0, 1.0)


def _unit_or_zero(x: float, y: float) -> Vector:
    m = max(abs(x), abs(y))
    if m == 0.0:
        return Vector(0.0, 0.0)
    x, y = x / m, y / m
    length = math.hypot(x, y)
    return Vector(x / length, y / length)


# -- point queries -----------------------------------------------------------------------------
def point_query(
    state: WorldState,
    point: Any,
    max_distance: Any,
    filter: Any,  # noqa: A002
    index: QueryIndex | None = None,
) -> list[QueryHit]:
    """Shapes whose surface lies within ``max_distance`` of ``point``, nearest first: each
    hit's ``point`` is the nearest point of the shape's surface, ``normal`` the unit normal
    there pointing away from the shape's solid (toward ``point`` when outside), ``distance``
    from the surface (< 0 inside). ``index``: the World's (None: made for this query)."""
    px, py = _point(point, "point")
    reach = max_distance
    if not (type(reach) is float and 0.0 <= reach < math.inf):
        reach = checks.real(max_distance, "max_distance", nonneg=True)
    f = _filter(filter)
    store = state.store
    hits: list[QueryHit] = []
    grow = reach + margin(px, py, px, py, 0.0, reach)
    box = (px - grow, py - grow, px + grow, py + grow)
    discs, shaped = _bodies(state, f, box, index)
    bodies = state.bodies
    nearest: dict[int, QueryHit] = {}  # (a body's nearest part)
    for k, shape, at in shaped:
        assert store is not None
        fr = _Frame(store, k, at)
        surface, n, d = shape.closest(fr.into((px, py)))  # in the body's frame
        if d <= reach and (k not in nearest or d < nearest[k].distance):
            nearest[k] = _hit(bodies[k], fr.out(surface), fr.turn_out(n), 0.0, d)
    hits += nearest.values()
    if discs:
        assert store is not None
        near: list[tuple[int, float, float, float, float, float, float]] = []
        if len(discs) <= _FEW:
            for k, cx, cy, r in discs:
                dx, dy = px - cx, py - cy
                gap = _hypot(dx, dy) - r
                if gap <= reach:
                    near.append((k, dx, dy, cx, cy, r, gap))
        else:
            rows = [d[0] for d in discs]
            ks = np.array(rows, dtype=np.intp)
            x, rs = store.x[ks], store.radius[ks]
            dxs, dys = px - x[:, 0], py - x[:, 1]
            gaps = np.hypot(dxs, dys) - rs
            for i in np.flatnonzero(gaps <= reach).tolist():
                near.append(
                    (
                        rows[i],
                        float(dxs[i]),
                        float(dys[i]),
                        float(x[i, 0]),
                        float(x[i, 1]),
                        float(rs[i]),
                        float(gaps[i]),
                    )
                )
        for k, dx, dy, cx, cy, r, gap in near:
            n = _unit_or_zero(dx, dy)
            if n[0] == 0.0 and n[1] == 0.0:
                n = _UP  # at the centre itself: up, as pymunk
            surface = _new(Vector, (cx + n[0] * r, cy + n[1] * r))
            hits.append(_hit(bodies[k], surface, n, 0.0, gap))
    grid = _grid(state, index)
    if grid is not None:
        colliders = grid.colliders
        for k in grid.near_box(box):
            c = colliders[k]
            if f is DEFAULT or f.collides(c.filter):
                if type(c) is Box:
                    # Box.closest's distance first, without its eight Vectors.
                    (x0, y0), (x1, y1) = c.lower_left, c.upper_right
                    if min(px - x0, x1 - px, py - y0, y1 - py) > reach:
                        continue
                surface, n, d = c.closest((px, py))
                if d <= reach:
                    hits.append(_hit(c, surface, n, 0.0, d))
    hits.sort(key=_distance)
    return hits


def _distance(hit: QueryHit) -> float:
    return hit.distance


_object_new = object.__new__


def _hit(shape: Any, point: Vector, normal: Vector, fraction: float, distance: float) -> QueryHit:
    """``QueryHit(shape, point, normal, fraction, distance)``, made without the frozen
    dataclass's five ``object.__setattr__`` calls (its fields straight into its dict, in
    their order): the same object, a few microseconds sooner."""
    hit = _object_new(QueryHit)
    hit.__dict__.update(
        shape=shape, point=point, normal=normal, fraction=fraction, distance=distance
    )
    return hit  # type: ignore[no-any-return]


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


def _ray_disc_one(
    a: tuple[float, float], v: tuple[float, float], cx: float, cy: float, R: float
) -> tuple[float, bool]:
    """``_ray_disc`` for one disc, in plain floats, to the same last bit."""
    dx, dy = a[0] - cx, a[1] - cy
    vv = v[0] * v[0] + v[1] * v[1]
    b = dx * v[0] + dy * v[1]
    k = _hypot(dx, dy)
    if k <= R:
        return math.inf, True
    if not b < 0.0:
        return math.inf, False
    cc = (k - R) * (k + R)
    disc = b * b - vv * cc
    if not disc >= 0.0:
        return math.inf, False
    t = cc / (math.sqrt(disc) - b)
    return (t, False) if 0.0 <= t <= 1.0 else (math.inf, False)


def segment_query(
    state: WorldState,
    start: Any,
    end: Any,
    radius: Any,
    filter: Any,  # noqa: A002
    index: QueryIndex | None = None,
    first: bool = False,
) -> list[QueryHit]:
    """Every shape a segment from ``start`` to ``end`` meets (a disc of ``radius`` swept
    along it), each at its first touch, in the order met (``fraction`` 0 to 1); with
    ``first``, only the first of them (the first found of those met at once).
    ``index``: the World's (None: made for this query)."""
    a = _point(start, "start")
    b = _point(end, "end")
    q = radius if type(radius) is float and 0.0 <= radius < math.inf else _radius(radius)
    f = _filter(filter)
    met = _segment_hits(state, a, b, q, f, index)
    if first and met:
        met = [min(met, key=_fraction)]  # the first of the least: as the stable sort's
    else:
        met.sort(key=_fraction)
    ax, ay = a
    vx, vy = b[0] - ax, b[1] - ay
    return [
        _hit(shape, _new(Vector, (ax + vx * t, ay + vy * t)) if t > 0.0 else a, n, t, 0.0)
        for t, shape, n in met
    ]


def _fraction(hit: tuple[float, Any, Vector]) -> float:
    return hit[0]


def _point(value: Any, name: str) -> Vector:
    """``value`` as a Vector (``point_of``: a finite 2D point), quickly for a Vector or a
    pair of floats."""
    t = type(value)
    if t is Vector or (t is tuple and len(value) == 2):
        x, y = value
        if type(x) is float and type(y) is float and -math.inf < x < math.inf > y > -math.inf:
            return value if t is Vector else _new(Vector, value)  # type: ignore[no-any-return]
    return _new(Vector, point_of(value, name))  # type: ignore[no-any-return]


def _radius(value: Any) -> float:
    return checks.real(value, "radius", nonneg=True)


def _segment_hits(
    state: WorldState,
    a: tuple[float, float],
    b: tuple[float, float],
    q: float,
    f: Filter,
    index: QueryIndex | None,
) -> list[tuple[float, Any, Vector]]:
    """(fraction, shape, normal) of every shape the disc of radius q swept from a to b meets,
    in the order found: bodies with shapes, bodies it starts in, the other bodies met, then
    colliders, each kind in the World's order (the order ties keep when sorted)."""
    ax, ay = a
    bx, by = b
    v = (bx - ax, by - ay)
    vx, vy = v
    met: list[tuple[float, Any, Vector]] = []
    # The region a hit can be in: the segment grown by the radius and the margin.
    x0, x1 = (ax, bx) if ax <= bx else (bx, ax)
    y0, y1 = (ay, by) if ay <= by else (by, ay)
    # engine.geometry.query_grid.margin, inline (a query's every microsecond counts).
    w = q + GROW * (1.0 + abs(x0) + abs(y0) + abs(x1) + abs(y1) + abs(vx) + abs(vy) + q)
    box = (x0 - w, y0 - w, x1 + w, y1 + w)
    index = QueryIndex() if index is None else index
    discs, shaped = _bodies(state, f, box, index)
    store = state.store
    bodies = state.bodies
    first: dict[int, tuple[float, Any, Vector]] = {}  # (a body's first part met)
    for k, shape, at in shaped:
        assert store is not None
        fr = _Frame(store, k, at)
        back = _unit_or_zero(-vx, -vy)
        bk = fr.turn_in((back.x, back.y))
        # In the body's frame, as a collider is met (its faces, box and pad kept).
        lines, rounds, bounds, pad = index.table(store).looks(shape)
        hit = _collider_hit(
            shape, fr.into(a), fr.turn_in(v), q, Vector(*bk), lines, rounds, bounds, w + pad
        )
        if hit is not None and (k not in first or hit[0] < first[k][0]):
            first[k] = (hit[0], bodies[k], fr.turn_out(hit[1]))
    met += first.values()
    if discs:
        assert store is not None
        inside: list[int] = []
        touched: list[tuple[int, float, float, float]] = []  # (row, t, centre x, centre y)
        if len(discs) <= _FEW:
            for k, cx, cy, r in discs:
                tk, starts_in = _ray_disc_one(a, v, cx, cy, r + q)
                if starts_in:
                    inside.append(k)
                elif tk != math.inf:
                    touched.append((k, tk, cx, cy))
        else:
            rows = [d[0] for d in discs]
            ks = np.array(rows, dtype=np.intp)
            c, R = store.x[ks], store.radius[ks] + q
            t, starts = _ray_disc(a, v, c, R)
            inside = ks[starts].tolist()
            for i in np.flatnonzero(np.isfinite(t)).tolist():
                touched.append((rows[i], float(t[i]), float(c[i, 0]), float(c[i, 1])))
        for k in inside:
            met.append((0.0, bodies[k], _ZERO))
        for k, tk, cx, cy in touched:
            n = _unit_or_zero(ax + vx * tk - cx, ay + vy * tk - cy)
            met.append((tk, bodies[k], n if n != _ZERO else _unit_or_zero(-vx, -vy)))
    grid = _grid(state, index)
    if grid is not None:
        colliders, faces, boxes, pads = grid.colliders, grid.faces, grid.boxes, grid.pads
        for k in grid.near_segment(ax, ay, bx, by, w):
            col = colliders[k]
            if f is DEFAULT or f.collides(col.filter):
                lines, rounds = faces[k]
                hit = _collider_hit(col, a, v, q, None, lines, rounds, boxes[k], w + pads[k])
                if hit is not None:
                    met.append((hit[0], col, hit[1]))
    return met


def _collider_hit(
    c: Collider,
    a: tuple[float, float],
    v: tuple[float, float],
    q: float,
    back: Vector | None,
    lines: list[Any] | None = None,
    discs: list[Any] | None = None,
    box: Region | None = None,
    slack: float = math.inf,
) -> tuple[float, Vector] | None:
    """(fraction, normal) where a disc of radius q swept from a along v first touches the
    collider c, or None; (0, zero) when it starts overlapping c's solid. ``back``: the unit
    vector from b back to a (the normal met by a ray that runs onto a point; None: made
    when needed). ``lines``, ``discs``: c's faces, if known (None: asked of c).

    ``box`` (c's bounds grown) and ``slack`` (q and the margins of the query and of c), if
    known, spare asking c for its distance from a (a dozen operations and two Vectors): a
    farther than slack from the box in x or y, or beyond one of the faces of a convex c by
    more than slack, is farther than q from c's solid, whatever the rounding."""
    ax, ay = a
    vx, vy = v
    if type(c) is Box and box is not None:
        # A room: a segment whose ends lie farther than the slack inside every wall stays
        # inside (the room is convex), beyond q of them all along: it meets nothing.
        (x0, y0), (x1, y1) = c.lower_left, c.upper_right
        bx, by = ax + vx, ay + vy
        if min(ax - x0, x1 - ax, ay - y0, y1 - ay, bx - x0, x1 - bx, by - y0, y1 - by) > slack:
            return None
    best_t = math.inf
    best_n: Vector | None = None
    below = box is None or (
        box[0] - slack <= ax <= box[2] + slack and box[1] - slack <= ay <= box[3] + slack
    )
    for p, n, rho, two, lo, hi in c.lines() if lines is None else lines:
        d0 = (ax - p[0]) * n[0] + (ay - p[1]) * n[1]
        s = -1.0 if two and d0 < 0.0 else 1.0
        g0 = s * d0 - rho - q
        # Beyond this face by more than the slack: outside a convex solid by as much.
        if below and g0 + q > slack and type(c) is not Box:
            below = False
        g1 = s * (vx * n[0] + vy * n[1])
        if g1 >= 0.0 or g0 < 0.0:
            continue
        t = -g0 / g1
        if t > 1.0:
            continue
        x0, x1 = ax + vx * t - p[0], ay + vy * t - p[1]
        u = -x0 * n[1] + x1 * n[0]  # along the tangent (-n_y, n_x)
        if lo <= u <= hi and t < best_t:
            best_t, best_n = t, _new(Vector, (s * n[0], s * n[1]))
    if below:
        if type(c) is Box:
            # Box.closest's distance (positive inside the room), without its Vectors.
            (x0, y0), (x1, y1) = c.lower_left, c.upper_right
            if min(ax - x0, x1 - ax, ay - y0, y1 - ay) < q:
                return 0.0, _ZERO
        elif c.distance(a) < q:
            return 0.0, _ZERO
    # A round face is met only within its radius (and the sweep's) of the segment: farther
    # in x or y by 1e-6 of that reach than it goes, it is not (the root of a discriminant
    # that cancels strays by at most 1.5e-8 of it; engine.geometry.query_grid's Margins).
    span = abs(vx) + abs(vy)
    for centre, rho in c.discs() if discs is None else discs:
        R = rho + q
        far = (R + span) * (1.0 + 1e-6)
        cx, cy = centre
        if abs(ax - cx) > far or abs(ay - cy) > far:
            continue
        t, _ = _ray_disc_one(a, v, cx, cy, R)
        if t < best_t:  # inf (not met) is never less
            n = _unit_or_zero(ax + vx * t - cx, ay + vy * t - cy)
            if n == _ZERO:  # a ray onto a point: it faces back
                n = _unit_or_zero(-vx, -vy) if back is None else back
            best_t, best_n = t, n
    return None if best_n is None else (best_t, best_n)


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


def bb_query(
    state: WorldState,
    bb: Any,
    filter: Any,  # noqa: A002
    index: QueryIndex | None = None,
) -> list[Any]:
    """The shapes (Bodies and colliders) that overlap the box ``bb`` = (left, bottom, right,
    top), in the World's order: bodies first, then colliders. ``index``: the World's (None:
    made for this query)."""
    box = _bb(bb)
    f = _filter(filter)
    out: list[Any] = []
    m = margin(*box, 0.0, 0.0)
    grown = (box[0] - m, box[1] - m, box[2] + m, box[3] + m)
    discs, shaped = _bodies(state, f, grown, index)
    store = state.store
    found: list[int] = []
    x0, y0, x1, y1 = box
    for k, px, py, r in discs:
        # As np.maximum(np.maximum(x0 - px, px - x1), 0.0) and np.hypot would.
        dx, dy = max(x0 - px, px - x1, 0.0), max(y0 - py, py - y1, 0.0)
        if _hypot(dx, dy) <= r:
            found.append(k)
    if shaped:
        assert store is not None
        for k, shape, at in shaped:
            fr = _Frame(store, k, at)
            if found and found[-1] == k:
                continue  # (a body of several shapes met by an earlier part)
            if fr.s != 0.0:
                # A shape that turned: placed in the world as it stands, then met as a collider.
                if _collider_overlaps_box(fr.placed(shape), box):
                    found.append(k)
                continue
            cx, cy = fr.cx, fr.cy
            if _collider_overlaps_box(shape, (box[0] - cx, box[1] - cy, box[2] - cx, box[3] - cy)):
                found.append(k)
        found.sort()
    out += [state.bodies[k] for k in found]
    grid = _grid(state, index)
    if grid is not None:
        for k in _colliders_seen(grid, grid.near_box(grown), f):
            c = grid.colliders[k]
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


def shape_query(
    state: WorldState,
    shape: Any,
    filter: Any,  # noqa: A002
    index: QueryIndex | None = None,
) -> list[QueryHit]:
    """The shapes that a query shape overlaps, deepest first: ``shape`` is a ``Circle`` or a
    ``Segment`` (a capsule) placed where it is asked about, not added to the World. Each hit:
    the shape found, the deepest point of its surface toward the query shape, the unit normal
    there (out of the shape found, toward the query shape), and ``distance`` < 0, the depth.
    ``index``: the World's (None: made for this query)."""
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
    x0, x1 = (a[0], b[0]) if a[0] <= b[0] else (b[0], a[0])
    y0, y1 = (a[1], b[1]) if a[1] <= b[1] else (b[1], a[1])
    w = q + margin(x0, y0, x1, y1, (x1 - x0) + (y1 - y0), q)
    box = (x0 - w, y0 - w, x1 + w, y1 + w)
    discs, shaped = _bodies(state, f, box, index)
    store = state.store
    deepest: dict[int, QueryHit] = {}  # (a body's deepest part)
    for k, body_shape, at in shaped:
        assert store is not None
        fr = _Frame(store, k, at)
        found = _collider_depth(body_shape, fr.into(a), fr.into(b), q)  # the body's frame
        if found is not None and (k not in deepest or found[2] < deepest[k].distance):
            point = fr.out(found[0])
            deepest[k] = _hit(state.bodies[k], point, fr.turn_out(found[1]), 0.0, found[2])
    hits += deepest.values()
    for k, cx, cy, r in discs:
        # The query shape's core point nearest the centre, then the gap between the discs.
        core = _nearest_on_segment((cx, cy), a, b)
        n = _unit_or_zero(core[0] - cx, core[1] - cy)
        if n == Vector(0.0, 0.0):
            n = Vector(0.0, 1.0)
        gap = math.hypot(core[0] - cx, core[1] - cy) - r - q
        if gap < 0.0:
            hits.append(QueryHit(state.bodies[k], Vector(cx + n.x * r, cy + n.y * r), n, 0.0, gap))
    grid = _grid(state, index)
    if grid is not None:
        for k in _colliders_seen(grid, grid.near_segment(a[0], a[1], b[0], b[1], w), f):
            c = grid.colliders[k]
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
