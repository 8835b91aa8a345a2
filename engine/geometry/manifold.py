"""The narrowphase: the contact manifold of each pair of shapes, many pairs of one kind at once.

Box2D v3's definitions (``src/manifold.c``), in numpy: one call a pair of kinds a step, never
a Python loop over pairs. The kinds (``engine.geometry.manifold_kinds``, re-exported here) hold the
shapes in their bodies' frames: ``Circles``, ``Capsules`` (a segment with a radius),
``Polygons`` (convex, up to 256 vertices, padded, with a rounding radius) and ``HalfPlanes``
(a ``Plane``, or a wall of a room ``Box``). Each function takes shape A's kind and its bodies'
positions (N, 2) and angles (N,) (rad), then B's, then ``margin``, the speculative distance
(length units, Box2D's 0.02 m by default): a pair farther apart than it gets no point, and
so does a point of a pair. The math is done in A's frame and the result turned into the
world's, so any angle works.

Each returns a ``Manifold`` of arrays: ``normal`` (N, 2) unit from A to B; ``count`` (N,) 0 to
2; ``point`` (N, 2, 2) world points midway between the surfaces; ``anchor_a`` and ``anchor_b``
the points less each body's position; ``separation`` (N, 2), the gap along the normal (< 0 when
they overlap); ``feature`` (N, 2) ids, 256 (A's vertex) + (B's vertex), which stay the same
while the same features touch.

* ``collide_circles``, ``collide_capsule_circle``: one point, at the exact distance less both
  radii, along the line of the nearest points.
* ``collide_capsules``: Box2D's capsule pair: when neither segment lies wholly beyond the
  other's ends, the one of the two whose side separates more (A's, unless B's by more than
  0.1 ``LINEAR_SLOP``) clips the other to its extent: two points, kept if one of them is
  within ``LINEAR_SLOP`` of the exact distance and, the cores apart, neither lies behind the
  reference side (so a capsule lying on another has two points, the nearer at most
  ``LINEAR_SLOP`` farther than the exact distance); else one point at the nearest points,
  exact.
* ``collide_polygon_circle``: one point; the exact signed distance from the circle's centre
  to the polygon, less both radii.
* ``collide_polygons``, ``collide_polygon_capsule``: the separating axis test and clipping
  (``engine.geometry.manifold_polygon``): a box resting flat gives two points at its corners, a box
  on its corner one (a clipped point beyond ``margin`` is dropped; Box2D keeps it). The
  least separation is the exact distance, or within 0.1 ``LINEAR_SLOP`` above it.
* ``collide_half_plane_circle``, ``collide_half_plane_capsule``,
  ``collide_half_plane_polygon``: against a half plane, the incident edge's two ends.
* ``collide(a, xa, qa, b, xb, qb, margin)``: any pair of kinds, in either order.
* ``static_shapes(colliders)``: the World's colliders as kinds (a room is four half planes),
  and ``collide_static`` to meet all of them without a broadphase.

>>> import numpy as np
>>> floor = HalfPlanes([[0.0, 0.0]], [[0.0, 1.0]])
>>> box = Polygons.of([[(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]])
>>> m = collide(floor, (0.0, 0.0), 0.0, box, [[3.0, 0.5]], [0.0])  # resting flat
>>> m.count.tolist(), m.separation.tolist(), m.point[0].tolist()
([2], [[0.0, 0.0]], [[3.5, 0.0], [2.5, 0.0]])
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import kernels
from .colliders import Box, Circle, Collider, Plane, Polygon, Segment
from .manifold_kinds import (
    LINEAR_SLOP,
    SPECULATIVE_DISTANCE,
    Capsules,
    Circles,
    HalfPlanes,
    Manifold,
    Polygons,
    capsule_corners,
    finish,
    frames,
)
from .manifold_polygon import collide_polygons, segment_distance

__all__ = [
    "LINEAR_SLOP",
    "SPECULATIVE_DISTANCE",
    "Manifold",
    "Circles",
    "Capsules",
    "Polygons",
    "HalfPlanes",
    "collide_circles",
    "collide_capsule_circle",
    "collide_capsules",
    "collide_polygon_circle",
    "collide_polygon_capsule",
    "collide_polygons",
    "collide_half_plane_circle",
    "collide_half_plane_capsule",
    "collide_half_plane_polygon",
    "collide",
    "StaticShapes",
    "static_shapes",
    "collide_static",
    "polygon_distance",
    "half_plane_polygon_loop",
]

Kind = Circles | Capsules | Polygons | HalfPlanes


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _left(v: np.ndarray) -> np.ndarray:
    """v turned a quarter turn counter-clockwise, (-v_y, v_x)."""
    return np.stack([-v[:, 1], v[:, 0]], axis=1)


def _unit(v: np.ndarray, fallback: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(v / |v|, |v|) row by row; ``fallback`` where |v| = 0 (coincident points)."""
    length = np.hypot(v[:, 0], v[:, 1])
    safe = np.where(length > 0.0, length, 1.0)[:, None]
    return np.where(length[:, None] > 0.0, v / safe, fallback), length


def _pairs(a: Any, b: Any) -> int:
    if len(a) != len(b):
        raise ValueError(f"a and b must hold one shape a pair, got {len(a)} and {len(b)}")
    return len(a)


def _margin(margin: Any) -> float:
    m = float(margin)
    if not m >= 0.0:  # nan too
        raise ValueError(f"margin must be >= 0 (length units; inf for every pair), got {margin!r}")
    return m


def _one_point(
    f: Any, normal: np.ndarray, cA: np.ndarray, cB: np.ndarray, sep: np.ndarray, margin: float
) -> Manifold:
    """A one-point manifold: the point midway between the surface points cA and cB."""
    n = len(sep)
    mid = 0.5 * (cA + cB)
    point = np.stack([mid, mid], axis=1)
    seps = np.stack([sep, sep], axis=1)
    live = np.zeros((n, 2), dtype=bool)
    live[:, 0] = True
    return finish(f, normal, point, seps, np.zeros((n, 2), dtype=np.int64), live, margin)


def collide_circles(
    a: Circles, xa: Any, qa: Any, b: Circles, xb: Any, qb: Any, margin: float = SPECULATIVE_DISTANCE
) -> Manifold:
    """Circle A against circle B: one point, separation |cB - cA| - rA - rB (b2CollideCircles)."""
    margin = _margin(margin)
    f = frames(xa, qa, xb, qb, _pairs(a, b))
    pA, pB = a.center, f.b_points(b.center)
    up = np.broadcast_to([0.0, 1.0], pA.shape)  # coincident centres: A's up
    normal, dist = _unit(pB - pA, up)
    cA = pA + a.radius[:, None] * normal
    cB = pB - b.radius[:, None] * normal
    return _one_point(f, normal, cA, cB, dist - a.radius - b.radius, margin)


def _nearest_on_segments(p1: np.ndarray, p2: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The point of each segment p1-p2 nearest c: p1 + clamp((c - p1).e / e.e, 0, 1) e."""
    e = p2 - p1
    s1, s2 = _dot(c - p1, e), _dot(p2 - c, e)
    inner = p1 + (s1 / _dot(e, e))[:, None] * e
    return np.where((s1 < 0.0)[:, None], p1, np.where((s2 < 0.0)[:, None], p2, inner))


def collide_capsule_circle(
    a: Capsules,
    xa: Any,
    qa: Any,
    b: Circles,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Capsule A against circle B: one point at the nearest points of A's segment and B's
    centre, separation their distance less both radii (b2CollideCapsuleAndCircle)."""
    margin = _margin(margin)
    f = frames(xa, qa, xb, qb, _pairs(a, b))
    pB = f.b_points(b.center)
    pA = _nearest_on_segments(a.a, a.b, pB)
    e = a.b - a.a
    side = _left(e) / np.hypot(e[:, 0], e[:, 1])[:, None]  # the centre on the segment
    normal, dist = _unit(pB - pA, side)
    cA = pA + a.radius[:, None] * normal
    cB = pB - b.radius[:, None] * normal
    return _one_point(f, normal, cA, cB, dist - a.radius - b.radius, margin)


def _clip_capsule(
    p2: np.ndarray, q2: np.ndarray, fp: np.ndarray, fq: np.ndarray, length: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The part of segment p2-q2 whose projections fp, fq along the other segment (which
    spans [0, length]) lie within it: each end poking out is moved along p2-q2 to the end."""
    with np.errstate(divide="ignore", invalid="ignore"):
        at0p = p2 + ((0.0 - fp) / (fq - fp))[:, None] * (q2 - p2)
        at0q = q2 + ((0.0 - fq) / (fp - fq))[:, None] * (p2 - q2)
        atLp = p2 + ((fp - length) / (fp - fq))[:, None] * (q2 - p2)
        atLq = q2 + ((fq - length) / (fq - fp))[:, None] * (p2 - q2)
    cp = np.where(
        ((fp < 0.0) & (fq > 0.0))[:, None],
        at0p,
        np.where(((fp > length) & (fq < length))[:, None], atLp, p2),
    )
    cq = np.where(
        ((fq < 0.0) & (fp > 0.0))[:, None],
        at0q,
        np.where(((fq > length) & (fp < length))[:, None], atLq, q2),
    )
    return cp, cq


def _side(
    p1: np.ndarray, u: np.ndarray, p2: np.ndarray, q2: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(normal, separation) of segment p2-q2 from the line through p1 along u: the side
    (left normal of u or its negative) where the nearer end is farther out."""
    n = _left(u)
    s1, s2 = _dot(p2 - p1, n), _dot(q2 - p1, n)
    pos, neg = np.minimum(s1, s2), np.minimum(-s1, -s2)
    return np.where((pos > neg)[:, None], n, -n), np.maximum(pos, neg)


def collide_capsules(
    a: Capsules,
    xa: Any,
    qa: Any,
    b: Capsules,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Capsule A against capsule B (b2CollideCapsules): two clipped points when the segments
    overlap along each other and one of them is within LINEAR_SLOP of the nearest distance,
    else one point at the nearest points (module doc)."""
    margin = _margin(margin)
    n = _pairs(a, b)
    f = frames(xa, qa, xb, qb, n)
    origin = a.a  # Box2D's shift: A's first end is the origin
    p1, q1 = np.zeros_like(origin), a.b - origin
    p2, q2 = f.b_points(b.a) - origin, f.b_points(b.b) - origin
    rA, rB = a.radius, b.radius
    R = rA + rB
    f1, f2, c1, c2, dd = segment_distance(p1, q1, p2, q2)
    dist = np.sqrt(dd)
    d1, d2 = q1 - p1, q2 - p2
    len1, len2 = np.hypot(d1[:, 0], d1[:, 1]), np.hypot(d2[:, 0], d2[:, 1])
    u1, u2 = d1 / len1[:, None], d2 / len2[:, None]
    # Does B project wholly beyond an end of A, or A beyond an end of B?
    fp2, fq2 = _dot(p2 - p1, u1), _dot(q2 - p1, u1)
    fp1, fq1 = _dot(p1 - p2, u2), _dot(q1 - p2, u2)
    outA = ((fp2 <= 0.0) & (fq2 <= 0.0)) | ((fp2 >= len1) & (fq2 >= len1))
    outB = ((fp1 <= 0.0) & (fq1 <= 0.0)) | ((fp1 >= len2) & (fq1 >= len2))
    nA, sepA = _side(p1, u1, p2, q2)
    nB, sepB = _side(p2, u2, p1, q1)
    useA = sepA + 0.1 * LINEAR_SLOP >= sepB  # biased to A, against flip-flop (Box2D)
    # Reference A: B clipped to A's extent, separations along nA.
    apA, aqA = _clip_capsule(p2, q2, fp2, fq2, len1)
    spA, sqA = _dot(apA - p1, nA), _dot(aqA - p1, nA)
    # Reference B: A clipped to B's extent, separations along nB; the normal is -nB.
    apB, aqB = _clip_capsule(p1, q1, fp1, fq1, len2)
    spB, sqB = _dot(apB - p2, nB), _dot(aqB - p2, nB)
    ua = useA[:, None]
    sp, sq = np.where(useA, spA, spB), np.where(useA, sqA, sqB)
    ref = np.where(ua, nA, nB)
    half = np.where(useA, rA - rB, rB - rA)
    cp = np.where(ua, apA, apB) + (0.5 * (half - sp))[:, None] * ref
    cq = np.where(ua, aqA, aqB) + (0.5 * (half - sq))[:, None] * ref
    two = ~outA & ~outB & ((sp <= dist + LINEAR_SLOP) | (sq <= dist + LINEAR_SLOP))
    # Not in Box2D: with the cores apart, a clipped point behind the reference side (s < 0)
    # is an end dipping past the other's line beside its end, not an overlap: one point, exact.
    # (A point within the reference's extent is |s| from its segment, so s >= dist there.)
    two &= (np.minimum(sp, sq) >= 0.0) | (dist <= 1e-12 * (len1 + len2))
    # One point at the nearest points; on each other (crossing cores), A's left side.
    normal, _ = _unit(c2 - c1, _left(u1))
    mid = 0.5 * (c1 + rA[:, None] * normal + c2 - rB[:, None] * normal)
    one_id = np.where(f1 == 0.0, 0, 1) << 8 | np.where(f2 == 0.0, 0, 1)
    t = two[:, None]
    normal = np.where(t, np.where(ua, nA, -nB), normal)
    point = np.where(t[:, :, None], np.stack([cp, cq], axis=1), np.stack([mid, mid], axis=1))
    sep = np.where(t, np.stack([sp, sq], axis=1) - R[:, None], (dist - R)[:, None])
    feature = np.where(
        t,
        np.where(ua, np.array([0, 1]), np.array([0, 256])),
        np.stack([one_id, one_id], axis=1),
    )
    live = np.where(t, True, np.array([True, False]))
    live &= (dist - R <= margin)[:, None]
    return finish(f, normal, point + origin[:, None, :], sep, feature, live, margin)


def collide_polygon_circle(
    a: Polygons,
    xa: Any,
    qa: Any,
    b: Circles,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Polygon A against circle B (b2CollidePolygonAndCircle): one point; the separation is
    the signed distance from B's centre to A's core polygon less both radii.

    The edge of largest separation s = n_i.(c - v_i) is the reference. Outside it and past one
    of its ends (in that vertex's region), the nearest point is the vertex; else the centre
    faces the edge (or is inside, where the largest s is minus the depth).
    """
    margin = _margin(margin)
    f = frames(xa, qa, xb, qb, _pairs(a, b))
    c = f.b_points(b.center)
    V, N = a.vertices, a.normals
    rows = np.arange(len(c))
    s = _dot(N, c[:, None, :] - V)  # (N, M)
    k = s.argmax(axis=1)
    sep = s[rows, k]
    v1, v2 = V[rows, k], V[rows, (k + 1) % a.count]
    u1, u2 = _dot(c - v1, v2 - v1), _dot(c - v2, v1 - v2)
    outside = sep > 0.0
    near1 = (outside & (u1 < 0.0))[:, None]
    near2 = (outside & (u2 < 0.0))[:, None] & ~near1
    vertex = np.where(near1, v1, v2)
    to_vertex, dist = _unit(c - vertex, N[rows, k])
    face = N[rows, k]
    normal = np.where(near1 | near2, to_vertex, face)
    corner = (near1 | near2)[:, 0]
    # The face: A's surface point is the centre's projection on the edge, pushed out rA.
    on_face = c + (a.radius - _dot(c - v1, face))[:, None] * face
    cA = np.where(corner[:, None], vertex + a.radius[:, None] * normal, on_face)
    cB = c - b.radius[:, None] * normal
    gap = np.where(corner, dist, sep) - a.radius - b.radius
    return _one_point(f, normal, cA, cB, gap, margin)


def collide_polygon_capsule(
    a: Polygons,
    xa: Any,
    qa: Any,
    b: Capsules,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Polygon A against capsule B: B as a two-vertex polygon (b2CollidePolygonAndCapsule)."""
    return collide_polygons(a, xa, qa, Polygons.from_capsules(b), xb, qb, _margin(margin))


def collide_half_plane_circle(
    a: HalfPlanes,
    xa: Any,
    qa: Any,
    b: Circles,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Half plane A against circle B: one point, separation n.(c - p) - rB."""
    margin = _margin(margin)
    f = frames(xa, qa, xb, qb, _pairs(a, b))
    c = f.b_points(b.center)
    n = a.normal
    s = _dot(c - a.point, n)
    # The plane's surface point is c - s n, B's is c - rB n.
    return _one_point(f, n, c - s[:, None] * n, c - b.radius[:, None] * n, s - b.radius, margin)


def collide_half_plane_polygon(
    a: HalfPlanes,
    xa: Any,
    qa: Any,
    b: Polygons,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
    fast: bool = False,
) -> Manifold:
    """Half plane A against polygon B: the ends of B's incident edge (its normal most against
    the plane's), each with separation n.(w - p) - rB; ids are B's vertex indices. ``fast``:
    the loop kernel ``half_plane_polygon_loop``."""
    margin = _margin(margin)
    n_pairs = _pairs(a, b)
    f = frames(xa, qa, xb, qb, n_pairs)  # validates the poses on both paths
    if fast:
        rows = np.arange(n_pairs)

        def pose(v: np.ndarray) -> np.ndarray:
            # C-contiguous and writable, never a read-only broadcast view: the kernel's one
            # specialisation (engine.kernels: no compile in play).
            return np.require(v, float, ["C", "W"])

        q_a = pose(np.broadcast_to(np.asarray(qa, dtype=float), (n_pairs,)))
        q_b = pose(np.broadcast_to(np.asarray(qb, dtype=float), (n_pairs,)))
        return Manifold(
            *half_plane_polygon_loop(
                a.point, a.normal, rows, pose(f.xa), q_a,
                b.vertices, b.normals, b.count, b.radius, rows, pose(f.xb), q_b, margin,
            )
        )  # fmt: skip
    W, NB = f.b_points(b.vertices), f.b_vectors(b.normals)
    n, p = a.normal, a.point
    rows = np.arange(len(n))
    e = _dot(NB, n[:, None, :]).argmin(axis=1)
    i1, i2 = e, (e + 1) % b.count
    w = np.stack([W[rows, i2], W[rows, i1]], axis=1)  # Box2D's order: the lower end first
    s = _dot(w - p[:, None, :], n[:, None, :])
    point = w - (0.5 * (s + b.radius[:, None]))[..., None] * n[:, None, :]
    feature = np.stack([i2, i1], axis=1).astype(np.int64)
    live = np.ones((len(n), 2), dtype=bool)
    return finish(f, n, point, s - b.radius[:, None], feature, live, margin)


def collide_half_plane_capsule(
    a: HalfPlanes,
    xa: Any,
    qa: Any,
    b: Capsules,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
) -> Manifold:
    """Half plane A against capsule B: B as a two-vertex polygon, both ends."""
    return collide_half_plane_polygon(a, xa, qa, Polygons.from_capsules(b), xb, qb, margin)


_TABLE: dict[tuple[type, type], Any] = {
    (Circles, Circles): collide_circles,
    (Capsules, Circles): collide_capsule_circle,
    (Capsules, Capsules): collide_capsules,
    (Polygons, Circles): collide_polygon_circle,
    (Polygons, Capsules): collide_polygon_capsule,
    (Polygons, Polygons): collide_polygons,
    (HalfPlanes, Circles): collide_half_plane_circle,
    (HalfPlanes, Capsules): collide_half_plane_capsule,
    (HalfPlanes, Polygons): collide_half_plane_polygon,
}
#: The pairs' functions that have a loop kernel (their ``fast`` argument).
_FAST = frozenset([collide_polygons, collide_half_plane_polygon])


def collide(
    a: Kind,
    xa: Any,
    qa: Any,
    b: Kind,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
    fast: bool = False,
) -> Manifold:
    """The manifolds of N pairs of any two kinds, the normal from A to B: the function for
    the pair, with A and B swapped (and the result ``flipped``) where the table has B first.
    ``fast``: the pair's loop kernel where it has one (``_FAST``), else its numpy."""
    fn = _TABLE.get((type(a), type(b)))
    more = {"fast": True} if fast and fn in _FAST else {}
    if fn is not None:
        return fn(a, xa, qa, b, xb, qb, margin, **more)  # type: ignore[no-any-return]
    fn = _TABLE.get((type(b), type(a)))
    more = {"fast": True} if fast and fn in _FAST else {}
    if fn is not None:
        return fn(b, xb, qb, a, xa, qa, margin, **more).flipped()  # type: ignore[no-any-return]
    raise TypeError(
        f"no narrowphase for {type(a).__name__} against {type(b).__name__}: a and b must be "
        f"Circles, Capsules, Polygons or HalfPlanes, and not two HalfPlanes"
    )


@dataclass(frozen=True)
class StaticShapes:
    """A World's colliders as kinds in the world's frame (the static body: position 0, angle
    0), each row with its ``owner``, the collider's index in the list given."""

    half_planes: HalfPlanes
    half_plane_owner: np.ndarray
    circles: Circles
    circle_owner: np.ndarray
    capsules: Capsules
    capsule_owner: np.ndarray
    polygons: Polygons
    polygon_owner: np.ndarray

    @functools.cached_property
    def capsule_polygons(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The capsules as two-vertex polygons (corners, normals, counts, radii), made once:
        a game's bodies come and go while its colliders stay, and the tables of both are
        made again then (engine.geometry.narrowphase.places_of)."""
        two = np.full(len(self.capsules), 2, dtype=np.intp)
        return (*capsule_corners(self.capsules), two, self.capsules.radius)

    def kinds(self) -> list[tuple[Kind, np.ndarray]]:
        """The non-empty kinds, each with its owners."""
        every: list[tuple[Kind, np.ndarray]] = [
            (self.half_planes, self.half_plane_owner),
            (self.circles, self.circle_owner),
            (self.capsules, self.capsule_owner),
            (self.polygons, self.polygon_owner),
        ]
        return [(k, o) for k, o in every if len(o)]


def static_shapes(colliders: Sequence[Collider]) -> StaticShapes:
    """The colliders as kinds: a ``Plane`` a half plane, a room ``Box`` four (its walls,
    solid outside), a ``Segment`` a capsule, a ``Circle`` a circle, a ``Polygon`` a polygon.
    Sensors are included like the rest: the owners let a caller leave them out."""
    planes: list[tuple[tuple[float, float], tuple[float, float], int]] = []
    circles, capsules, polygons = [], [], []
    for k, c in enumerate(colliders):
        if isinstance(c, Plane):
            planes.append(((c.point.x, c.point.y), (c.normal.x, c.normal.y), k))
        elif isinstance(c, Box):
            for p, nrm, _, _, _, _ in c.lines():
                planes.append((p, nrm, k))
        elif isinstance(c, Segment):
            capsules.append(((c.a.x, c.a.y), (c.b.x, c.b.y), c.radius, k))
        elif isinstance(c, Circle):
            circles.append(((c.center.x, c.center.y), c.radius, k))
        elif isinstance(c, Polygon):
            polygons.append((c, k))
        else:
            raise TypeError(
                f"colliders must be Plane, Box, Segment, Circle or Polygon, got {c!r} at {k}"
            )
    owner = np.intp
    if polygons:
        shapes = Polygons.of(
            [[tuple(v) for v in c.vertices] for c, _ in polygons], [c.radius for c, _ in polygons]
        )
    else:
        shapes = Polygons(np.zeros((0, 3, 2)), np.zeros((0, 3, 2)), np.zeros(0, owner), np.zeros(0))
    return StaticShapes(
        HalfPlanes(
            np.array([p for p, _, _ in planes], float).reshape(-1, 2),
            np.array([nn for _, nn, _ in planes], float).reshape(-1, 2),
        ),
        np.array([k for _, _, k in planes], owner),
        Circles(
            np.array([c for c, _, _ in circles], float).reshape(-1, 2),
            np.array([r for _, r, _ in circles], float),
        ),
        np.array([k for _, _, k in circles], owner),
        Capsules(
            np.array([a for a, _, _, _ in capsules], float).reshape(-1, 2),
            np.array([b for _, b, _, _ in capsules], float).reshape(-1, 2),
            np.array([r for _, _, r, _ in capsules], float),
        ),
        np.array([k for _, _, _, k in capsules], owner),
        shapes,
        np.array([k for _, k in polygons], owner),
    )


def collide_static(
    shapes: Kind, x: Any, q: Any, statics: StaticShapes, margin: float = SPECULATIVE_DISTANCE
) -> list[tuple[Manifold, np.ndarray, np.ndarray]]:
    """Every shape (A, on bodies at ``x`` (N, 2), ``q`` (N,)) against every static shape (B),
    with no broadphase: for each static kind, (manifolds of the pairs with a point, the
    shape's row, the collider's index). A broadphase would pass only nearby pairs to
    ``collide``; this is the all-pairs reference for few shapes."""
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    q = np.broadcast_to(np.asarray(q, dtype=float), (len(x),))
    out = []
    for kind, owner in statics.kinds():
        rows = np.repeat(np.arange(len(x)), len(owner))
        cols = np.tile(np.arange(len(owner)), len(x))
        m = collide(shapes.take(rows), x[rows], q[rows], kind.take(cols), (0.0, 0.0), 0.0, margin)
        hit = m.count > 0
        out.append((m.take(hit), rows[hit], owner[cols[hit]]))
    return out


def polygon_distance(polygon: Polygon, points: Any) -> np.ndarray:
    """Signed distance (length units) from each of ``points`` (N, 2) to a ``Polygon``'s
    surface, < 0 inside: the polygon against circles of radius 0 at the points."""
    X = np.asarray(points, dtype=float).reshape(-1, 2)
    shape = Polygons.of([[tuple(v) for v in polygon.vertices]], polygon.radius)
    n = len(X)
    m = collide_polygon_circle(
        shape.take(np.zeros(n, dtype=np.intp)),
        (0.0, 0.0),
        0.0,
        Circles(X, np.zeros(n)),
        (0.0, 0.0),
        0.0,
        np.inf,
    )
    return m.separation[:, 0]


# -- the loop kernel (engine.kernels: the fast path) ------------------------------------------


def _sample_half_plane() -> tuple[object, ...]:
    """The smallest call of ``half_plane_polygon_loop``: a unit box resting on a floor."""
    v = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]])
    nn = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]])
    i, q = np.array([0]), np.zeros(1)
    up, x0 = np.array([[0.0, 1.0]]), np.zeros((1, 2))
    return x0, up, i, x0, q, v, nn, np.array([4]), np.zeros(1), i, np.array([[0.0, 0.5]]), q, 0.02


@kernels.loop(sample=_sample_half_plane)
def half_plane_polygon_loop(
    P: np.ndarray,
    Nh: np.ndarray,
    ia: np.ndarray,
    xa: np.ndarray,
    qa: np.ndarray,
    V: np.ndarray,
    N: np.ndarray,
    cB: np.ndarray,
    rB: np.ndarray,
    ib: np.ndarray,
    xb: np.ndarray,
    qb: np.ndarray,
    margin: float,
) -> tuple[np.ndarray, ...]:
    """``collide_half_plane_polygon`` as a loop over pairs: pair k is half plane ``ia[k]``
    (P, Nh: point and unit normal) at pose (xa[k], qa[k]) against polygon ``ib[k]`` of (V, N,
    cB, rB) at (xb[k], qb[k]) (length units, rad); returns the Manifold's arrays, each step
    its twin's products in its order."""
    n = len(ia)
    normal_w = np.empty((n, 2))
    count = np.zeros(n, dtype=np.int64)
    world = np.zeros((n, 2, 2))
    anchor_a = np.zeros((n, 2, 2))
    anchor_b = np.zeros((n, 2, 2))
    sep_out = np.full((n, 2), np.inf)
    feat_out = np.full((n, 2), -1, dtype=np.int64)
    for k in range(n):
        h, b = ia[k], ib[k]
        # Frames (engine.geometry.manifold_kinds.frames): B's pose in A's frame.
        ca, sn = np.cos(qa[k]), np.sin(qa[k])
        dx, dy = xb[k, 0] - xa[k, 0], xb[k, 1] - xa[k, 1]
        px, py = ca * dx + sn * dy, -sn * dx + ca * dy
        rel = qb[k] - qa[k]
        c, s = np.cos(rel), np.sin(rel)
        nx, ny = Nh[h, 0], Nh[h, 1]
        # The incident edge: B's normal most against n (the first of equals, as argmin).
        e, best = 0, np.inf
        for j in range(cB[b]):
            ux, uy = N[b, j, 0], N[b, j, 1]
            d = (c * ux - s * uy) * nx + (s * ux + c * uy) * ny
            if d < best:
                e, best = j, d
        i1, i2 = e, (e + 1) % cB[b]
        r = rB[b]
        normal_w[k, 0] = ca * nx - sn * ny
        normal_w[k, 1] = sn * nx + ca * ny
        slot = 0
        for i in (i2, i1):  # Box2D's order: the lower end first
            vx, vy = V[b, i, 0], V[b, i, 1]
            wx, wy = c * vx - s * vy + px, s * vx + c * vy + py
            gap = (wx - P[h, 0]) * nx + (wy - P[h, 1]) * ny
            # Midway: B's surface is r in from w along -n, the plane's is gap in from w.
            half = 0.5 * (gap + r)
            sep = gap - r
            if not sep <= margin:  # finish: dropped, and a lone second moves up
                continue
            x_, y_ = wx - half * nx, wy - half * ny
            ax_, ay_ = ca * x_ - sn * y_, sn * x_ + ca * y_
            anchor_a[k, slot, 0], anchor_a[k, slot, 1] = ax_, ay_
            world[k, slot, 0], world[k, slot, 1] = ax_ + xa[k, 0], ay_ + xa[k, 1]
            anchor_b[k, slot, 0] = ax_ + (xa[k, 0] - xb[k, 0])
            anchor_b[k, slot, 1] = ay_ + (xa[k, 1] - xb[k, 1])
            sep_out[k, slot], feat_out[k, slot] = sep, i
            slot += 1
        count[k] = slot
    return normal_w, count, world, anchor_a, anchor_b, sep_out, feat_out
