"""Every pair's manifold in a few calls: the soft step's narrowphase (engine.pipeline.game_step).

The manifold functions of ``engine.geometry.manifold`` take N pairs of one kind against one kind,
and each call pays numpy's (or the wrapper's) fixed cost once. A game's scene mixes kinds (boxes,
capsules, discs, the level's segments and coins), so the soft step puts every shape, the
bodies' and the colliders', into two tables:

* ``polygons``: every polygon and every capsule (a capsule as Box2D's two-vertex polygon,
  ``Polygons.from_capsules``), padded to the largest;
* ``circles``: every disc and every circle collider (a centre in its body's frame, a radius);

and sorts the pairs into three groups, each one call: polygon against polygon
(``engine.geometry.manifold_polygon``: Box2D's b2CollidePolygons), polygon against circle and circle
against circle (the round pairs: b2CollidePolygonAndCircle and b2CollideCircles), and a half
plane against each kind of body shape (``collide_pairs``, the numpy path's stage, which puts
the manifolds back in the broadphase's order). On the fast path the soft step calls the loop
kernels (``polygon_loop``, ``round_loop`` here) from its own compiled contacts stage
(engine.pipeline.game_contacts), straight on the tables; ``collide_polygon_pairs`` and
``collide_round_pairs`` take either. ``round_loop`` is ``collide_polygon_circle`` and
``collide_circles`` written as one loop, each product in its twin's order, so both paths
give the same bits.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from .. import kernels
from .manifold import StaticShapes, collide, collide_circles, collide_polygon_circle
from .manifold_kinds import (
    LINEAR_SLOP,
    SPECULATIVE_DISTANCE,
    Circles,
    Manifold,
    Polygons,
    capsule_corners,
)
from .manifold_polygon import collide_polygons, polygon_loop
from .passing import passing, passing_loop
from .shaped import CAPSULE, DISC, POLYGON, ShapeTable

__all__ = [
    "Places",
    "Tables",
    "Touches",
    "collide_pairs",
    "collide_polygon_pairs",
    "collide_round_pairs",
    "places_of",
    "round_loop",
]


class Tables:
    """The shapes of a scene in two tables (module doc): ``polygons`` (a ``Polygons``, or
    None without any) and ``circles`` (a ``Circles``)."""

    def __init__(self, polygons: Polygons | None, circles: Circles) -> None:
        self.polygons = polygons
        self.circles = circles
        if polygons is not None:
            # The loop kernels' own copies: C-contiguous, int64 counts.
            self.vertices = np.ascontiguousarray(polygons.vertices)
            self.normals = np.ascontiguousarray(polygons.normals)
            self.count = np.ascontiguousarray(polygons.count, dtype=np.int64)
            self.radius = np.ascontiguousarray(polygons.radius)
        self.center = np.ascontiguousarray(circles.center)
        self.round = np.ascontiguousarray(circles.radius)
        #: The polygon table as the loop kernels take it (vertices, normals, count, radius),
        #: or one-row stand-ins of the same types where the scene has no polygon.
        self.kernel_polygons: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] = (
            (self.vertices, self.normals, self.count, self.radius)
            if polygons is not None
            else (np.zeros((1, 2, 2)), np.zeros((1, 2, 2)), np.zeros(1, np.int64), np.zeros(1))
        )


def _manifold(parts: tuple[np.ndarray, ...]) -> Manifold:
    return Manifold(*parts)


#: Polygon pairs up to which the numpy path runs ``polygon_loop`` as plain Python rather than
#: ``collide_polygons`` over arrays (measured on the platformer's calls, 2026-12-06: one pair
#: 43 us against 263, three 121 against 300, eight about even; about 38 us a pair).
FEW_POLYGON = 8


def collide_polygon_pairs(
    t: Tables, ia: np.ndarray, xa: np.ndarray, qa: np.ndarray,
    ib: np.ndarray, xb: np.ndarray, qb: np.ndarray, margin: float, fast: bool,
) -> Manifold:  # fmt: skip
    """Polygon ``ia[k]`` of the table at (xa[k], qa[k]) against polygon ``ib[k]`` at
    (xb[k], qb[k]) (m, rad): their manifolds, the normal from A to B."""
    assert t.polygons is not None
    if fast or len(ia) <= FEW_POLYGON:
        # (A few pairs on the numpy path: the kernel's loop run as plain Python, the same
        # products in the same order, where numpy's calls cost more than the loop.)
        kernel: Any = polygon_loop if fast else polygon_loop.py
        return _manifold(
            kernel(t.vertices, t.normals, t.count, t.radius, ia, xa, qa,
                   t.vertices, t.normals, t.count, t.radius, ib, xb, qb, margin)
        )  # fmt: skip
    p = t.polygons
    return collide_polygons(p.take(ia), xa, qa, p.take(ib), xb, qb, margin)


#: Round pairs up to which the numpy path runs ``round_loop`` as plain Python rather than
#: ``collide_circles`` and ``collide_polygon_circle`` over arrays (measured on the platformer's
#: 3 round pairs: 24 us against 114; the loop costs about 8 us a pair).
FEW_ROUND = 12


def collide_round_pairs(
    t: Tables, circle_a: np.ndarray, ia: np.ndarray, xa: np.ndarray, qa: np.ndarray,
    ib: np.ndarray, xb: np.ndarray, qb: np.ndarray, margin: float, fast: bool,
) -> Manifold:  # fmt: skip
    """Shape ``ia[k]`` (a circle of the table where ``circle_a[k]``, else a polygon) at
    (xa[k], qa[k]) against circle ``ib[k]`` at (xb[k], qb[k]): their manifolds (A to B)."""
    if fast or len(ia) <= FEW_ROUND:
        # (A few pairs on the numpy path: the kernel's loop run as plain Python, the same
        # products in the same order, where numpy's calls cost more than the loop.)
        vertices, normals, count, radius = t.kernel_polygons
        kernel: Any = round_loop if fast else round_loop.py
        return _manifold(
            kernel(vertices, normals, count, radius, t.center, t.round, circle_a, ia, xa, qa,
                   ib, xb, qb, margin)
        )  # fmt: skip
    out = []
    order = []
    for circles in (False, True):
        sel = np.flatnonzero(circle_a == circles)
        if not len(sel):
            continue
        b = t.circles.take(ib[sel])
        if circles:
            a_c = t.circles.take(ia[sel])
            m = collide_circles(a_c, xa[sel], qa[sel], b, xb[sel], qb[sel], margin)
        else:
            assert t.polygons is not None
            a_p = t.polygons.take(ia[sel])
            m = collide_polygon_circle(a_p, xa[sel], qa[sel], b, xb[sel], qb[sel], margin)
        out.append(m)
        order.append(sel)
    if len(out) == 1:
        return out[0]
    joined = Manifold.concat(out)
    back = np.empty(len(ia), dtype=np.intp)
    back[np.concatenate(order)] = np.arange(len(ia))
    return joined.take(back)


def _sample_round() -> tuple[object, ...]:
    """The smallest call of ``round_loop``: a unit box and a disc beside it, and two discs."""
    v = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]])
    nn = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]])
    c, r = np.array([4]), np.zeros(1)
    centers, radii = np.zeros((2, 2)), np.array([0.25, 0.5])
    flag = np.array([False, True])
    i, x, q = np.array([0, 1]), np.zeros((2, 2)), np.zeros(2)
    xb = np.array([[0.7, 0.0], [0.0, 0.7]])
    return v, nn, c, r, centers, radii, flag, i, x, q, np.array([0, 0]), xb, q, 0.02


@kernels.loop(sample=_sample_round)
def round_loop(
    VA: np.ndarray, NA: np.ndarray, cA: np.ndarray, rA: np.ndarray,
    C: np.ndarray, rC: np.ndarray, circle_a: np.ndarray,
    ia: np.ndarray, xa: np.ndarray, qa: np.ndarray,
    ib: np.ndarray, xb: np.ndarray, qb: np.ndarray, margin: float,
) -> tuple[np.ndarray, ...]:  # fmt: skip
    """``collide_polygon_circle`` and ``collide_circles`` as one loop over pairs: pair k is
    polygon ``ia[k]`` of (VA, NA, cA, rA), or circle ``ia[k]`` of (C, rC) where
    ``circle_a[k]``, at (xa[k], qa[k]), against circle ``ib[k]`` of (C, rC) at (xb[k],
    qb[k]); returns the Manifold's arrays, each product its twins' in their order."""
    n = len(ia)
    normal_w = np.empty((n, 2))
    count = np.zeros(n, dtype=np.int64)
    world = np.zeros((n, 2, 2))
    anchor_a = np.zeros((n, 2, 2))
    anchor_b = np.zeros((n, 2, 2))
    sep_out = np.full((n, 2), np.inf)
    feat_out = np.full((n, 2), -1, dtype=np.int64)
    for k in range(n):
        # Frames (engine.geometry.manifold_kinds.frames): B's centre in A's frame.
        ca, sn = np.cos(qa[k]), np.sin(qa[k])
        dx, dy = xb[k, 0] - xa[k, 0], xb[k, 1] - xa[k, 1]
        px, py = ca * dx + sn * dy, -sn * dx + ca * dy
        rel = qb[k] - qa[k]
        c, s = np.cos(rel), np.sin(rel)
        j = ib[k]
        vx, vy = C[j, 0], C[j, 1]
        cx, cy = c * vx - s * vy + px, s * vx + c * vy + py
        rb = rC[j]
        i = ia[k]
        if circle_a[k]:
            # collide_circles: the normal along the centres (A's up where they coincide).
            pax, pay = C[i, 0], C[i, 1]
            ra = rC[i]
            ux, uy = cx - pax, cy - pay
            dist = np.hypot(ux, uy)
            if dist > 0.0:
                nx, ny = ux / dist, uy / dist
            else:
                nx, ny = 0.0, 1.0
            ax_, ay_ = pax + ra * nx, pay + ra * ny
            gap = dist - ra - rb
        else:
            # collide_polygon_circle: the face of largest separation, or a vertex past it.
            ra = rA[i]
            m = cA[i]
            best = 0
            sep = -np.inf
            for e in range(m):
                d = NA[i, e, 0] * (cx - VA[i, e, 0]) + NA[i, e, 1] * (cy - VA[i, e, 1])
                if d > sep or e == 0:
                    best, sep = e, d
            v1x, v1y = VA[i, best, 0], VA[i, best, 1]
            e2 = (best + 1) % m
            v2x, v2y = VA[i, e2, 0], VA[i, e2, 1]
            u1 = (cx - v1x) * (v2x - v1x) + (cy - v1y) * (v2y - v1y)
            u2 = (cx - v2x) * (v1x - v2x) + (cy - v2y) * (v1y - v2y)
            fx, fy = NA[i, best, 0], NA[i, best, 1]
            outside = sep > 0.0
            near1 = outside and u1 < 0.0
            near2 = outside and u2 < 0.0 and not near1
            if near1 or near2:
                wx, wy = (v1x, v1y) if near1 else (v2x, v2y)
                ux, uy = cx - wx, cy - wy
                dist = np.hypot(ux, uy)
                if dist > 0.0:
                    nx, ny = ux / dist, uy / dist
                else:
                    nx, ny = fx, fy
                ax_, ay_ = wx + ra * nx, wy + ra * ny
                gap = dist - ra - rb
            else:
                nx, ny = fx, fy
                h = ra - ((cx - v1x) * fx + (cy - v1y) * fy)
                ax_, ay_ = cx + h * fx, cy + h * fy
                gap = sep - ra - rb
        bx_, by_ = cx - rb * nx, cy - rb * ny
        # _one_point and finish: the point midway, kept within margin, into the world's frame.
        normal_w[k, 0] = ca * nx - sn * ny
        normal_w[k, 1] = sn * nx + ca * ny
        if gap <= margin:
            mx, my = 0.5 * (ax_ + bx_), 0.5 * (ay_ + by_)
            wx_, wy_ = ca * mx - sn * my, sn * mx + ca * my
            anchor_a[k, 0, 0], anchor_a[k, 0, 1] = wx_, wy_
            world[k, 0, 0], world[k, 0, 1] = wx_ + xa[k, 0], wy_ + xa[k, 1]
            anchor_b[k, 0, 0] = wx_ + (xa[k, 0] - xb[k, 0])
            anchor_b[k, 0, 1] = wy_ + (xa[k, 1] - xb[k, 1])
            sep_out[k, 0], feat_out[k, 0] = gap, 0
            count[k] = 1
    return normal_w, count, world, anchor_a, anchor_b, sep_out, feat_out


class Touches(NamedTuple):
    """The narrowphase's manifolds with a point, and whose: ``a`` body A's row, ``b`` body B's
    (n: the static body), ``place`` the static shape's place among the colliders' (-1 for a
    pair of bodies)."""

    m: Manifold
    a: np.ndarray
    b: np.ndarray
    place: np.ndarray

    def take(self, rows: np.ndarray) -> Touches:
        """The manifolds of ``rows`` (an index array or a boolean mask)."""
        rows = np.asarray(rows)
        if rows.dtype == bool:
            rows = rows.nonzero()[0]
        # (ndarray.take: what indexing gives, at a third of its cost on a few rows.)
        return Touches(self.m.take(rows), self.a.take(rows), self.b.take(rows),
                       self.place.take(rows))  # fmt: skip


def _padded(a: np.ndarray, m: int) -> np.ndarray:
    """Corners or normals (N, k, 2) padded to ``m`` (the last one repeated, as
    engine.geometry.manifold_kinds pads)."""
    k = a.shape[1]
    if k == m:
        return a
    return np.concatenate([a, np.repeat(a[:, -1:], m - k, axis=1)], axis=1)


class Places(NamedTuple):
    """The two tables of a scene's shapes (engine.geometry.narrowphase) and where each shape is in
    them: by body row and by static shape's place, whether it is a circle and its index
    (a half plane, which the tables do not hold, as -1 - its index among the half planes)."""

    tables: Tables
    body_circle: np.ndarray
    body_index: np.ndarray
    static_circle: np.ndarray
    static_index: np.ndarray


#: The last polygons' table ``places_of`` made: (the bodies' polygons and capsules and the
#: static shapes it was made of, the table). Kept while they are the same objects: a game
#: that spawns or takes out a ball changes only the discs' rows (engine.geometry.shaped keeps
#: the others' arrays then).
_POLYGONS: list[Any] = [None, None, None, None]


def _polygons_of(table: ShapeTable, statics: StaticShapes) -> Polygons | None:
    """The polygons' tables in order (each corners, normals, counts, radii): the bodies'
    polygons, their capsules (two-vertex polygons), the static polygons, the static
    capsules; None where there are none."""
    kept = _POLYGONS
    if kept[0] is table.polygons and kept[1] is table.capsules and kept[2] is statics:
        return kept[3]  # type: ignore[no-any-return]
    parts: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []
    if table.polygons is not None:
        p = table.polygons
        parts.append((p.vertices, p.normals, p.count, p.radius))
    if len(table.capsules):
        two = np.full(len(table.capsules), 2, dtype=np.intp)
        parts.append((*capsule_corners(table.capsules), two, table.capsules.radius))
    if len(statics.polygon_owner):
        p = statics.polygons
        parts.append((p.vertices, p.normals, p.count, p.radius))
    if len(statics.capsule_owner):
        parts.append(statics.capsule_polygons)
    polygons = None
    if parts:
        m = max(v.shape[1] for v, _, _, _ in parts)
        polygons = Polygons(
            np.concatenate([_padded(v, m) for v, _, _, _ in parts]),
            np.concatenate([_padded(nn, m) for _, nn, _, _ in parts]),
            np.concatenate([c for _, _, c, _ in parts]),
            np.concatenate([r for _, _, _, r in parts]),
        )
    kept[:] = [table.polygons, table.capsules, statics, polygons]
    return polygons


def places_of(table: ShapeTable, statics: StaticShapes) -> Places:
    """The tables of the bodies' shapes and the colliders' (engine.geometry.narrowphase)."""
    n = len(table)
    polygons = _polygons_of(table, statics)
    circles = Circles(
        np.concatenate([table.circles.center, statics.circles.center]),
        np.concatenate([table.circles.radius, statics.circles.radius]),
    )
    n_poly = 0 if table.polygons is None else len(table.polygons)
    n_cap = len(table.capsules)
    body_circle = table.kind == DISC
    body_index = np.where(
        body_circle, np.arange(n), np.where(table.kind == CAPSULE, n_poly, 0) + table.index
    )
    # The static shapes in the order of statics.kinds(): half planes, circles, capsules,
    # polygons (those present).
    circle_parts, index_parts = [], []
    base_poly = n_poly + n_cap
    n_static_poly = len(statics.polygon_owner)
    for _kind, own in statics.kinds():
        k = len(own)
        if own is statics.half_plane_owner:
            circle_parts.append(np.zeros(k, dtype=bool))
            index_parts.append(-1 - np.arange(k))  # half plane h as -1 - h
        elif own is statics.circle_owner:
            circle_parts.append(np.ones(k, dtype=bool))
            index_parts.append(n + np.arange(k))
        elif own is statics.capsule_owner:
            circle_parts.append(np.zeros(k, dtype=bool))
            index_parts.append(base_poly + n_static_poly + np.arange(k))
        else:
            circle_parts.append(np.zeros(k, dtype=bool))
            index_parts.append(base_poly + np.arange(k))
    static_circle = np.concatenate(circle_parts) if circle_parts else np.zeros(0, dtype=bool)
    static_index = (
        np.concatenate(index_parts) if index_parts else np.zeros(0, dtype=np.intp)
    ).astype(np.int64)
    return Places(
        Tables(polygons, circles), body_circle, body_index.astype(np.int64), static_circle,
        static_index,
    )  # fmt: skip


#: The last ``Places``' static shapes' circle flags and indices, each with one entry appended
#: (False, 0: what a pair of bodies, place -1, picks): (the places, the two arrays). Kept
#: while ``collide_pairs`` is asked of the same places, as a game's every step is.
_ENDS: list[Any] = [None, None, None]


def _static_ends(places: Places) -> tuple[np.ndarray, np.ndarray]:
    """``places``' static_circle and static_index, each with one entry appended (``_ENDS``)."""
    if _ENDS[0] is not places:
        _ENDS[:] = [
            places,
            np.append(places.static_circle, False),
            np.append(places.static_index, 0),
        ]
    return _ENDS[1], _ENDS[2]


def collide_pairs(
    places: Places,
    table: ShapeTable,
    store: Any,
    statics: StaticShapes,
    pairs: np.ndarray,
    faces: np.ndarray,
    margin: np.ndarray,
    dt: float,
    struck: np.ndarray | None = None,
    unit: float = 1.0,
) -> Touches:
    """The manifolds of the pairs and faces with a point, in the broadphase's order (the
    pairs, then the faces): polygon against polygon in one call, the round pairs in another
    (engine.geometry.narrowphase), a half plane against each kind of body shape in one each (the
    half plane as A, flipped back); each call's speculative margin the largest reach among its
    pairs: ``margin`` (n,) each body's reach (m), ``struck`` its reach toward a static shape
    (engine.pipeline.game_broadphase.struck; None: ``margin``); ``unit`` the World's length
    units a metre (its ``length_units_per_meter``), which the speculative distance and the
    slop are scaled by. The numpy path's stage (the fast path's is
    engine.pipeline.game_contacts.contacts_loop)."""
    n = len(store)
    x, q = store.x, store.angle
    # Every pair as (A's row, B's row or n, the static place or -1), A a body: the pairs'
    # rows then the faces', each column written in place (fewer calls than concatenating).
    k = len(pairs)
    a, b, place = (np.empty(k + len(faces), dtype=np.intp) for _ in range(3))
    a[:k], a[k:] = pairs[:, 0], faces[:, 0]
    b[:k], b[k:] = pairs[:, 1], n
    place[:k], place[k:] = -1, faces[:, 1]
    is_static = place >= 0
    # (A body pair's place is -1: it picks the one entry appended past the statics.)
    static_circle, static_index = _static_ends(places)
    static_circle = static_circle[place]
    static_index = static_index[place]
    half = is_static & (static_index < 0)
    other = np.minimum(b, n - 1)
    circ_a = places.body_circle[a]
    circ_b = np.where(is_static, static_circle, places.body_circle[other])
    idx_a = places.body_index[a]
    idx_b = np.where(is_static, static_index, places.body_index[other])
    # (A table's rows by index as ndarray.take(rows, axis=0) here: indexing's answer, at a
    # third of its cost on a game's few rows.)
    xb, qb = x.take(other, axis=0), q[other]  # (a static shape's frame: the origin, angle 0)
    xb[is_static] = 0.0
    qb[is_static] = 0.0
    xa, qa = x.take(a, axis=0), q[a]
    toward = margin if struck is None else struck
    reach = np.where(is_static, toward[a], margin[a] + margin[other])
    reach = reach + SPECULATIVE_DISTANCE * unit
    t = places.tables
    parts: list[Manifold] = []
    order: list[np.ndarray] = []
    c = np.ascontiguousarray
    # (mask.nonzero()[0]: np.flatnonzero's answer for a 1D mask, without its Python wrapper.)
    sel = (~circ_a & ~circ_b & ~half).nonzero()[0]
    if len(sel):
        parts.append(collide_polygon_pairs(
            t, c(idx_a[sel]), c(xa[sel]), c(qa[sel]), c(idx_b[sel]), c(xb[sel]), c(qb[sel]),
            float(reach[sel].max()), False,
        ))  # fmt: skip
        order.append(sel)
    # The round pairs: B a circle; where only A is one, the pair is taken the other way
    # round (the polygon as A) and its manifold flipped back.
    sel = ((circ_a | circ_b) & ~half).nonzero()[0]
    if len(sel):
        swap = circ_a[sel] & ~circ_b[sel]
        ia = np.where(swap, idx_b[sel], idx_a[sel])
        ib = np.where(swap, idx_a[sel], idx_b[sel])
        xa_sel, xb_sel = xa.take(sel, axis=0), xb.take(sel, axis=0)
        pa = np.where(swap[:, None], xb_sel, xa_sel)
        pb = np.where(swap[:, None], xa_sel, xb_sel)
        wa = np.where(swap, qb[sel], qa[sel])
        wb = np.where(swap, qa[sel], qb[sel])
        flag = np.where(swap, False, circ_a[sel])
        m = collide_round_pairs(
            t, c(flag), c(ia), c(pa), c(wa), c(ib), c(pb), c(wb), float(reach[sel].max()), False
        )
        # A body's point against a static shape kept for reach that its path passes by is
        # dropped (engine.geometry.passing): the body's move relative to the shape at its
        # velocity, and the slack of a slop and what it can move beyond that (its reach less
        # |v| dt). (A pair of bodies keeps its points: another body may push either toward
        # the other within the step, where a static shape's partner is the only one moving.)
        ask = (
            (m.count > 0) & (m.separation[:, 0] > SPECULATIVE_DISTANCE * unit) & is_static[sel]
        ).nonzero()[0]
        if len(ask):
            body = a[sel][ask]
            v = store.v[body]
            speed = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1])
            slack = LINEAR_SLOP * unit + np.maximum(toward[body] - speed * dt, 0.0)
            # B's move relative to A: the body's where the shape is A (the pair swapped),
            # else the shape's relative to the body, minus it.
            turned = swap[ask][:, None]
            u = np.where(turned, (v - 0.0) * dt, (0.0 - v) * dt)
            vertices, _, count, radius = t.kernel_polygons
            test: Any = passing_loop.py if len(ask) <= FEW_ROUND else passing
            keep = test(
                vertices, count, radius, t.center, t.round, c(flag[ask]), c(ia[ask]),
                c(pa[ask]), c(wa[ask]), c(ib[ask]), c(pb[ask]), c(wb[ask]), c(u), c(slack),
            )  # fmt: skip
            m.count[ask[~np.asarray(keep, dtype=bool)]] = 0
        swapped = np.count_nonzero(swap)
        if swapped == len(swap):
            m = m.flipped()
        elif swapped:
            m = m.flipped_where(swap)
        parts.append(m)
        order.append(sel)
    # Half planes (a Plane, a room's walls), by the kind of the body's shape.
    kind = table.kind
    for ka in (DISC, CAPSULE, POLYGON) if np.count_nonzero(half) else ():
        sel = np.flatnonzero(half & (kind[a] == ka))
        if not len(sel):
            continue
        r, h = a[sel], -1 - static_index[sel]
        m = collide(
            table.kinds(r), x[r], q[r], statics.half_planes.take(h), np.zeros((len(r), 2)),
            np.zeros(len(r)), float(reach[sel].max()), False,
        )  # fmt: skip
        parts.append(m)
        order.append(sel)
    if not parts:
        empty = np.zeros(0, dtype=np.intp)
        none = Manifold(
            np.zeros((0, 2)),
            np.zeros(0, dtype=np.intp),
            np.zeros((0, 2, 2)),
            np.zeros((0, 2, 2)),
            np.zeros((0, 2, 2)),
            np.zeros((0, 2)),
            np.zeros((0, 2), dtype=np.int64),
        )
        return Touches(none, empty, empty, empty)
    # Back in the broadphase's order (so the solver meets the rows as the fast path's); one
    # call's rows that are every pair are in that order already (a flatnonzero of all).
    if len(parts) == 1 and len(order[0]) == len(a):
        m = parts[0]
    else:
        idx = np.concatenate(order)
        back = np.empty(len(idx), dtype=np.intp)
        back[idx] = np.arange(len(idx))
        m = Manifold.concat(parts).take(back)
    return Touches(m, a, b, place).take(m.count > 0)
