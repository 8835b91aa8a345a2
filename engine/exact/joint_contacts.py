"""The pile's contacts of bodies held by joints, handed on to the joint solver
(engine.exact.joint_solver, as engine.exact.joint_rows' ``Touch``), and a disc's distance from a
polygon that turns.

A joint solve can turn a body far within one step (a flipper knocked onto its stop turns
0.7 rad in a step of 1/120 s). A contact row linear in the angles turned then misses where
the bat went, and a fast ball passes it. So a disc against a polygon or a capsule (its core a
two-vertex polygon, ``shapes_of``) is handed on whole: its row (engine.exact.joint_rows, at each
Newton iterate) is the disc's centre's distance from the polygon where the polygon is then
(``polygon_distance``), less the radii, exact for any turn:

* the polygon's face of greatest separation (the separating axis), and if the centre's
  projection falls past that face's ends, its nearer corner (Box2D's polygon and circle);
* the side it came from holds: when the centre's path in the polygon's frame, from where it
  was as the step began to where it is now, entered the polygon (it is inside, or went
  through), the distance is measured from the face it entered by, so a ball pushed through a
  thin bat goes back out the way it came in, not on through (a capsule's core has no ends to
  clip by: its path must cross the segment itself).

It is measured so that the row's value where the step began is the pile's separation there
(the manifold's), not the gap the pile's step left (linear in the angles turned). Other
contacts (two discs, two shapes, the static world) keep the pile's linear row.
"""

from __future__ import annotations

import numpy as np

from ..geometry.manifold_kinds import Polygons
from ..geometry.shaped import CAPSULE, DISC, POLYGON, ShapeTable

__all__ = ["joined_rows", "polygon_distance", "shapes_of"]


def shapes_of(table: ShapeTable) -> Polygons | None:
    """The polygons and the capsules of ``table`` as one set of polygons (a capsule as a
    two-vertex polygon with its radius, Box2D's b2MakeCapsule), the polygons first, padded to
    one size: what the rows of ``joined_rows`` index (engine.exact.collisions makes it with the
    table)."""
    parts = [] if table.polygons is None else [table.polygons]
    if len(table.capsules):
        parts.append(Polygons.from_capsules(table.capsules))
    if not parts:
        return None
    m = max(p.vertices.shape[1] for p in parts)
    v = np.concatenate([_pad(p.vertices, m) for p in parts])
    nn = np.concatenate([_pad(p.normals, m) for p in parts])
    count = np.concatenate([p.count for p in parts])
    return Polygons(v, nn, count, np.concatenate([p.radius for p in parts]))


def _pad(a: np.ndarray, m: int) -> np.ndarray:
    """(N, k, 2) padded to (N, m, 2) by repeating the last entry (Polygons' padding)."""
    if a.shape[1] == m:
        return a
    return np.concatenate([a, np.repeat(a[:, -1:], m - a.shape[1], axis=1)], axis=1)


def joined_rows(
    joined: np.ndarray,
    U: np.ndarray,
    ra: np.ndarray,
    rb: np.ndarray,
    nv: np.ndarray,
    gap: np.ndarray,
    sep: np.ndarray,
    r: np.ndarray,
    friction: np.ndarray,
    restitution: np.ndarray,
    total: np.ndarray,
    m: int,
    m_disc: int,
    m_pairs: int,
    anchors: list[np.ndarray],
    table: ShapeTable,
) -> tuple[np.ndarray, ...] | None:
    """The pile's rows (A ``ra``, B ``rb`` among the pile's bodies ``U``; the static slot past
    them) that touch a body held by a joint (``joined``, by World row): (body = B, other = A,
    normal n from A to B, contact point less each one's centre, gap (length units), friction,
    impulse, turn, polygon, disc's radius, restitution). A disc's contact point is r n from
    A's centre and -r n from B's; a shape's, its manifold's anchors (at the step's start, as
    the rows). ``gap``: the pile's gap now; ``sep``: at the step's start."""
    nU = len(U)
    ua = np.where(ra < nU, U[np.minimum(ra, nU - 1)], -1)
    ub = U[rb]
    hit = joined[ub] | ((ua >= 0) & joined[np.maximum(ua, 0)])
    if not hit.any():
        return None
    q = np.flatnonzero(hit)
    n = nv[q]
    r_a = np.zeros((len(q), 2))
    r_b = -r[rb[q], None] * n
    pair = q < m
    r_a[pair] = r[ra[q[pair]], None] * n[pair]
    k = q - m_disc
    sp = (k >= 0) & (k < m_pairs)
    r_a[sp], r_b[sp] = anchors[0][k[sp]], anchors[1][k[sp]]
    ss = k >= m_pairs
    r_b[ss] = anchors[2][k[ss] - m_pairs]
    ua_q, ub_q = ua[q], ub[q]
    turn = np.zeros(len(q), dtype=np.int8)
    poly = np.full(len(q), -1, dtype=np.intp)
    radius = np.zeros(len(q))
    kind_a = np.where(sp, table.kind[np.maximum(ua_q, 0)], -1)
    kind_b = np.where(sp, table.kind[ub_q], -1)
    n_poly = 0 if table.polygons is None else len(table.polygons)
    shape_a = (kind_a == POLYGON) | (kind_a == CAPSULE)
    shape_b = (kind_b == POLYGON) | (kind_b == CAPSULE)
    for side, p_row, d_row, rows in (
        (1, ub_q, ua_q, np.flatnonzero(shape_b & (kind_a == DISC))),
        (-1, ua_q, ub_q, np.flatnonzero(shape_a & (kind_b == DISC))),
    ):
        # (A capsule is the two-vertex polygon past the polygons in ``shapes_of``.)
        turn[rows] = side
        pr = p_row[rows]
        poly[rows] = table.index[pr] + np.where(table.kind[pr] == CAPSULE, n_poly, 0)
        radius[rows] = table.circles.radius[d_row[rows]]
    gap_q = np.where(turn != 0, sep[q], gap[q])
    return ub_q, ua_q, n, r_b, r_a, gap_q, friction[q], total[q], turn, poly, radius, restitution[q]


def polygon_distance(
    polygons: Polygons, index: np.ndarray, p: np.ndarray, p0: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The distance of points ``p`` (k, 2; in each polygon's frame) from polygons ``index``
    (their rounding not counted; < 0 inside) for a point that came from ``p0`` (module doc):
    (distance, the feature's outward unit normal (k, 2), whether it is a corner, the
    corner (k, 2))."""
    V = polygons.vertices[index]
    N = polygons.normals[index]
    count = polygons.count[index]
    k = np.arange(len(index))
    s = np.einsum("kmj,kmj->km", N, p[:, None, :] - V)  # each face's separation
    f = np.argmax(s, axis=1)
    v1 = V[k, f]
    v2 = V[k, (f + 1) % count]
    before = np.einsum("kj,kj->k", p - v1, v2 - v1) < 0.0
    past = np.einsum("kj,kj->k", p - v2, v1 - v2) < 0.0
    corner = (s[k, f] > 0.0) & (before | past)
    at = np.where(before[:, None], v1, v2)
    e = p - at
    length = np.hypot(e[:, 0], e[:, 1])
    safe = np.where(length > 0.0, length, 1.0)
    normal = np.where(corner[:, None], e / safe[:, None], N[k, f])
    dist = np.where(corner, length, s[k, f])
    # The path p0 -> p clipped by each face's half-plane (Cyrus-Beck): it met the polygon
    # when the last entry comes before the first exit. Then the face it entered by holds.
    s0 = np.einsum("kmj,kmj->km", N, p0[:, None, :] - V)
    enters = (s0 > 0.0) & (s <= 0.0)
    leaves = (s0 <= 0.0) & (s > 0.0)
    t = s0 / np.where(s0 != s, s0 - s, 1.0)
    t_in = np.where(enters, t, -np.inf).max(axis=1)
    t_out = np.where(leaves, t, np.inf).min(axis=1)
    missed = ((s0 > 0.0) & (s > 0.0)).any(axis=1)
    crossed = ~missed & (t_in <= t_out) & np.isfinite(t_in)
    g = np.argmax(np.where(enters, t, -np.inf), axis=1)
    if (count == 2).any():
        # A capsule's core has no ends to clip by: the path crossed its line, but within
        # the segment? (A polygon's entry point always is on its entry face.)
        q = p0 + np.where(np.isfinite(t_in), t_in, 0.0)[:, None] * (p - p0)
        a, b = V[k, g], V[k, (g + 1) % count]
        along = np.einsum("kj,kj->k", q - a, b - a)
        within = (along >= 0.0) & (along <= np.einsum("kj,kj->k", b - a, b - a))
        crossed &= (count != 2) | within
    if crossed.any():
        dist = np.where(crossed, s[k, g], dist)
        normal = np.where(crossed[:, None], N[k, g], normal)
        corner = corner & ~crossed
    return dist, normal, corner, at
