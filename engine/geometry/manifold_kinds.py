"""The narrowphase's data: shape kinds as arrays, the contact manifold, and the frames of pairs.

Read ``engine.geometry.manifold`` first: it holds the functions and re-exports everything here. A
kind holds N shapes of one kind in their bodies' frames (length units), one row a pair:

* ``Circles(center, radius)``: (N, 2), (N,);
* ``Capsules(a, b, radius)``: a segment a-b (a != b) rounded by ``radius`` >= 0;
* ``Polygons(vertices, normals, count, radius)``: (N, M, 2) counter-clockwise convex vertices,
  (N, M, 2) the outward unit normal of each edge (vertices[i] to vertices[i + 1]), (N,) how
  many vertices each has (2 for a capsule as Box2D's b2MakeCapsule, else 3 to M), (N,) the
  rounding. **Padding**: a row with fewer than M vertices repeats its last vertex and its
  last normal up to M (``Polygons.of`` does it). Every step that reads them is a max or a
  min over vertices or normals, or indexes (i + 1) % count, so a repeat changes nothing;
  an argmax over repeats returns the first, the real one. M is the largest count of the
  rows at hand, not a fixed size: a table pads to its largest polygon, and ``take`` trims a
  batch to its own largest, so the numpy path's work for a pair (M^2, every vertex against
  every edge) stays a box's for boxes in a scene that holds a 64-gon; the loop kernels go
  only to each row's ``count``.
* ``HalfPlanes(point, normal)``: the solid is behind the line through ``point`` (a ``Plane``,
  or one wall of a room ``Box``).

A body's pose is its position (N, 2) and its angle (N,) in radians: a point v of its shape is
at position + R(angle) v in the world, R(q) = [[cos q, -sin q], [sin q, cos q]].
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import convex

__all__ = [
    "LINEAR_SLOP",
    "SPECULATIVE_DISTANCE",
    "Manifold",
    "Circles",
    "Capsules",
    "Polygons",
    "HalfPlanes",
    "Frames",
    "frames",
    "finish",
]

#: Box2D's B2_LINEAR_SLOP (m): a distance the narrowphase treats as touching when it picks
#: features (its tolerances are tenths of it).
LINEAR_SLOP = 0.005
#: Box2D's B2_SPECULATIVE_DISTANCE (m): the default ``margin``; a pair this far apart or
#: nearer gets contact points, so the solver can stop it before it touches.
SPECULATIVE_DISTANCE = 4.0 * LINEAR_SLOP


def _array(value: Any, name: str, shape: tuple[int, ...]) -> np.ndarray:
    """``value`` as a float array of ``shape`` (-1: any length); ValueError naming ``name``."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(
            f"{name} must be an array of numbers of shape {shape}, got {type(value).__name__}"
        ) from None
    if arr.ndim != len(shape) or any(
        want not in (-1, got) for want, got in zip(shape, arr.shape, strict=True)
    ):
        raise ValueError(f"{name} must have shape {shape} (-1: any), got {arr.shape}")
    return arr


def _rows(name: str, *arrays: np.ndarray) -> int:
    n = len(arrays[0])
    if any(len(a) != n for a in arrays):
        raise ValueError(
            f"{name}: every field must have one row a shape, got {[len(a) for a in arrays]}"
        )
    return n


def _seen_from_b(feature: np.ndarray) -> np.ndarray:
    """Feature ids seen from the other shape: each id's two bytes (A's feature, B's) swapped;
    a negative id (no feature) as it is."""
    return np.where(feature >= 0, (feature & 255) << 8 | (feature >> 8), feature)


@dataclass(frozen=True)
class Manifold:
    """The contact manifolds of N pairs (Box2D's b2Manifold), in the world's frame.

    ``normal`` (N, 2): unit, from shape A to shape B. ``count`` (N,): 0, 1 or 2 points.
    ``point`` (N, 2, 2): each point, midway between the two surfaces (length units).
    ``anchor_a``, ``anchor_b`` (N, 2, 2): the point less body A's (B's) position: the lever
    arms. ``separation`` (N, 2): the gap between the surfaces along the normal at the point
    (length units), < 0 where they overlap. ``feature`` (N, 2): ids, 256 a + b for the
    feature (vertex index) a of A and b of B that make the point; the same while the same
    features touch, for warm starting. Slots past ``count`` hold point 0, separation inf and
    feature -1; a row with count 0 still has a normal (meaningless).
    """

    normal: np.ndarray
    count: np.ndarray
    point: np.ndarray
    anchor_a: np.ndarray
    anchor_b: np.ndarray
    separation: np.ndarray
    feature: np.ndarray

    def __len__(self) -> int:
        return len(self.count)

    def flipped(self) -> Manifold:
        """The same contacts seen from B: normal negated, anchors and feature halves swapped."""
        return Manifold(
            -self.normal,
            self.count,
            self.point,
            self.anchor_b,
            self.anchor_a,
            self.separation,
            _seen_from_b(self.feature),
        )

    def flipped_where(self, swap: np.ndarray) -> Manifold:
        """``flipped``'s rows where ``swap`` (bool (N,)), the others as they are, in their
        order."""
        s2, s3 = swap[:, None], swap[:, None, None]
        return Manifold(
            np.where(s2, -self.normal, self.normal),
            self.count,
            self.point,
            np.where(s3, self.anchor_b, self.anchor_a),
            np.where(s3, self.anchor_a, self.anchor_b),
            self.separation,
            np.where(s2, _seen_from_b(self.feature), self.feature),
        )

    def take(self, rows: Any) -> Manifold:
        """The manifolds of ``rows`` (an index array or a boolean mask)."""
        rows = np.asarray(rows)
        if rows.dtype == bool:
            rows = rows.nonzero()[0]
        # (ndarray.take along the rows: what indexing by ``rows`` gives, at a third of its
        # cost on a game's few rows, seven times a call.)
        return Manifold(
            self.normal.take(rows, axis=0),
            self.count.take(rows, axis=0),
            self.point.take(rows, axis=0),
            self.anchor_a.take(rows, axis=0),
            self.anchor_b.take(rows, axis=0),
            self.separation.take(rows, axis=0),
            self.feature.take(rows, axis=0),
        )

    @staticmethod
    def concat(parts: Sequence[Manifold]) -> Manifold:
        """The manifolds of ``parts`` one after another."""

        def joined(name: str) -> np.ndarray:
            return np.concatenate([getattr(p, name) for p in parts])

        return Manifold(
            joined("normal"),
            joined("count"),
            joined("point"),
            joined("anchor_a"),
            joined("anchor_b"),
            joined("separation"),
            joined("feature"),
        )


@dataclass(frozen=True)
class Circles:
    """N circles: ``center`` (N, 2) in the body's frame, ``radius`` (N,) >= 0."""

    center: np.ndarray
    radius: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "center", _array(self.center, "center", (-1, 2)))
        object.__setattr__(self, "radius", _array(self.radius, "radius", (-1,)))
        _rows("Circles", self.center, self.radius)

    def __len__(self) -> int:
        return len(self.radius)

    def take(self, rows: Any) -> Circles:
        """The shapes of ``rows`` (say, one row per pair from a broadphase)."""
        return Circles(self.center[rows], self.radius[rows])


@dataclass(frozen=True)
class Capsules:
    """N capsules: segments ``a``-``b`` (N, 2) each, a != b, rounded by ``radius`` (N,)."""

    a: np.ndarray
    b: np.ndarray
    radius: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "a", _array(self.a, "a", (-1, 2)))
        object.__setattr__(self, "b", _array(self.b, "b", (-1, 2)))
        object.__setattr__(self, "radius", _array(self.radius, "radius", (-1,)))
        _rows("Capsules", self.a, self.b, self.radius)
        same = np.flatnonzero((self.a == self.b).all(axis=1))
        if len(same):
            raise ValueError(
                f"a and b must differ (a capsule of no length is a circle: use Circles), but "
                f"rows {same[:5].tolist()} have a == b"
            )

    def __len__(self) -> int:
        return len(self.radius)

    def take(self, rows: Any) -> Capsules:
        """The shapes of ``rows``."""
        return Capsules(self.a[rows], self.b[rows], self.radius[rows])


@dataclass(frozen=True)
class Polygons:
    """N convex polygons, padded to M vertices (module doc): ``vertices`` and ``normals``
    (N, M, 2), ``count`` (N,) int, ``radius`` (N,) the rounding (length units)."""

    vertices: np.ndarray
    normals: np.ndarray
    count: np.ndarray
    radius: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "vertices", _array(self.vertices, "vertices", (-1, -1, 2)))
        m = self.vertices.shape[1]
        object.__setattr__(self, "normals", _array(self.normals, "normals", (-1, m, 2)))
        object.__setattr__(self, "count", np.asarray(self.count, dtype=np.intp))
        object.__setattr__(self, "radius", _array(self.radius, "radius", (-1,)))
        _rows("Polygons", self.vertices, self.normals, self.count, self.radius)
        if len(self.count) and not (self.count.min() >= 2 and self.count.max() <= m):
            raise ValueError(f"count must be in [2, {m}] (M, the padded size), got {self.count}")

    def __len__(self) -> int:
        return len(self.radius)

    def take(self, rows: Any) -> Polygons:
        """The shapes of ``rows``, padded only to the largest count among them: the numpy
        narrowphase's work a pair grows as M^2, so boxes taken from a table that holds a
        32-gon cost what boxes do (C-contiguous, as the loop kernels take them)."""
        count = self.count[rows]
        m = max(int(count.max()), 2) if len(count) else self.vertices.shape[1]
        return Polygons(
            np.ascontiguousarray(self.vertices[rows, :m]),
            np.ascontiguousarray(self.normals[rows, :m]),
            count,
            self.radius[rows],
        )

    @classmethod
    def of(cls, polygons: Sequence[Sequence[Any]], radius: Any = 0.0) -> Polygons:
        """Polygons from lists of (x, y) vertices (3 to ``engine.geometry.convex.MAX_VERTICES``,
        either winding, convex: checked, as ``engine.Polygon``'s), padded to the longest; ``radius``
        one for all or one each."""
        rows = [
            convex.convex_polygon(
                [(float(x), float(y)) for x, y in p], f"polygons[{k}]", convex.MAX_VERTICES
            )
            for k, p in enumerate(polygons)
        ]
        n = len(rows)
        m = max((len(r) for r in rows), default=3)
        v = np.empty((n, m, 2))
        nn = np.empty((n, m, 2))
        for k, r in enumerate(rows):
            normals = convex.edge_normals(r)
            v[k, : len(r)] = r
            nn[k, : len(r)] = normals
            v[k, len(r) :] = r[-1]  # padding: the last vertex and normal again
            nn[k, len(r) :] = normals[-1]
        radii = np.broadcast_to(np.asarray(radius, dtype=float), (n,)).copy()
        if not (np.isfinite(radii).all() and (radii >= 0.0).all()):
            raise ValueError(f"radius must be finite and >= 0, got {radius!r}")
        return cls(v, nn, np.array([len(r) for r in rows], dtype=np.intp), radii)

    @classmethod
    def of_shapes(cls, shapes: Sequence[Any]) -> Polygons:
        """Polygons from ``engine.Polygon`` shapes (one or more), padded to the longest: their
        corners and edge normals as each was made (checked then, and not again here: the same
        arrays as ``of`` their corners and radii, in a tenth of the time, so a World that gains
        a body in play does not wait on every body's shape being checked again)."""
        n = len(shapes)
        m = max(len(s.vertices) for s in shapes)
        v = np.empty((n, m, 2))
        nn = np.empty((n, m, 2))
        count = np.empty(n, dtype=np.intp)
        for k, shape in enumerate(shapes):
            c = len(shape.vertices)
            v[k, :c] = shape.vertices
            nn[k, :c] = shape.normals
            v[k, c:] = v[k, c - 1]  # padding: the last vertex and normal again
            nn[k, c:] = nn[k, c - 1]
            count[k] = c
        return cls(v, nn, count, np.array([s.radius for s in shapes], dtype=float))

    @classmethod
    def from_capsules(cls, capsules: Capsules) -> Polygons:
        """Each capsule as a two-vertex polygon (Box2D's b2MakeCapsule; ``capsule_corners``)."""
        v, nn = capsule_corners(capsules)
        return cls(v, nn, np.full(len(capsules), 2, dtype=np.intp), capsules.radius)


def capsule_corners(capsules: Capsules) -> tuple[np.ndarray, np.ndarray]:
    """Each capsule's corners and edge normals (N, 2, 2) as a two-vertex polygon's (Box2D's
    b2MakeCapsule): vertices a and b, normals r and -r, r the right perpendicular of b - a
    (the outside of a CCW edge)."""
    d = capsules.b - capsules.a
    length = np.hypot(d[:, 0], d[:, 1])
    right = np.stack([d[:, 1], -d[:, 0]], axis=1) / length[:, None]
    return np.stack([capsules.a, capsules.b], axis=1), np.stack([right, -right], axis=1)


@dataclass(frozen=True)
class HalfPlanes:
    """N half planes: the solid behind the line through ``point`` (N, 2) with unit
    ``normal`` (N, 2), in the body's frame."""

    point: np.ndarray
    normal: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "point", _array(self.point, "point", (-1, 2)))
        object.__setattr__(self, "normal", _array(self.normal, "normal", (-1, 2)))
        _rows("HalfPlanes", self.point, self.normal)

    def __len__(self) -> int:
        return len(self.point)

    def take(self, rows: Any) -> HalfPlanes:
        """The shapes of ``rows``."""
        return HalfPlanes(self.point[rows], self.normal[rows])


@dataclass(frozen=True)
class Frames:
    """The poses of N pairs of bodies, and B's pose in A's frame (where the math is done).

    ``xa``, ``xb`` (N, 2) positions; ``ca``, ``sa`` (N,) cos and sin of A's angle; ``p``
    (N, 2) B's origin in A's frame, R(-qa) (xb - xa); ``c``, ``s`` (N,) cos and sin of
    qb - qa, B's rotation seen from A.
    """

    xa: np.ndarray
    xb: np.ndarray
    ca: np.ndarray
    sa: np.ndarray
    p: np.ndarray
    c: np.ndarray
    s: np.ndarray

    def b_points(self, v: np.ndarray) -> np.ndarray:
        """Points of B's shape, (N, 2) or (N, K, 2) in B's frame, in A's frame."""
        c, s, p = self._b(v)
        return np.stack(
            [c * v[..., 0] - s * v[..., 1] + p[..., 0], s * v[..., 0] + c * v[..., 1] + p[..., 1]],
            axis=-1,
        )

    def b_vectors(self, v: np.ndarray) -> np.ndarray:
        """Directions of B's shape (normals), (N, 2) or (N, K, 2), turned into A's frame."""
        c, s, _ = self._b(v)
        return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)

    def _b(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if v.ndim == 3:
            return self.c[:, None], self.s[:, None], self.p[:, None, :]
        return self.c, self.s, self.p


def _pose(value: Any, name: str, n: int, shape: tuple[int, ...]) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.shape == shape[1:]:
        return np.broadcast_to(arr, (n, *shape[1:]))
    if arr.shape != (n, *shape[1:]):
        raise ValueError(
            f"{name} must have shape {(n, *shape[1:])} (one a pair) or {shape[1:]} (one for "
            f"all, a static body), got {arr.shape}"
        )
    return arr


def frames(xa: Any, qa: Any, xb: Any, qb: Any, n: int) -> Frames:
    """The ``Frames`` of n pairs from positions (n, 2) or (2,) and angles (n,) or scalars (rad).

    A single pose (a (2,) position, a scalar angle) is shared by all n pairs: a static body.
    """
    pa, pb = _pose(xa, "xa", n, (n, 2)), _pose(xb, "xb", n, (n, 2))
    a, b = _pose(qa, "qa", n, (n,)), _pose(qb, "qb", n, (n,))
    ca, sa = np.cos(a), np.sin(a)
    d = pb - pa
    # R(-qa) d: the transpose of A's rotation takes world directions into A's frame.
    p = np.stack([ca * d[:, 0] + sa * d[:, 1], -sa * d[:, 0] + ca * d[:, 1]], axis=1)
    rel = b - a
    return Frames(pa, pb, ca, sa, p, np.cos(rel), np.sin(rel))


def finish(
    f: Frames,
    normal: np.ndarray,
    point: np.ndarray,
    separation: np.ndarray,
    feature: np.ndarray,
    live: np.ndarray,
    margin: float,
) -> Manifold:
    """The world's Manifold from results in A's frame: ``normal`` (N, 2), ``point`` (N, 2, 2),
    ``separation`` and ``feature`` (N, 2), ``live`` (N, 2) the slots computed.

    A point farther apart than ``margin`` is dropped (Box2D keeps it; the solver would do
    nothing with it this step), and a lone second point moves to the first slot.
    """
    keep = live & (separation <= margin)
    # A kept second point with no first: swap the slots (ids travel with their points).
    swap = keep[:, 1] & ~keep[:, 0]
    if swap.any():
        order = np.where(swap[:, None], [1, 0], [0, 1])
        point = np.take_along_axis(point, order[:, :, None], axis=1)
        separation = np.take_along_axis(separation, order, axis=1)
        feature = np.take_along_axis(feature, order, axis=1)
        keep = np.take_along_axis(keep, order, axis=1)
    ca, sa = f.ca[:, None], f.sa[:, None]
    # R(qa) takes A's frame to the world's.
    ax = np.where(keep, ca * point[..., 0] - sa * point[..., 1], 0.0)
    ay = np.where(keep, sa * point[..., 0] + ca * point[..., 1], 0.0)
    anchor_a = np.stack([ax, ay], axis=-1)
    world = anchor_a + f.xa[:, None, :]
    anchor_b = np.where(keep[..., None], anchor_a + (f.xa - f.xb)[:, None, :], 0.0)
    world = np.where(keep[..., None], world, 0.0)
    nx = f.ca * normal[:, 0] - f.sa * normal[:, 1]
    ny = f.sa * normal[:, 0] + f.ca * normal[:, 1]
    return Manifold(
        np.stack([nx, ny], axis=1),
        keep.sum(axis=1),
        world,
        anchor_a,
        anchor_b,
        np.where(keep, separation, np.inf),
        np.where(keep, feature, -1).astype(np.int64),
    )
