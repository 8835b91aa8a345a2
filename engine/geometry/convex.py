"""Convex polygons as plain geometry: checked and ordered vertices, edge normals, and the area,
centroid and second moment of a polygon rounded by a radius (Box2D's rounded polygon).

A polygon here is a tuple of (x, y) pairs in length units, counter-clockwise, every turn
strictly to the left (convex, no three vertices on one line). A rounded polygon of radius r is
every point within r of it: the core, a rectangle r deep on each edge, and a circular sector at
each vertex; the sectors' angles add up to one full turn, so together they make one disc.

Standard library only: the colliders, the mass functions and the narrowphase all use it.

>>> square = convex_polygon([(0, 0), (0, 2), (2, 2), (2, 0)], "vertices")  # clockwise in
>>> square
((0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0))
>>> edge_normals(square)
((0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0))
>>> area(square), centroid(square)
(4.0, (1.0, 1.0))
>>> convex_polygon([(0, 0), (2, 0), (1, 0.5), (2, 2), (0, 2)], "vertices")  # doctest: +ELLIPSIS
Traceback (most recent call last):
ValueError: vertices must make a convex polygon: it turns the other way at vertices[2] ...
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

__all__ = [
    "MAX_VERTICES",
    "TOO_CLOSE",
    "convex_polygon",
    "edge_normals",
    "area",
    "centroid",
    "second_moment",
]

#: The most vertices a polygon may have. Not Box2D's 8 (B2_MAX_POLYGON_VERTICES, a fixed-size
#: array in its b2Polygon): our polygons are padded only to the largest count of a batch of
#: pairs (``engine.geometry.manifold_kinds.Polygons.take``), so boxes cost what they did beside a
#: 32-gon. What bounds it is a contact point's feature id, which names the vertex of each
#: shape that makes it in 8 bits each (256 a + b, ``engine.geometry.manifold``), so that a contact's
# key : fits the 16 bits the soft step's warm start keeps for it (``engine.geometry.shaped``,
#: ``engine.exact.pile``): vertex indices 0 to 255.
MAX_VERTICES = 256

#: Neighbouring vertices nearer than this fraction of the polygon's size are one point.
TOO_CLOSE = 1e-9

Point = tuple[float, float]


def _sag(n: int) -> float:
    """How far (a fraction of the radius) a regular n-gon's edge midpoints fall inside the
    circle through its vertices: 1 - cos(pi / n)."""
    return 1.0 - math.cos(math.pi / n)


def _cross(ax: float, ay: float, bx: float, by: float) -> float:
    return ax * by - ay * bx


#: How far a turn's cross product computed in floats may be from the exact one, over the sum
#: of its two products' sizes: Shewchuk's ``ccwerrboundA``, (3 + 16 eps) eps, eps = 2^-53, as
#: here the edges are differences of the points (rounded) and their products rounded too.
_TURN_ERROR = (3.0 + 16.0 * 2.0**-53) * 2.0**-53


def _exact_turn(a: Point, b: Point, c: Point) -> float:
    """The sign (-1.0, 0.0 or 1.0) of the cross product of the edges a->b and b->c, exactly
    (the corners are floats: their differences and products are exact as fractions)."""
    fa, fb, fc = [(Fraction(x), Fraction(y)) for x, y in (a, b, c)]
    turn = (fb[0] - fa[0]) * (fc[1] - fb[1]) - (fb[1] - fa[1]) * (fc[0] - fb[0])
    return float((turn > 0) - (turn < 0))


def convex_polygon(
    points: Sequence[Point], name: str, max_count: int | None = None
) -> tuple[Point, ...]:
    """The points as a convex polygon, counter-clockwise; ValueError naming ``name`` otherwise.

    ``points`` are finite (x, y) pairs of floats, in either winding: clockwise input is
    reversed (and started from the same first point). Refused, each with the index of the
    vertex at fault: fewer than 3 points (or more than ``max_count``), a point repeated next
    to itself (or nearer it than ``TOO_CLOSE`` of the polygon's size), every point on one
    line (no area), a vertex on the straight line between its neighbours, a turn the other
    way (not convex) and a polygon that winds round more than once (a star).
    """
    pts = [(float(x), float(y)) for x, y in points]
    count = len(pts)
    if count < 3:
        raise ValueError(
            f"{name} must have at least 3 points (a triangle), got {count}: {pts!r}; "
            f"use a Segment for a line or a Circle for a point"
        )
    if max_count is not None and count > max_count:
        raise ValueError(
            f"{name} must have at most {max_count} points (a contact names each shape's "
            f"vertex in 8 bits: engine.geometry.convex.MAX_VERTICES), got {count}; use fewer "
            f"points (a regular {max_count}-gon strays from its circle by {_sag(max_count):.1e} "
            f"of the radius) or split the shape into several polygons"
        )
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    for i in range(count):
        j = (i + 1) % count
        if pts[i] == pts[j]:
            raise ValueError(
                f"{name}[{i}] and {name}[{j}] are the same point {pts[i]}: leave the repeat out"
            )
        # Nearer than rounding can tell apart once the polygon is turned and moved: the
        # narrowphase could not say which of the two touches (Box2D welds within 5 mm).
        gap = max(abs(pts[j][0] - pts[i][0]), abs(pts[j][1] - pts[i][1]))
        if gap <= TOO_CLOSE * size:
            raise ValueError(
                f"{name}[{i}] = {pts[i]} and {name}[{j}] = {pts[j]} are {gap:.3g} apart, the same "
                f"point to {TOO_CLOSE:g} of the polygon's size {size:.3g}: leave one out"
            )
    # Twice the signed area by the shoelace formula, about the first point (for round-off):
    # positive when the points run counter-clockwise.
    x0, y0 = pts[0]
    twice = 0.0
    for i in range(1, count - 1):
        twice += _cross(pts[i][0] - x0, pts[i][1] - y0, pts[i + 1][0] - x0, pts[i + 1][1] - y0)
    if not math.isfinite(twice):
        raise ValueError(
            f"{name} must lie within the float range of each other (the area overflows), "
            f"got {pts!r}"
        )
    if twice == 0.0:
        # No area: every point on one line, or a path that crosses itself so that its two
        # lobes cancel (a bow tie given out of order).
        far = max(range(1, count), key=lambda i: abs(pts[i][0] - x0) + abs(pts[i][1] - y0))
        dx, dy = pts[far][0] - x0, pts[far][1] - y0
        if all(_cross(dx, dy, x - x0, y - y0) == 0.0 for x, y in pts):
            raise ValueError(f"{name} must enclose an area: all {count} points lie on one line")
        raise ValueError(
            f"{name} must go in order round the polygon: {pts!r} cross over themselves and "
            f"enclose no area; give the corners in order, clockwise or counter-clockwise"
        )
    if twice < 0.0:  # clockwise: reverse, keeping the first point first
        pts = [pts[0], *pts[:0:-1]]
        index = [0, *range(count - 1, 0, -1)]  # where each vertex was in the input
    else:
        index = list(range(count))
    # Each turn must be strictly left: the cross product of consecutive edges > 0. The turning
    # angles (each in (0, pi)) then add up to 2 pi times the times it winds round: 2 pi for a
    # convex polygon, 4 pi for a pentagram.
    turning = 0.0
    for i in range(count):
        (ax, ay), (bx, by), (cx, cy) = pts[i - 1], pts[i], pts[(i + 1) % count]
        e1x, e1y, e2x, e2y = bx - ax, by - ay, cx - bx, cy - by
        turn = _cross(e1x, e1y, e2x, e2y)
        if abs(turn) <= _TURN_ERROR * (abs(e1x * e2y) + abs(e1y * e2x)):
            # Within the rounding of the differences and products (Shewchuk's bound for this
            # orientation test): its sign from the exact cross product of the exact edges.
            turn = _exact_turn((ax, ay), (bx, by), (cx, cy))
        if turn == 0.0 and e1x * e2x + e1y * e2y > 0.0:
            raise ValueError(
                f"{name}[{index[i]}] = {pts[i]} lies on the straight line between its "
                f"neighbours: leave it out (a polygon's vertices are its corners)"
            )
        if turn <= 0.0:
            raise ValueError(
                f"{name} must make a convex polygon: it turns the other way at "
                f"{name}[{index[i]}] = {pts[i]} (concave there); split the shape into convex "
                f"polygons"
            )
        turning += math.atan2(turn, e1x * e2x + e1y * e2y)
    if turning > 3.0 * math.pi:  # 2 pi for convex; 4 pi or more when it winds round again
        raise ValueError(
            f"{name} must make a simple convex polygon: the points wind round "
            f"{round(turning / (2.0 * math.pi))} times (a star); give the corners in order"
        )
    return tuple(pts)


def edge_normals(vertices: Sequence[Point]) -> tuple[Point, ...]:
    """The outward unit normal of each edge (from vertex i to i + 1) of a CCW polygon.

    For a counter-clockwise polygon the outside is on the right of each edge, so the normal
    of the edge e = (ex, ey) is e turned clockwise, (ey, -ex), over its length.
    """
    count = len(vertices)
    out = []
    for i in range(count):
        (ax, ay), (bx, by) = vertices[i], vertices[(i + 1) % count]
        ex, ey = bx - ax, by - ay
        scale = max(abs(ex), abs(ey))  # scaled first: hypot of tiny or huge edges stays exact
        ex, ey = ex / scale, ey / scale
        length = math.hypot(ex, ey)
        out.append((ey / length + 0.0, -ex / length + 0.0))  # + 0.0: no -0.0 components
    return tuple(out)


def _moments(vertices: Sequence[Point], radius: float) -> tuple[float, float, float, float]:
    """(area, first moment x, first moment y, polar second moment), all about vertices[0].

    Each part of the rounded polygon adds its share (u = a vertex less vertices[0]):
    - the core, as triangles (0, u_i, u_{i+1}) of area c / 2 with c = u_i x u_{i+1}: first
      moment c (u_i + u_{i+1}) / 6, polar moment c (u_i.u_i + u_i.u_{i+1} + u_{i+1}.u_{i+1}) / 12;
    - edge i's rectangle, length L by r, centre m = (u_i + u_{i+1}) / 2 + r n_i / 2: area
      a = L r, first moment a m, polar moment a (L^2 + r^2) / 12 + a m.m (parallel axes);
    - vertex i's sector, angle t between n_{i-1} and n_i, bisector b: area t r^2 / 2, and
      with s the offset from its apex, int s dA = (2/3) r^3 sin(t / 2) b and
      int s.s dA = t r^4 / 4, so about the origin: first moment a u + (2/3) r^3 sin(t/2) b,
      polar moment a u.u + 2 u.(2/3) r^3 sin(t/2) b + t r^4 / 4.
    """
    count = len(vertices)
    x0, y0 = vertices[0]
    u = [(x - x0, y - y0) for x, y in vertices]
    A = Sx = Sy = J = 0.0
    for i in range(count):
        (ax, ay), (bx, by) = u[i], u[(i + 1) % count]
        c = _cross(ax, ay, bx, by)
        A += 0.5 * c
        Sx += c * (ax + bx) / 6.0
        Sy += c * (ay + by) / 6.0
        J += c * (ax * ax + ay * ay + ax * bx + ay * by + bx * bx + by * by) / 12.0
    if radius > 0.0:
        r = radius
        normals = edge_normals(vertices)
        for i in range(count):
            (ax, ay), (bx, by) = u[i], u[(i + 1) % count]
            nx, ny = normals[i]
            length = math.hypot(bx - ax, by - ay)
            a = length * r
            mx, my = 0.5 * (ax + bx) + 0.5 * r * nx, 0.5 * (ay + by) + 0.5 * r * ny
            A += a
            Sx += a * mx
            Sy += a * my
            J += a * (length * length + r * r) / 12.0 + a * (mx * mx + my * my)
            # The sector at vertex i, between the previous edge's normal p and this one's.
            px, py = normals[i - 1]
            t = math.atan2(_cross(px, py, nx, ny), px * nx + py * ny)  # in (0, pi): convex
            # The bisector: p turned counter-clockwise by t / 2.
            h = 0.5 * t
            qx, qy = math.cos(h) * px - math.sin(h) * py, math.sin(h) * px + math.cos(h) * py
            # (Products, not powers: near the float range a product overflows to inf, which the
            # caller refuses by name, where a float power raises OverflowError.)
            r2 = r * r
            k = (2.0 / 3.0) * (r2 * r) * math.sin(h)
            a = 0.5 * t * r * r
            A += a
            Sx += a * ax + k * qx
            Sy += a * ay + k * qy
            J += a * (ax * ax + ay * ay) + 2.0 * k * (ax * qx + ay * qy) + 0.25 * t * r2 * r2
    return A, Sx, Sy, J


def area(vertices: Sequence[Point], radius: float = 0.0) -> float:
    """Area (length units squared) of the CCW convex polygon rounded by ``radius``.

    The rounding adds r times the perimeter (the edges' rectangles) and pi r^2 (the sectors).
    """
    return _moments(vertices, radius)[0]


def centroid(vertices: Sequence[Point], radius: float = 0.0) -> Point:
    """Centroid (length units) of the CCW convex polygon rounded by ``radius``."""
    A, Sx, Sy, _ = _moments(vertices, radius)
    x0, y0 = vertices[0]
    return x0 + Sx / A, y0 + Sy / A


def second_moment(
    vertices: Sequence[Point], radius: float = 0.0, about: Point = (0.0, 0.0)
) -> float:
    """Polar second moment of area, int |x - about|^2 dA (length^4), of the rounded polygon.

    Taken about the centroid first (the sums are about vertices[0], so the parallel-axis step
    J_c = J_0 - A |c|^2 loses nothing to large coordinates), then moved to ``about``.
    """
    A, Sx, Sy, J0 = _moments(vertices, radius)
    cx, cy = Sx / A, Sy / A
    Jc = J0 - A * (cx * cx + cy * cy)
    x0, y0 = vertices[0]
    dx, dy = x0 + cx - about[0], y0 + cy - about[1]
    return Jc + A * (dx * dx + dy * dy)
