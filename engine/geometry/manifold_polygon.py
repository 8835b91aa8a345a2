"""Polygon against polygon: the separating axis test, then the incident edge clipped against the
reference edge (Box2D v3's b2CollidePolygons and b2ClipPolygons), for N pairs at once.

``engine.geometry.manifold`` re-exports ``collide_polygons``; its doc says what a manifold holds.
The steps, each one array operation over all pairs (padding as ``engine.geometry.manifold_kinds``
says):

1. B's vertices and normals go into A's frame, and both polygons are shifted so that A's
   first vertex is the origin (Box2D's shift: smaller numbers, less round-off).
2. Separating axes: for each edge normal n_i of A, the separation of B from that edge's line
   is min_j n_i.(w_j - v_i); the largest over i is A's best axis (sepA), and the same with the
   roles swapped gives sepB. For convex shapes the distance is at least max(sepA, sepB), so
   beyond ``margin`` plus both radii there is no point.
3. The reference edge is the best axis's edge (A's unless sepB > sepA); the incident edge is
   the other polygon's edge whose normal is most anti-parallel to it. The incident edge is
   clipped to the reference edge's extent along its tangent; each end left is a point, with
   its separation along the reference normal, placed midway between the two surfaces.
4. When the cores are apart (a separation > 0), the nearest points of the two edges are
   found too (Ericson's segment distance). If they are two vertices and their distance is
   clearly smaller than the clipped points' (by more than 0.1 LINEAR_SLOP), or the clip
   found no point, the manifold is that one vertex-vertex point along their direction,
   exact; so the least separation is the exact distance, or at most 0.1 LINEAR_SLOP more.
   (For separated convex polygons the best axes bracket the direction of the nearest
   points, so these two edges hold them: the distance found is the polygons' distance.)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import kernels
from .manifold_kinds import (
    LINEAR_SLOP,
    SPECULATIVE_DISTANCE,
    Manifold,
    Polygons,
    finish,
    frames,
)

__all__ = ["collide_polygons", "polygon_loop", "segment_distance"]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def segment_distance(
    p1: np.ndarray, q1: np.ndarray, p2: np.ndarray, q2: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The nearest points of segments p1-q1 and p2-q2, (N, 2) each (Box2D's b2SegmentDistance).

    Returns (f1, f2, c1, c2, dd): the fractions along each segment, the points
    c1 = p1 + f1 (q1 - p1) and c2 = p2 + f2 (q2 - p2), and their squared distance. Ericson
    5.1.9: minimise |p1 + f1 d1 - p2 - f2 d2|^2; its gradient is zero at
    f1 = (d12 rd2 - rd1 dd2) / (dd1 dd2 - d12^2) (clamped to [0, 1]; 0 for parallel lines),
    then f2 = (d12 f1 + rd2) / dd2, and when f2 leaves [0, 1] it is clamped and f1 found again
    for that end. A segment shorter than 1e-12 of the other is a point (Box2D's degenerate
    cases): its fraction is 0 and the other's is the nearest point to it, clamp(-rd1 / dd1)
    or clamp(rd2 / dd2); the general formula would divide rounding by almost nothing.
    """
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    dd1, dd2 = _dot(d1, d1), _dot(d2, d2)
    rd1, rd2, d12 = _dot(r, d1), _dot(r, d2), _dot(d1, d2)
    point1, point2 = dd1 <= 1e-24 * dd2, dd2 <= 1e-24 * dd1  # both when both are 0
    safe1, safe2 = np.where(dd1 > 0.0, dd1, 1.0), np.where(dd2 > 0.0, dd2, 1.0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        denom = dd1 * dd2 - d12 * d12
        f1 = np.where(denom != 0.0, np.clip((d12 * rd2 - rd1 * dd2) / denom, 0.0, 1.0), 0.0)
        f2 = (d12 * f1 + rd2) / safe2
        f1 = np.where(
            f2 < 0.0,
            np.clip(-rd1 / safe1, 0.0, 1.0),
            np.where(f2 > 1.0, np.clip((d12 - rd1) / safe1, 0.0, 1.0), f1),
        )
        f2 = np.clip(f2, 0.0, 1.0)
        f1 = np.where(point2, np.clip(-rd1 / safe1, 0.0, 1.0), f1)
        f2 = np.where(point2, 0.0, f2)
        f2 = np.where(point1, np.where(point2, 0.0, np.clip(rd2 / safe2, 0.0, 1.0)), f2)
        f1 = np.where(point1, 0.0, f1)
    c1 = p1 + f1[:, None] * d1
    c2 = p2 + f2[:, None] * d2
    e = c2 - c1
    return f1, f2, c1, c2, _dot(e, e)


def _at(v: np.ndarray, index: np.ndarray) -> np.ndarray:
    """Row k's entry index[k] of v (N, M, ...)."""
    return v[np.arange(len(v)), index]


def collide_polygons(
    a: Polygons,
    xa: Any,
    qa: Any,
    b: Polygons,
    xb: Any,
    qb: Any,
    margin: float = SPECULATIVE_DISTANCE,
    fast: bool = False,
) -> Manifold:
    """Manifolds of N pairs of (rounded) convex polygons, up to 2 points each (module doc).

    ``a``, ``b``: the shapes in their bodies' frames; ``xa``, ``xb`` (N, 2) or (2,) the
    bodies' positions and ``qa``, ``qb`` (N,) or scalars their angles (rad); ``margin`` the
    speculative distance (length units): pairs farther apart get no point. ``fast``: the
    loop kernel ``polygon_loop``.
    """
    n = len(a)
    if len(b) != n:
        raise ValueError(f"a and b must hold one shape a pair, got {n} and {len(b)}")
    f = frames(xa, qa, xb, qb, n)  # validates the poses on both paths
    if fast:
        rows = np.arange(n)

        def pose(v: np.ndarray) -> np.ndarray:
            # C-contiguous and writable, never a read-only broadcast view: the kernel's one
            # specialisation (engine.kernels: no compile in play).
            return np.require(v, float, ["C", "W"])

        q_a = pose(np.broadcast_to(np.asarray(qa, dtype=float), (n,)))
        q_b = pose(np.broadcast_to(np.asarray(qb, dtype=float), (n,)))
        return Manifold(
            *polygon_loop(
                a.vertices, a.normals, a.count, a.radius, rows, pose(f.xa), q_a,
                b.vertices, b.normals, b.count, b.radius, rows, pose(f.xb), q_b, float(margin),
            )
        )  # fmt: skip
    rows = np.arange(n)
    o = a.vertices[:, 0, :]  # step 1: A's first vertex becomes the origin
    VA = a.vertices - o[:, None, :]
    NA = a.normals
    VB = f.b_points(b.vertices) - o[:, None, :]
    NB = f.b_vectors(b.normals)
    cA, cB = a.count, b.count
    rA, rB = a.radius, b.radius
    R = rA + rB

    # Step 2: s[k, i, j] = n_i.(w_j - v_i); the deepest vertex per axis, the best axis.
    sA = _dot(NA[:, :, None, :], VB[:, None, :, :] - VA[:, :, None, :]).min(axis=2)
    sB = _dot(NB[:, :, None, :], VA[:, None, :, :] - VB[:, :, None, :]).min(axis=2)
    edgeA, edgeB = sA.argmax(axis=1), sB.argmax(axis=1)
    sepA, sepB = sA[rows, edgeA], sB[rows, edgeB]
    far = (sepA > margin + R) | (sepB > margin + R)

    # Step 3: the reference edge is on B when B's axis separates more; the incident edge is
    # the other polygon's edge whose normal is most anti-parallel to the reference normal.
    flip = sepB > sepA
    incB = _dot(_at(NA, edgeA)[:, None, :], NB).argmin(axis=1)
    incA = _dot(_at(NB, edgeB)[:, None, :], NA).argmin(axis=1)
    edgeA = np.where(flip, incA, edgeA)
    edgeB = np.where(flip, edgeB, incB)
    iA1, iA2 = edgeA, (edgeA + 1) % cA
    iB1, iB2 = edgeB, (edgeB + 1) % cB
    vA1, vA2, vB1, vB2 = _at(VA, iA1), _at(VA, iA2), _at(VB, iB1), _at(VB, iB2)
    fl = flip[:, None]
    v11, v12 = np.where(fl, vB1, vA1), np.where(fl, vB2, vA2)  # reference edge
    v21, v22 = np.where(fl, vA1, vB1), np.where(fl, vA2, vB2)  # incident edge
    normal = np.where(fl, _at(NB, edgeB), _at(NA, edgeA))
    r1, r2 = np.where(flip, rB, rA), np.where(flip, rA, rB)
    i11, i12 = np.where(flip, iB1, iA1), np.where(flip, iB2, iA2)
    i21, i22 = np.where(flip, iA1, iB1), np.where(flip, iA2, iB2)

    # Clip, along the tangent t = (-n_y, n_x) from v11: the reference edge spans
    # [0, upper1]; the incident edge runs the other way (both CCW), v22 at lower2 and v21 at
    # upper2. Where it pokes out past an end, the point is moved along it to that end.
    t = np.stack([-normal[:, 1], normal[:, 0]], axis=1)
    upper1 = _dot(v12 - v11, t)
    upper2, lower2 = _dot(v21 - v11, t), _dot(v22 - v11, t)
    disjoint = (upper2 < 0.0) | (upper1 < lower2)
    span = upper2 - lower2
    safe = np.where(span > 0.0, span, 1.0)
    cut_lower = ((lower2 < 0.0) & (span > 0.0))[:, None]
    cut_upper = ((upper2 > upper1) & (span > 0.0))[:, None]
    v_lower = np.where(cut_lower, v22 + ((0.0 - lower2) / safe)[:, None] * (v21 - v22), v22)
    v_upper = np.where(cut_upper, v22 + ((upper1 - lower2) / safe)[:, None] * (v21 - v22), v21)
    sep_lower, sep_upper = _dot(v_lower - v11, normal), _dot(v_upper - v11, normal)
    # Midway between the surfaces: the reference surface is r1 out along n, the incident one
    # r2 in from the clipped point, so the middle is the point + (r1 - r2 - s) n / 2.
    p_lower = v_lower + (0.5 * (r1 - r2 - sep_lower))[:, None] * normal
    p_upper = v_upper + (0.5 * (r1 - r2 - sep_upper))[:, None] * normal
    # Seen from A: the points in the order A's vertices meet them, ids 256 (A's) + (B's).
    point = np.where(
        fl[:, :, None],
        np.stack([p_upper, p_lower], axis=1),
        np.stack([p_lower, p_upper], axis=1),
    )
    sep = (
        np.where(
            fl,
            np.stack([sep_upper, sep_lower], axis=1),
            np.stack([sep_lower, sep_upper], axis=1),
        )
        - R[:, None]
    )
    feature = np.where(
        fl,
        np.stack([i21 << 8 | i12, i22 << 8 | i11], axis=1),
        np.stack([i11 << 8 | i22, i12 << 8 | i21], axis=1),
    )
    normal = np.where(fl, -normal, normal)
    live = np.repeat(~disjoint[:, None], 2, axis=1)

    # Step 4: apart, and the nearest points are two vertices clearly nearer than the clip's
    # (or the clip found nothing). Box2D looks only past 0.1 LINEAR_SLOP, where its floats
    # can normalise the direction; in doubles any gap can, and a corner just off a corner
    # (whose clip is empty) keeps its point.
    apart = (sepA > 0.0) | (sepB > 0.0)
    f1, f2, c1, c2, dd = segment_distance(vA1, vA2, vB1, vB2)
    dist = np.sqrt(dd)
    too_far = apart & (dist - R > margin)
    least = np.where(live[:, 0], sep.min(axis=1), np.inf)
    corner = ((f1 == 0.0) | (f1 == 1.0)) & ((f2 == 0.0) | (f2 == 1.0))
    vv = apart & ~too_far & (corner | ~live[:, 0]) & (dist - R + 0.1 * LINEAR_SLOP < least)
    if vv.any():
        with np.errstate(divide="ignore", invalid="ignore"):
            u = (c2 - c1) / np.where(dist > 0.0, dist, 1.0)[:, None]
        mid = 0.5 * (c1 + rA[:, None] * u + c2 - rB[:, None] * u)
        ids = np.where(f1 == 0.0, iA1, iA2) << 8 | np.where(f2 == 0.0, iB1, iB2)
        vvc = vv[:, None]
        normal = np.where(vvc, u, normal)
        point = np.where(vvc[:, :, None], np.stack([mid, mid], axis=1), point)
        sep = np.where(vvc, (dist - R)[:, None], sep)
        feature = np.where(vvc, ids[:, None], feature)
        live = np.where(vvc, np.array([True, False]), live)
    live &= ~(far | too_far)[:, None]
    return finish(f, normal, point + o[:, None, :], sep, feature, live, margin)


# -- the loop kernel (engine.kernels: the fast path) ------------------------------------------


def _sample_polygons() -> tuple[object, ...]:
    """The smallest call of ``polygon_loop``: two unit boxes side by side, touching."""
    v = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]])
    nn = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]])
    c, r, i, q = np.array([4]), np.zeros(1), np.array([0]), np.zeros(1)
    return v, nn, c, r, i, np.zeros((1, 2)), q, v, nn, c, r, i, np.array([[1.0, 0.0]]), q, 0.02


@kernels.loop(sample=_sample_polygons)
def polygon_loop(
    VA: np.ndarray,
    NA: np.ndarray,
    cA: np.ndarray,
    rA: np.ndarray,
    ia: np.ndarray,
    xa: np.ndarray,
    qa: np.ndarray,
    VB: np.ndarray,
    NB: np.ndarray,
    cB: np.ndarray,
    rB: np.ndarray,
    ib: np.ndarray,
    xb: np.ndarray,
    qb: np.ndarray,
    margin: float,
) -> tuple[np.ndarray, ...]:
    """``collide_polygons`` as a loop over pairs: pair k is shape ``ia[k]`` of the table
    (VA, NA, cA, rA) at pose (xa[k], qa[k]) (length units, rad) against shape ``ib[k]`` of
    (VB, NB, cB, rB) at (xb[k], qb[k]); returns the Manifold's arrays (normal, count, point,
    anchor_a, anchor_b, separation, feature), each step its twin's products in its order."""
    n = len(ia)
    normal_w = np.empty((n, 2))
    count = np.zeros(n, dtype=np.int64)
    world = np.zeros((n, 2, 2))
    anchor_a = np.zeros((n, 2, 2))
    anchor_b = np.zeros((n, 2, 2))
    sep_out = np.full((n, 2), np.inf)
    feat_out = np.full((n, 2), -1, dtype=np.int64)
    M = VB.shape[1]
    WB = np.empty((M, 2))  # B's vertices and normals in A's frame, shifted (step 1)
    UB = np.empty((M, 2))
    for k in range(n):
        sa_, sb_ = ia[k], ib[k]
        na, nb = cA[sa_], cB[sb_]
        ra, rb = rA[sa_], rB[sb_]
        R = ra + rb
        # Frames (engine.geometry.manifold_kinds.frames): B's pose in A's frame.
        ca, sn = np.cos(qa[k]), np.sin(qa[k])
        dx, dy = xb[k, 0] - xa[k, 0], xb[k, 1] - xa[k, 1]
        px, py = ca * dx + sn * dy, -sn * dx + ca * dy
        rel = qb[k] - qa[k]
        c, s = np.cos(rel), np.sin(rel)
        ox, oy = VA[sa_, 0, 0], VA[sa_, 0, 1]
        for j in range(nb):
            vx, vy = VB[sb_, j, 0], VB[sb_, j, 1]
            WB[j, 0] = (c * vx - s * vy + px) - ox
            WB[j, 1] = (s * vx + c * vy + py) - oy
            wx, wy = NB[sb_, j, 0], NB[sb_, j, 1]
            UB[j, 0], UB[j, 1] = c * wx - s * wy, s * wx + c * wy
        # Step 2: the best axis of each; a strict > keeps the first of equals, as argmax.
        edgeA, sepA = 0, -np.inf
        for i in range(na):
            ax, ay = VA[sa_, i, 0] - ox, VA[sa_, i, 1] - oy
            nx, ny = NA[sa_, i, 0], NA[sa_, i, 1]
            least = np.inf
            for j in range(nb):
                d = nx * (WB[j, 0] - ax) + ny * (WB[j, 1] - ay)
                if d < least:
                    least = d
            if least > sepA or i == 0:
                edgeA, sepA = i, least
        edgeB, sepB = 0, -np.inf
        for j in range(nb):
            nx, ny = UB[j, 0], UB[j, 1]
            least = np.inf
            for i in range(na):
                d = nx * ((VA[sa_, i, 0] - ox) - WB[j, 0]) + ny * ((VA[sa_, i, 1] - oy) - WB[j, 1])
                if d < least:
                    least = d
            if least > sepB or j == 0:
                edgeB, sepB = j, least
        far = sepA > margin + R or sepB > margin + R
        # Step 3: the reference edge, and the incident edge most anti-parallel to it.
        flip = sepB > sepA
        if flip:
            nx, ny = UB[edgeB, 0], UB[edgeB, 1]
            best = np.inf
            for i in range(na):
                d = nx * NA[sa_, i, 0] + ny * NA[sa_, i, 1]
                if d < best:
                    edgeA, best = i, d
        else:
            nx, ny = NA[sa_, edgeA, 0], NA[sa_, edgeA, 1]
            best = np.inf
            for j in range(nb):
                d = nx * UB[j, 0] + ny * UB[j, 1]
                if d < best:
                    edgeB, best = j, d
        iA1, iA2 = edgeA, (edgeA + 1) % na
        iB1, iB2 = edgeB, (edgeB + 1) % nb
        a1x, a1y = VA[sa_, iA1, 0] - ox, VA[sa_, iA1, 1] - oy
        a2x, a2y = VA[sa_, iA2, 0] - ox, VA[sa_, iA2, 1] - oy
        b1x, b1y, b2x, b2y = WB[iB1, 0], WB[iB1, 1], WB[iB2, 0], WB[iB2, 1]
        if flip:  # reference v11-v12 on B, incident v21-v22 on A
            x11, y11, x12, y12, x21, y21, x22, y22 = b1x, b1y, b2x, b2y, a1x, a1y, a2x, a2y
            nx, ny = UB[edgeB, 0], UB[edgeB, 1]
            r1, r2 = rb, ra
            i11, i12, i21, i22 = iB1, iB2, iA1, iA2
        else:
            x11, y11, x12, y12, x21, y21, x22, y22 = a1x, a1y, a2x, a2y, b1x, b1y, b2x, b2y
            nx, ny = NA[sa_, edgeA, 0], NA[sa_, edgeA, 1]
            r1, r2 = ra, rb
            i11, i12, i21, i22 = iA1, iA2, iB1, iB2
        # Clip along t = (-n_y, n_x) from v11 (the twin's comment derives it).
        tx, ty = -ny, nx
        upper1 = (x12 - x11) * tx + (y12 - y11) * ty
        upper2 = (x21 - x11) * tx + (y21 - y11) * ty
        lower2 = (x22 - x11) * tx + (y22 - y11) * ty
        live = not (upper2 < 0.0 or upper1 < lower2)
        span = upper2 - lower2
        safe = span if span > 0.0 else 1.0
        lx, ly = x22, y22
        if lower2 < 0.0 and span > 0.0:
            f = (0.0 - lower2) / safe
            lx, ly = x22 + f * (x21 - x22), y22 + f * (y21 - y22)
        ux, uy = x21, y21
        if upper2 > upper1 and span > 0.0:
            f = (upper1 - lower2) / safe
            ux, uy = x22 + f * (x21 - x22), y22 + f * (y21 - y22)
        sep_lower = (lx - x11) * nx + (ly - y11) * ny
        sep_upper = (ux - x11) * nx + (uy - y11) * ny
        h = 0.5 * (r1 - r2 - sep_lower)
        plx, ply = lx + h * nx, ly + h * ny
        h = 0.5 * (r1 - r2 - sep_upper)
        pux, puy = ux + h * nx, uy + h * ny
        # Seen from A: the points in the order A's vertices meet them.
        if flip:
            p0x, p0y, p1x, p1y = pux, puy, plx, ply
            s0, s1 = sep_upper - R, sep_lower - R
            f0, f1_ = i21 << 8 | i12, i22 << 8 | i11
            nx, ny = -nx, -ny
        else:
            p0x, p0y, p1x, p1y = plx, ply, pux, puy
            s0, s1 = sep_lower - R, sep_upper - R
            f0, f1_ = i11 << 8 | i22, i12 << 8 | i21
        live0 = live1 = live
        # Step 4: the nearest points of the two edges (segment_distance, Ericson 5.1.9).
        apart = sepA > 0.0 or sepB > 0.0
        d1x, d1y, d2x, d2y = a2x - a1x, a2y - a1y, b2x - b1x, b2y - b1y
        rx, ry = a1x - b1x, a1y - b1y
        dd1, dd2 = d1x * d1x + d1y * d1y, d2x * d2x + d2y * d2y
        rd1, rd2, d12 = rx * d1x + ry * d1y, rx * d2x + ry * d2y, d1x * d2x + d1y * d2y
        point1, point2 = dd1 <= 1e-24 * dd2, dd2 <= 1e-24 * dd1
        safe1 = dd1 if dd1 > 0.0 else 1.0
        safe2 = dd2 if dd2 > 0.0 else 1.0
        denom = dd1 * dd2 - d12 * d12
        g1 = 0.0
        if denom != 0.0:
            g1 = min(max((d12 * rd2 - rd1 * dd2) / denom, 0.0), 1.0)
        g2 = (d12 * g1 + rd2) / safe2
        if g2 < 0.0:
            g1 = min(max(-rd1 / safe1, 0.0), 1.0)
        elif g2 > 1.0:
            g1 = min(max((d12 - rd1) / safe1, 0.0), 1.0)
        g2 = min(max(g2, 0.0), 1.0)
        if point2:
            g1, g2 = min(max(-rd1 / safe1, 0.0), 1.0), 0.0
        if point1:
            g2 = 0.0 if point2 else min(max(rd2 / safe2, 0.0), 1.0)
            g1 = 0.0
        c1x, c1y = a1x + g1 * d1x, a1y + g1 * d1y
        c2x, c2y = b1x + g2 * d2x, b1y + g2 * d2y
        ex, ey = c2x - c1x, c2y - c1y
        dist = np.sqrt(ex * ex + ey * ey)
        too_far = apart and dist - R > margin
        least = min(s0, s1) if live0 else np.inf
        corner = (g1 == 0.0 or g1 == 1.0) and (g2 == 0.0 or g2 == 1.0)
        if apart and not too_far and (corner or not live0) and dist - R + 0.1 * LINEAR_SLOP < least:
            q = dist if dist > 0.0 else 1.0
            ux, uy = ex / q, ey / q
            mx = 0.5 * (c1x + ra * ux + c2x - rb * ux)
            my = 0.5 * (c1y + ra * uy + c2y - rb * uy)
            nx, ny = ux, uy
            p0x, p0y, p1x, p1y = mx, my, mx, my
            s0 = s1 = dist - R
            f0 = f1_ = (iA1 if g1 == 0.0 else iA2) << 8 | (iB1 if g2 == 0.0 else iB2)
            live0, live1 = True, False
        if far or too_far:
            live0 = live1 = False
        # finish (engine.geometry.manifold_kinds): keep what is within margin, a lone second point
        # moved to the first slot, and A's frame turned into the world's by R(qa).
        keep0, keep1 = live0 and s0 <= margin, live1 and s1 <= margin
        if keep1 and not keep0:
            p0x, p0y, p1x, p1y = p1x, p1y, p0x, p0y
            s0, s1, f0, f1_ = s1, s0, f1_, f0
            keep0, keep1 = True, False
        normal_w[k, 0] = ca * nx - sn * ny
        normal_w[k, 1] = sn * nx + ca * ny
        for slot in range(2):
            if slot == 0:
                if not keep0:
                    continue
                x_, y_, s_, f_ = p0x + ox, p0y + oy, s0, f0
            else:
                if not keep1:
                    continue
                x_, y_, s_, f_ = p1x + ox, p1y + oy, s1, f1_
            ax_, ay_ = ca * x_ - sn * y_, sn * x_ + ca * y_
            anchor_a[k, slot, 0], anchor_a[k, slot, 1] = ax_, ay_
            world[k, slot, 0], world[k, slot, 1] = ax_ + xa[k, 0], ay_ + xa[k, 1]
            anchor_b[k, slot, 0] = ax_ + (xa[k, 0] - xb[k, 0])
            anchor_b[k, slot, 1] = ay_ + (xa[k, 1] - xb[k, 1])
            sep_out[k, slot], feat_out[k, slot] = s_, f_
            count[k] += 1
    return normal_w, count, world, anchor_a, anchor_b, sep_out, feat_out
