"""Push-out: bodies found inside a solid collider are moved to the nearest place outside.

A body of radius r is inside when it overlaps a face by more than TOUCH (1 + r) (TOUCH from
engine.geometry.impact): it was added there, moved there by the game, freed from a pin there, rolled
over a round edge onto a flat side it overlaps, or stopped at the impact cap (engine.exact.sweep).
It is moved out in rounds, every body at once: each round moves each body out of the face it
is deepest in, along that face's normal, then looks again, so a body in the corner of two
faces leaves one a round. A convex polygon is overlapped only when the body is behind every
one of its faces (checked exactly at its corners by ``engine.geometry.manifold.polygon_distance``),
and is left by the face the body is least deep behind. Four rounds that do not settle it (a
ball pressed between a peg and a wall, pushed out of each in turn) end in ``out_of_corner``:
the nearest point outside every face, a projection out of one face or a point where the
surfaces of two, offset by the radius, meet. After each move the part of the velocity going
into the faces the body then touches is removed.

On the fast path (engine.kernels) ``push_out_rows`` runs its rounds as the loop kernel
``push_rows``: a body's rounds depend on its own position alone, so each row is taken through
its rounds in turn, with the twin's arithmetic, to the same numbers bit for bit. A polygon
(whose inside needs ``polygon_distance``) keeps the numpy rounds.
"""

from __future__ import annotations

import math

import numpy as np

from .. import kernels
from ..filters import DEFAULT as DEFAULT_FILTER
from ..geometry.colliders import Collider, Polygon
from ..geometry.face_grid import FaceGrid
from ..geometry.faces import Faces, dot, face_meets, signed_distance
from ..geometry.impact import TOUCH
from ..geometry.manifold import polygon_distance

__all__ = ["face_gaps", "out_of_corner", "push_out", "push_out_rows", "take_speed_into"]


def push_out(
    colliders: list[Collider],
    faces: Faces,
    body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
    x: np.ndarray,
    v: np.ndarray,
    radius: np.ndarray,
    rows: np.ndarray,
    grid: FaceGrid | None = None,
) -> list[tuple[int, int]]:
    """Move bodies (World ``rows``) that overlap a solid collider they meet to the nearest
    place outside every one (``push_out_rows``), in place; return (place in x, a
    collider it overlapped) for each. ``faces``: the solid colliders' (engine.geometry.faces);
    ``body_filters``: the World's bodies' (group, categories, mask) arrays by row, or None.
    ``grid``: the faces' broadphase if it is built: then only the bodies its bounds put
    within reach of a face, against the colliders of the faces near them (and every
    polygon, whose inside the bounds do not see), are looked at; the rest overlap nothing.
    The same answer as looking at every body against every collider.

    The velocity's part into the surfaces it then touches is removed.
    """
    if len(x) == 0 or not len(faces.owner):
        return []
    if len(x) == 1 and (_all_face_gaps(faces, x[0], float(radius[0]))[0] >= 0.0).all():
        # One body (a game spawning one) clear of every face at once: it overlaps no collider
        # (a ball inside a convex polygon is behind the face it is nearest, within its ends),
        # and no collider need be asked one by one.
        return []
    overlapped = []
    bf = body_filters
    some: np.ndarray | None = None  # the rows to look at, None for all
    look: list[int] | range = range(len(colliders))
    if grid is not None:
        some, look = _near(grid, faces, colliders, x, radius)
    for k in look:
        c = colliders[k]
        if not c.sensor:
            if some is None or isinstance(c, Polygon):
                d = signed_distance(c, x) - radius
                bad = d < -1e-9 * (1.0 + radius)
            else:
                r = radius[some]
                bad = np.zeros(len(x), dtype=bool)
                bad[some] = signed_distance(c, x[some]) - r < -1e-9 * (1.0 + r)
            if c.filter != DEFAULT_FILTER and bf is not None and bad.any():
                f = c.filter
                g, cat, m = bf[0][rows], bf[1][rows], bf[2][rows]
                bad &= ((cat & f.mask) != 0) & ((f.categories & m) != 0)
                bad &= ~((g == f.group) & (g != 0))
            overlapped.append((k, bad))
    if not any(bad.any() for _, bad in overlapped):
        return []
    pushed = push_out_rows(faces, colliders, x, v, radius, face_meets(faces, bf, rows))
    moved = []
    for i in np.flatnonzero(pushed).tolist():
        first = next((k for k, bad in overlapped if bad[i]), None)
        if first is not None:
            moved.append((i, first))
    return moved


def _near(
    grid: FaceGrid, faces: Faces, colliders: list[Collider], x: np.ndarray, radius: np.ndarray
) -> tuple[np.ndarray, list[int]]:
    """(the rows of x that may overlap a face, the colliders to look at, in order): the rows
    whose lower bound on the distance to every face (``FaceGrid.gap``) is within their
    radius (a body overlaps a collider by more than 1e-9 (1 + r) only inside its faces grown
    by r, and the bound is below the distance by far more than its rounding), and the
    colliders of the faces within reach of those, with every polygon."""
    cell = grid.cells(x) if grid.n_finite else None
    slack = 1e-9 * (1.0 + radius)
    some = np.flatnonzero(grid.gap(x, cell) - radius <= slack)
    owners: list[np.ndarray] = (
        [np.array([k for k, c in enumerate(colliders) if isinstance(c, Polygon)], dtype=np.intp)]
        if faces.polygons
        else []
    )
    if len(some):
        X, r = x[some], radius[some] + 2.0 * slack[some]
        bi, f = grid.pairs(X, r)
        finite = f >= len(faces.p)
        finite[~finite] = ~faces.infinite[f[~finite]]
        if finite.any():
            # The listed faces as capsules (``FaceGrid.cap``: a, b - a, 1 / |b - a|^2,
            # radius grown): only those a ball reaches.
            k = np.flatnonzero(finite)
            cap = grid.cap[f[k]]
            D = X[bi[k]] - cap[:, :2]
            along = np.clip(dot(D, cap[:, 2:4]) * cap[:, 4], 0.0, 1.0)
            C = D - cap[:, 2:4] * along[:, None]
            far = np.sqrt(dot(C, C)) - cap[:, 5] > r[bi[k]]
            keep = np.ones(len(f), dtype=bool)
            keep[k[far]] = False
            f = f[keep]
        owners.append(faces.owner[f])
    if not owners:
        return some, []
    return some, np.unique(np.concatenate(owners)).tolist()


def push_out_rows(
    faces: Faces,
    colliders: list[Collider],
    X: np.ndarray,
    V: np.ndarray,
    r: np.ndarray,
    meets: np.ndarray | None = None,
    fast: bool = False,
) -> np.ndarray:
    """Push rows of X (balls of radii r, velocities V) out of any solid face they overlap (by
    more than TOUCH), in place; return which rows moved. ``colliders``: the World's, which
    ``faces.owner`` indexes. ``meets`` (rows, faces) bool: which faces each row meets
    (``engine.geometry.faces.face_meets``), or None for all. ``fast``: the rounds by the loop kernel
    ``push_rows`` (unless a polygon is among the faces)."""
    L = len(faces.p)
    if fast and not faces.polygons and X.dtype == V.dtype == r.dtype == np.float64:
        some = meets is not None
        m = meets if meets is not None else np.zeros((0, 0), dtype=bool)
        pushed, unsettled = push_rows(X, V, r, faces.p, faces.n, faces.rho, faces.two,
                                      faces.lo, faces.hi, faces.c, faces.r, m, some)  # fmt: skip
        if unsettled:
            for i in np.flatnonzero(pushed).tolist():
                out_of_corner(faces, X, V, i, float(r[i]), None if meets is None else meets[i])
        return pushed  # type: ignore[no-any-return]
    pushed = np.zeros(len(X), dtype=bool)
    for _ in range(4):
        # Each round pushes each body out of the face it is deepest in (all bodies at
        # once), then looks again: a body in the corner of two faces leaves one a round.
        moved = False
        if L:
            # n.x by columns, not X @ n.T: a matrix product may round a row differently
            # with other rows beside it, and one row pushed alone must move as in a crowd.
            d = X[:, :1] * faces.n[:, 0] + X[:, 1:] * faces.n[:, 1] - dot(faces.p, faces.n)
            side = np.where(faces.two[None, :] & (d < 0.0), -1.0, 1.0)
            gap = side * d - faces.rho[None, :] - r[:, None]
            tang = np.stack([-faces.n[:, 1], faces.n[:, 0]], axis=1)
            u = X[:, :1] * tang[:, 0] + X[:, 1:] * tang[:, 1] - dot(faces.p, tang)
            deep = gap < -TOUCH * (1.0 + r[:, None])
            inside = deep & (u >= faces.lo) & (u <= faces.hi)
            for cols in faces.polygons:
                # A convex polygon: the body overlaps it when it is behind every face
                # (checked exactly at the corners: ``polygon_distance``), and leaves by
                # the face it is least deep behind.
                sub = gap[:, cols]
                top = sub.max(axis=1)
                hit = deep[:, cols].all(axis=1)
                if hit.any():
                    owner = colliders[int(faces.owner[cols[0]])]
                    assert isinstance(owner, Polygon)
                    k = np.flatnonzero(hit)
                    hit[k] = polygon_distance(owner, X[k]) < r[k] - TOUCH * (1.0 + r[k])
                inside[:, cols] = (sub == top[:, None]) & hit[:, None]
            if meets is not None:
                inside &= meets[:, :L]
            i = np.flatnonzero(inside.any(axis=1))
            if len(i):
                j = np.argmin(np.where(inside[i], gap[i], np.inf), axis=1)
                nrm = side[i, j][:, None] * faces.n[j]
                X[i] -= gap[i, j][:, None] * nrm
                take_speed_into(V, i, nrm)
                moved = True
                pushed[i] = True
        if len(faces.c):
            D = X[:, None, :] - faces.c[None, :, :]
            dist = np.sqrt((D * D).sum(axis=2))
            gap = dist - faces.r[None, :] - r[:, None]
            inside = gap < -TOUCH * (1.0 + r[:, None])
            if meets is not None:
                inside &= meets[:, L:]
            i = np.flatnonzero(inside.any(axis=1))
            if len(i):
                j = np.argmin(np.where(inside[i], gap[i], np.inf), axis=1)
                dij = dist[i, j]
                safe = np.where(dij > 0.0, dij, 1.0)[:, None]
                nrm = np.where((dij > 0.0)[:, None], D[i, j] / safe, (0.0, 1.0))
                X[i] = faces.c[j] + nrm * (faces.r[j] + r[i])[:, None]
                take_speed_into(V, i, nrm)
                moved = True
                pushed[i] = True
        if not moved:
            break
    else:
        # Four rounds did not settle it: a body pressed into the corner of two faces
        # (between a peg and a wall, pushed out of each in turn) is put at the corner.
        for i in np.flatnonzero(pushed).tolist():
            out_of_corner(faces, X, V, i, float(r[i]), None if meets is None else meets[i])
    return pushed


# -- the loop kernel (engine.kernels: the fast path) ------------------------------------------
# push_out_rows' rounds row by row. The twin moves every row at once, a round at a time, until
# a round moves none; a row's round depends on its own position alone, and a row that a round
# does not move no later round moves, so each row can be taken through its rounds on its own:
# up to four, ending at the first that does not move it. The rounds end unsettled (the twin's
# ``else``: out_of_corner for every pushed row) when some row moved in the fourth. The same
# products and sums as the twin's columns, in the same order, so the same bits.


def _sample_push() -> tuple[object, ...]:
    """The smallest call of ``push_rows``: a ball sunk into a floor, a peg beside it."""
    f2, f1 = np.zeros((1, 2)), np.zeros(1)
    return (np.array([[0.0, 0.1]]), np.array([[0.0, -1.0]]), np.ones(1), f2,
            np.array([[0.0, 1.0]]), f1, np.zeros(1, dtype=bool), f1 - 10.0, f1 + 10.0,
            np.array([[5.0, 0.0]]), f1 + 1.0, np.zeros((0, 0), dtype=bool), False)  # fmt: skip


@kernels.loop(sample=_sample_push)
def push_rows(
    X: np.ndarray,
    V: np.ndarray,
    r: np.ndarray,
    p: np.ndarray,
    n: np.ndarray,
    rho: np.ndarray,
    two: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    c: np.ndarray,
    cr: np.ndarray,
    meets: np.ndarray,
    some: bool,
) -> tuple[np.ndarray, bool]:
    """push_out_rows' rounds on rows of X (length units) and V (length units/s) in place, for
    flat faces (p, n, rho, two, lo, hi) and round ones (c, cr) met where ``meets`` says (if
    ``some``): (which rows moved, whether some row still moved in the fourth round)."""
    L, D = len(p), len(c)
    # Each face's n.p and t.p (t = (-n_y, n_x)), as the twin's dot(faces.p, ...) rounds them.
    pn, pt = np.empty(L), np.empty(L)
    for f in range(L):
        pn[f] = p[f, 0] * n[f, 0] + p[f, 1] * n[f, 1]
        pt[f] = p[f, 0] * -n[f, 1] + p[f, 1] * n[f, 0]
    pushed = np.zeros(len(X), dtype=np.bool_)
    unsettled = False
    for i in range(len(X)):
        ri = r[i]
        deep = -TOUCH * (1.0 + ri)
        for round_ in range(4):
            moved = False
            # The flat face the row is deepest in (the first of the least gaps).
            best, best_gap, best_side = -1, np.inf, 1.0
            for f in range(L):
                x, y = X[i, 0], X[i, 1]
                d = x * n[f, 0] + y * n[f, 1] - pn[f]
                side = -1.0 if two[f] and d < 0.0 else 1.0
                gap = side * d - rho[f] - ri
                u = x * -n[f, 1] + y * n[f, 0] - pt[f]
                inside = gap < deep and u >= lo[f] and u <= hi[f]
                if inside and (not some or meets[i, f]) and (best < 0 or gap < best_gap):
                    best, best_gap, best_side = f, gap, side
            if best >= 0:
                nx, ny = best_side * n[best, 0], best_side * n[best, 1]
                X[i, 0] -= best_gap * nx
                X[i, 1] -= best_gap * ny
                vn = V[i, 0] * nx + V[i, 1] * ny  # take_speed_into: the speed into it taken
                if vn < 0.0:
                    V[i, 0] -= vn * nx
                    V[i, 1] -= vn * ny
                moved = True
            # Then the round face it is deepest in, from where the flat one left it.
            best, best_gap, best_dist = -1, np.inf, 0.0
            for f in range(D):
                dx, dy = X[i, 0] - c[f, 0], X[i, 1] - c[f, 1]
                dist = np.sqrt(dx * dx + dy * dy)
                gap = dist - cr[f] - ri
                if gap < deep and (not some or meets[i, L + f]) and (best < 0 or gap < best_gap):
                    best, best_gap, best_dist = f, gap, dist
            if best >= 0:
                dx, dy = X[i, 0] - c[best, 0], X[i, 1] - c[best, 1]
                if best_dist > 0.0:
                    nx, ny = dx / best_dist, dy / best_dist
                else:
                    nx, ny = 0.0, 1.0
                reach = cr[best] + ri
                X[i, 0] = c[best, 0] + nx * reach
                X[i, 1] = c[best, 1] + ny * reach
                vn = V[i, 0] * nx + V[i, 1] * ny
                if vn < 0.0:
                    V[i, 0] -= vn * nx
                    V[i, 1] -= vn * ny
                moved = True
            if not moved:
                break
            pushed[i] = True
            if round_ == 3:
                unsettled = True
    return pushed, unsettled


def take_speed_into(V: np.ndarray, i: np.ndarray, nrm: np.ndarray) -> None:
    """Take the part of rows i of V that goes into the faces of normals ``nrm``, in place."""
    vn = V[i, 0] * nrm[:, 0] + V[i, 1] * nrm[:, 1]
    into = vn < 0.0
    if into.any():
        V[i[into]] -= vn[into][:, None] * nrm[into]


def face_gaps(
    faces: Faces, x: np.ndarray, r: float, meets: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Every solid face's gap (length units, < 0 inside) to a ball of radius r at x, and
    its unit normal toward x; a flat face beyond its ends, or one the ball does not meet
    (``meets`` False), has gap inf."""
    gaps, nrm = _all_face_gaps(faces, x, r)
    if meets is not None:
        gaps[~meets] = np.inf
    return gaps, nrm


def _all_face_gaps(faces: Faces, x: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray]:
    L = len(faces.p)
    gaps = np.full(L + len(faces.c), np.inf)
    nrm = np.zeros((L + len(faces.c), 2))
    if L:
        d = (x[0] - faces.p[:, 0]) * faces.n[:, 0] + (x[1] - faces.p[:, 1]) * faces.n[:, 1]
        side = np.where(faces.two & (d < 0.0), -1.0, 1.0)
        u = (x[0] - faces.p[:, 0]) * -faces.n[:, 1] + (x[1] - faces.p[:, 1]) * faces.n[:, 0]
        within = (u >= faces.lo) & (u <= faces.hi)
        gaps[:L] = np.where(within, side * d - faces.rho - r, np.inf)
        nrm[:L] = faces.n * side[:, None]
    if len(faces.c):
        D = x - faces.c
        dist = np.sqrt(D[:, 0] * D[:, 0] + D[:, 1] * D[:, 1])
        gaps[L:] = dist - faces.r - r
        safe = np.where(dist > 0.0, dist, 1.0)
        nrm[L:] = np.where((dist > 0.0)[:, None], D / safe[:, None], (0.0, 1.0))
    return gaps, nrm


def out_of_corner(
    faces: Faces,
    X: np.ndarray,
    V: np.ndarray,
    i: int,
    r: float,
    meets: np.ndarray | None = None,
) -> None:
    """Put row i, still inside some face after push_out_rows' rounds, at the nearest point
    outside every face: its projection out of one face, or a corner where the surfaces
    of two meet (offset by r: two lines meet in a point; a line and a circle, or two
    circles, in up to two). Its speed into the faces it then touches is taken."""
    L = len(faces.p)
    x = X[i].astype(float)
    slack = TOUCH * (1.0 + r)
    gaps, nrm = face_gaps(faces, x, r, meets)
    if not (gaps < -slack).any():
        return
    # The faces that bound the corner: those it overlaps or nearly touches.
    near = np.flatnonzero(gaps < 0.5 * r + slack).tolist()
    cands = [x - gaps[j] * nrm[j] for j in near if gaps[j] < 0.0]
    for k, a in enumerate(near):
        for b in near[k + 1 :]:
            cands += _corners(faces, L, a, b, x, nrm, r)
    best = _nearest_free(faces, x, r, meets, cands, slack)
    if best is None:
        # No way out of one face, nor a corner of two near ones, frees it: a ball wedged in
        # a gap narrower than itself (between a capsule and a ceiling, pushed out of each in
        # turn). Look wider: the far side of each face it overlaps that has one (a capsule's
        # or a segment's other side, a peg's; a room's wall has none), and the corners of the
        # faces within its diameter (around a capsule's end). A face j's far side is where
        # the ball's centre is its radius r and the face's own (rho, or the peg's R) beyond
        # the face's line (or centre): from x, along -n_j, by the depth there
        # d_j = g_j + rho_j + r, and then rho_j + r, that is g_j + 2 (rho_j + r).
        rad = np.concatenate([faces.rho, faces.r])
        through = np.flatnonzero(
            (gaps < -slack) & np.concatenate([faces.two, np.ones(len(faces.c), dtype=bool)])
        )
        cands = [x - (gaps[j] + 2.0 * (rad[j] + r)) * nrm[j] for j in through.tolist()]
        wide = np.flatnonzero(gaps < 2.0 * r + slack).tolist()
        for k, a in enumerate(wide):
            for b in wide[k + 1 :]:
                cands += _corners(faces, L, a, b, x, nrm, r)
        best = _nearest_free(faces, x, r, meets, cands, slack)
    if best is None:
        return  # nothing near frees it (three faces at once): left to the next step
    X[i] = best
    g, n_at = face_gaps(faces, best, r, meets)
    for j in np.flatnonzero(g <= slack * 4.0).tolist():
        vn = float(V[i] @ n_at[j])
        if vn < 0.0:
            V[i] -= vn * n_at[j]


def _nearest_free(
    faces: Faces,
    x: np.ndarray,
    r: float,
    meets: np.ndarray | None,
    cands: list[np.ndarray],
    slack: float,
) -> np.ndarray | None:
    """The candidate nearest x where a ball of radius r overlaps no face (by more than four
    times ``slack``), or None."""
    best, best_d = None, math.inf
    for c in cands:
        g, _ = face_gaps(faces, c, r, meets)
        dist = float(np.hypot(*(c - x)))
        if (g >= -slack * 4.0).all() and dist < best_d:
            best, best_d = c, dist
    return best


def _corners(
    faces: Faces, L: int, a: int, b: int, x: np.ndarray, nrm: np.ndarray, r: float
) -> list[np.ndarray]:
    """Where the surfaces of faces a and b, offset by r toward x, meet: points (2,)."""

    def line(j: int) -> tuple[np.ndarray, float]:  # points p with n.p = c
        n = nrm[j]
        return n, float(n @ faces.p[j]) + float(faces.rho[j]) + r

    def circle(j: int) -> tuple[np.ndarray, float]:
        return faces.c[j - L], float(faces.r[j - L]) + r

    out: list[np.ndarray] = []
    if a < L and b < L:
        (n1, c1), (n2, c2) = line(a), line(b)
        det = n1[0] * n2[1] - n1[1] * n2[0]
        if abs(det) > 1e-12:
            out.append(np.array([(c1 * n2[1] - c2 * n1[1]) / det, (n1[0] * c2 - n2[0] * c1) / det]))
        return out
    if a >= L and b >= L:
        (p1, R1), (p2, R2) = circle(a), circle(b)
        d = p2 - p1
        dd = float(d @ d)
        if dd == 0.0:
            return out
        # Along d from p1: s = (dd + R1^2 - R2^2) / (2 dd); off it by h, h^2 = R1^2 - s^2 dd.
        s = (dd + R1 * R1 - R2 * R2) / (2.0 * dd)
        h2 = R1 * R1 - s * s * dd
        if h2 < 0.0:
            return out
        h = math.sqrt(h2 / dd)
        base = p1 + s * d
        perp = np.array([-d[1], d[0]])
        return [base + h * perp, base - h * perp]
    j_line, j_circ = (a, b) if a < L else (b, a)
    (n, c), (p, R) = line(j_line), circle(j_circ)
    # The line n.q = c meets |q - p| = R where q = p + (c - n.p) n + t t_dir, t^2 = R^2 - h^2.
    h = c - float(n @ p)
    t2 = R * R - h * h
    if t2 < 0.0:
        return out
    t = math.sqrt(t2)
    foot = p + h * n
    t_dir = np.array([-n[1], n[0]])
    return [foot + t * t_dir, foot - t * t_dir]
