"""A step's first two looks at the static faces: which bodies may meet one at all.

A step's contacts (engine.exact.contacts) are solved cheapest test first, since in a typical scene
few bodies meet anything:

1. ``near``, over every body in about twenty array operations: a lower bound on its distance
   to every face (one look-up in the grid, engine.geometry.face_grid, whose cells' bounds hold the
   endless lines too) against how far it can reach (``reach``).
2. ``narrow``, over those near a face: the faces each can reach, and whether its path, not
   yet turned by any bounce, can meet one at all (a tangent-line bound; see there). Bodies
   that cannot, and do not rest on a face, keep the state their method reached. Usually every
   body it looks at is in a cell clear of the endless lines' backs, and then each body's
   faces, endless or not, come from one row of a table and are tested alike
   (``FaceGrid.listed_fast``).

The rest are swept impact by impact (engine.exact.sweep, engine.exact.sweep_one).

The two bounds, in short (each derived where it is computed). A body on the path
x(t) = x0 + V t + B t^2 / 2 with velocity V + W t, bounced at most by e <= 1, covers at most
|V| T + |W| T^2 / 2 + |B| T^2 in a step T, so it reaches no farther than that plus its radius
r: if the grid's lower bound on its distance to every face is larger, it meets nothing. If it
is not, each face's distance d is convex along a straight line, so it lies above its tangent
at x0, d(x(t)) >= d(x0) + u.V t + u.B t^2 / 2 (u the unit vector from the face's nearest point
to x0), and a body whose bound d(x0) + min(u.V, 0) T - |B| T^2 / 2 stays above r for every
face it can reach meets none of them on its first, unturned path, hence none at all.

At a thousand bodies the cost is the count of array operations, each a microsecond or two
whatever its length, and the Python of the few impacts, not the arithmetic per body. A
clearance budget carried from step to step (a body's distance to the faces when last
looked at, less how far it has moved since) was measured and does not pay here: in the
benchmark's box balls move 0.1 to 0.2 m a step and the nearest face is a metre or two away,
so 110 to 140 of 1,000 need a fresh bound every step even with exact distances, and an
operation on 140 rows costs nearly what one on 1,000 does.

On the fast path (engine.kernels) both looks, with the resting bodies' test of staying put,
are one loop over the bodies, ``looks_loop`` (called by ``first_looks``): the same numbers
in the same order, at 1,000 bodies about 10 us a step where the array operations take about
60 (measured on a 2-core machine).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .. import kernels
from .impact import TOUCH

if TYPE_CHECKING:
    from .face_grid import FaceGrid
    from .faces import Faces

__all__ = ["first_looks", "grid_args", "looks_loop", "looks_ready", "narrow", "near", "reach"]


def reach(speed: np.ndarray, a: float, T: float, r: np.ndarray) -> np.ndarray:
    """How far from its start a ball can reach within T, bounces and all (length units), from
    its speed |V| (the array, turned into the answer in place) and a bound a on the sizes of
    its path's B and W.

    On each piece of its path x = x_k + V_k t + B t^2 / 2, and a bounce never raises the speed
    (e <= 1), so |V_k| <= |V| + |W| t: the distance covered is at most
    |V| T + |W| T^2 / 2 + |B| T^2, and the ball reaches r beyond its centre. (Sliding on a
    face, friction only slows it: its speed along the face is at most |V| + |W| t too.) A
    spinning ball's bounce can turn spin into speed: its caller grows r for that
    (engine.exact.contacts' ``_spin_reach``).
    """
    grow = 1.0 + 1e-9
    reach = speed
    reach *= T * grow
    reach += r * grow
    reach += 1.5 * a * (T * T) * grow + TOUCH
    return reach


def near(
    grid: FaceGrid,
    x0: np.ndarray,
    v0: np.ndarray,
    B: np.ndarray,
    W: np.ndarray,
    dt: float,
    radius: np.ndarray,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray, float]:
    """(whether each body's path this step may come within reach of a solid face, every
    body's grid cell or None, every body's reach, a bound on every body's |B| and |W|), for
    bodies on the paths x0 + v0 t + B t^2 / 2 with velocity v0 + W t over dt.

    This pass goes over every body, so it is kept to a few array operations: the reach
    (``reach``) takes the largest acceleration of all bodies, |B| <= sqrt(2) max |B_x|,
    |B_y|, in place of each body's own (a larger reach only lets more bodies through to
    the exact tests), and one lower bound on the distance to every face (``FaceGrid.gap``)
    is compared with it.
    """
    a_max = float(np.abs(B).max()) if W is B else float(max(np.abs(B).max(), np.abs(W).max()))
    a_bound = 1.4142136 * a_max
    vv = v0 * v0
    speed = vv[:, 0] + vv[:, 1]
    far = reach(np.sqrt(speed, out=speed), a_bound, dt, radius)
    cell = grid.cells(x0) if grid.n_finite else None
    need = grid.gap(x0, cell) <= far
    return need, cell, far, a_bound


def narrow(
    grid: FaceGrid,
    rows: np.ndarray,
    busy: np.ndarray,
    cell: np.ndarray | None,
    reach: np.ndarray,
    a_bound: float,
    x0: np.ndarray,
    v0: np.ndarray,
    dt: float,
    radius: np.ndarray,
    allowed: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Of the rows near a face, those that may meet one this step or rest on one, with the
    (body, face) pairs each is to test: (rows, pair bodies as places in rows, pair faces).

    ``busy``: the rows resting on a face (they slide, lift or stay: always solved), turned
    here into the rows kept. ``cell``, ``reach`` and ``a_bound``: ``near``'s, for these rows.
    ``allowed(rows, faces)``: whether each body meets each face, when colliders have filters.

    The pairs are every face a body can reach this step, bounces and all (``reach``);
    the solver needs them all, since a bounce turns the path. But a body meets nothing at
    all unless its first path, unturned, meets a face, so the bodies whose first paths
    surely meet nothing are dropped, by a test that errs only toward keeping them. With
    d(x) the distance of x from a face (less its radius rho), a ball of radius r meets it
    when d(x(t)) <= r. For a convex face, d is convex, so it lies above its tangent:

        d(x(t)) >= d(x0) + u.(x(t) - x0) = d(x0) + u.V t + u.B t^2 / 2,

    u being the unit vector from the face's nearest point to x0 (its normal s n for an
    endless line on side s). On [0, T] that is at least d(x0) + min(u.V, 0) T - |B| T^2 / 2,
    so a body whose bound stays above r on every face it can reach is dropped. The test is
    widened by 1e-8 of the lengths in it, far more than the root finders' rounding, so no
    pair the exact kernels would find a hit in is lost. The faces are an endless line
    (convex: a half-plane) or a capsule, the points within rho of a segment a-b: a flat
    face is the middle of its segment's capsule, a round face one with a = b.
    """
    T = dt
    grow = 1.0 + 1e-8
    # The right side of the test, r + |B| T^2 / 2, widened (reach > |V| T + |B| T^2).
    slack = radius.take(rows) * grow
    slack += 0.5 * a_bound * (T * T) * grow + 1e-8
    slack += 1e-8 * reach
    parts_b: list[np.ndarray] = []
    parts_f: list[np.ndarray] = []
    # The quick way (``FaceGrid._fast_lists``): every body in a cell wholly on the free
    # side of every endless face and reaching at most pad, so its cell's list holds every
    # face it can reach, the endless ones as capsules, all tested alike below.
    quick = (
        cell is not None
        and grid.table is not None
        and float(reach.max()) <= grid.pad
        and bool(grid.safe.take(cell).all())
    )
    if quick:
        assert cell is not None
        fb, ff = grid.listed_fast(cell)
        at = rows.take(fb)
        Xf, Vf = x0.take(at, axis=0), v0.take(at, axis=0)
    else:
        X, V = x0.take(rows, axis=0), v0.take(rows, axis=0)
        if grid.n_inf:
            # Endless faces (one-sided, s = 1: u = n), all rows against all of them at
            # once; d0 = n.(x0 - p) as the kernels compute it, so no rounding differs.
            px, py, nx, ny = grid.inf_cols
            d0 = X[:, :1] - px
            d0 *= nx
            dy = X[:, 1:] - py
            dy *= ny
            d0 += dy
            toward = V[:, :1] * nx
            toward += V[:, 1:] * ny
            np.minimum(toward, 0.0, out=toward)
            toward *= T
            low = d0 * (1.0 - 1e-8)
            low += toward
            busy |= (low <= grid.inf_rho_up + slack[:, None]).any(axis=1)
            bi, fi = np.nonzero(d0 - grid.inf_rho <= reach[:, None])
            parts_b.append(bi)
            parts_f.append(grid.inf_ids[fi])
        if cell is not None:
            fb, ff = grid.listed(reach, cell)
            Xf, Vf = X.take(fb, axis=0), V.take(fb, axis=0)
    if cell is not None:
        # The faces the grid lists, each a capsule: the points within rad of its segment
        # a-b (a flat face is the middle of one, a round face one with a = b). Their
        # numbers in one table: a, b - a, 1 / |b - a|^2, rad. (Each dot product as one
        # product and one sum of its columns: the same operations as column by column.)
        cap = grid.cap.take(ff, axis=0)
        ab = cap[:, 2:4]
        D = Xf - cap[:, :2]
        P = D * ab
        along = P[:, 0] + P[:, 1]
        along *= cap[:, 4]  # the nearest point: a + along (b - a)
        np.minimum(np.maximum(along, 0.0, out=along), 1.0, out=along)
        C = D - ab * along[:, None]  # from the nearest point of the segment to the ball
        P = C * C
        dist = P[:, 0] + P[:, 1]
        np.sqrt(dist, out=dist)
        gap = dist - cap[:, 5]
        # u = C / |C|; the test is multiplied by |C|, so it needs no division.
        P = C * Vf
        toward = P[:, 0] + P[:, 1]
        np.minimum(toward, 0.0, out=toward)
        meets = gap * dist * (1.0 - 1e-8) + toward * T <= slack[fb] * dist
        busy[fb[meets]] = True
        within = gap <= reach[fb]
        parts_b.append(fb[within])
        parts_f.append(ff[within])
    kept = np.flatnonzero(busy)
    if not len(kept):
        return kept, kept, kept
    pb = np.concatenate(parts_b) if len(parts_b) > 1 else parts_b[0]
    pf = np.concatenate(parts_f) if len(parts_f) > 1 else parts_f[0]
    if allowed is not None:
        # Faces of colliders whose filters a body's does not meet are not there for it.
        ok = allowed(rows[pb], pf)
        pb, pf = pb[ok], pf[ok]
    if len(kept) < len(rows):
        mine = busy[pb]
        pb, pf = np.searchsorted(kept, pb[mine]), pf[mine]  # its place among the kept
        rows = rows.take(kept)
    return rows, pb, pf


# -- the fast path: both looks in one loop over the bodies ------------------------------------


def looks_ready(grid: FaceGrid) -> bool:
    """Whether ``looks_loop`` can take this grid: it has finite faces and their table."""
    return bool(grid.n_finite) and grid.table is not None


_NO_ROWS = np.zeros(0, dtype=bool)
_NO_LINES = (np.zeros((0, 2)), np.zeros(0))


def first_looks(
    grid: FaceGrid,
    faces: Faces,
    x0: np.ndarray,
    v0: np.ndarray,
    B: np.ndarray,
    W: np.ndarray,
    dt: float,
    radius: np.ndarray,
    friction: np.ndarray,
    rest: np.ndarray,
    frozen: np.ndarray | None,
    allowed: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``narrow``'s (rows, pair bodies as places in rows, pair faces) for every body and the
    resting rows that stay put (``engine.exact.resting.asleep``), as engine.exact.contacts finds
    them on the numpy path (``near``, ``asleep``, ``narrow``), from one call of the loop kernel
    ``looks_loop`` (``looks_ready(grid)`` must hold). ``rest``: each body's resting face (-1:
    free); ``frozen``: rows left alone (or None). When a near body is not in the quick way's
    reach (``narrow``), its rows go to numpy's ``narrow``: the same pairs."""
    rows, pb, pf, quick, cell, far, a_bound, asleep = looks_loop(
        *grid_args(grid), faces.p, faces.n, faces.two, faces.c, faces.mu, x0, v0, B, W, dt,
        radius, friction, rest, _NO_ROWS if frozen is None else frozen,
    )  # fmt: skip
    if not quick:
        if not len(rows):
            return rows, rows, rows, asleep
        busy = rest.take(rows) >= 0
        rows, pb, pf = narrow(grid, rows, busy, cell, far, a_bound, x0, v0, dt, radius, allowed)
        return rows, pb, pf, asleep
    if allowed is not None and len(pb):
        # The filters drop pairs, not bodies (``narrow``): kept or not, in order.
        ok = allowed(rows[pb], pf)
        pb, pf = pb[ok], pf[ok]
    return rows, pb, pf, asleep


def grid_args(grid: FaceGrid) -> tuple[object, ...]:
    """The grid's part of ``looks_loop``'s arguments."""
    nx, ny = grid.shape
    assert grid.table is not None
    lines = _NO_LINES
    outside = _NO_ROWS
    if grid.n_inf and not grid.boxed:
        # Out in the ring the endless faces are measured (``FaceGrid.gap``).
        lines, outside = (grid.inf_n, grid.inf_c), grid.outside
    return (
        grid._gap_ring, float(grid._ring_lo[0]), float(grid._ring_lo[1]), 1.0 / grid.h,
        nx + 1.0, ny + 1.0, ny + 2, outside, *lines, grid.table, grid._slot_face,
        grid._ident, grid.safe, grid.pad, grid.cap,
    )  # fmt: skip


def _sample_looks() -> tuple[object, ...]:
    """The smallest call of ``looks_loop``: one ball in a 1 x 1 grid with one face."""
    x = np.array([[0.5, 0.5]])
    table = np.zeros((9, 1), dtype=np.int32)
    cap = np.array([[0.0, 0.0, 1.0, 0.0, 1.0, 0.0]])
    i = np.zeros(1, dtype=np.intp)
    return (
        np.zeros(9), -1.0, -1.0, 1.0, 2.0, 2.0, 3, _NO_ROWS, *_NO_LINES, table, i, True,
        np.ones(9, dtype=bool), 4.0, cap, x, x, i == 0, x, np.ones(1), x, x, x, x, 0.01,
        np.ones(1), np.ones(1), i - 1, _NO_ROWS,
    )  # fmt: skip


@kernels.loop(sample=_sample_looks)
def looks_loop(
    ring: np.ndarray,
    lo_x: float,
    lo_y: float,
    inv_h: float,
    top_x: float,
    top_y: float,
    stride: int,
    outside: np.ndarray,
    inf_n: np.ndarray,
    inf_c: np.ndarray,
    table: np.ndarray,
    slot_face: np.ndarray,
    ident: bool,
    safe: np.ndarray,
    pad: float,
    cap: np.ndarray,
    lp: np.ndarray,
    ln: np.ndarray,
    ltwo: np.ndarray,
    dc: np.ndarray,
    fmu: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    B: np.ndarray,
    W: np.ndarray,
    dt: float,
    radius: np.ndarray,
    friction: np.ndarray,
    rest: np.ndarray,
    frozen: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool, np.ndarray, np.ndarray, float, np.ndarray]:
    """``near`` and then ``narrow``'s quick way, body by body: (rows, pair bodies as places
    in rows, pair faces, whether the quick way held, and for ``narrow`` when it did not: the
    near rows, their cells and reaches (length units), the bound on |B| and |W|; and the
    resting rows that stay put, ``engine.exact.sweep_one.asleep_few``'s).

    The grid as ``FaceGrid`` holds it: ``ring`` the bounds with the ring (``gap``), the
    ring's corner, 1 / h, the top cells and the row stride (``cells``), the ring cells
    ``outside`` where the endless faces (normals ``inf_n``, offsets ``inf_c``) are measured
    (``gap``; empty: none are), ``table``,
    ``slot_face`` (unless ``ident``), ``safe``, ``pad`` and ``cap`` (``narrow``). A body is
    near when its grid bound is within its reach or it rests on a face, and not when asleep
    or frozen. The faces (lines p, n, two; discs c; mu) give a resting body's normal. Each
    number is the twins' own operations in their order, so the answers are theirs bit for
    bit.
    """
    n = x0.shape[0]
    # The bound on |B| and |W| of every body, as near's (|x| >= 0: the max starts at 0).
    a_max = 0.0
    for i in range(n):
        for k in range(2):
            a = abs(B[i, k])
            if a > a_max:
                a_max = a
            a = abs(W[i, k])
            if a > a_max:
                a_max = a
    a_bound = 1.4142136 * a_max
    grow = 1.0 + 1e-9
    T_grow = dt * grow
    extra = 1.5 * a_bound * (dt * dt) * grow + TOUCH  # reach's part shared by all
    L = lp.shape[0]
    sleeping = np.empty(n, dtype=np.intp)
    ns = 0
    rows = np.empty(n, dtype=np.intp)
    cells = np.empty(n, dtype=np.intp)
    far = np.empty(n)
    m = 0
    quick = True
    for i in range(n):
        f = rest[i]
        if f >= 0 and v0[i, 0] == 0.0 and v0[i, 1] == 0.0:
            # Resting still: it stays put if pressed onto its face and held by static
            # friction (``asleep_few``, with ``_normal_one``: the normal toward the body).
            px, py = x0[i, 0], x0[i, 1]
            if f < L:
                nx, ny = ln[f, 0], ln[f, 1]
                side = 1.0
                if ltwo[f] and (px - lp[f, 0]) * nx + (py - lp[f, 1]) * ny < 0.0:
                    side = -1.0
                nx, ny = nx * side, ny * side
            else:
                ddx, ddy = px - dc[f - L, 0], py - dc[f - L, 1]
                dist = math.sqrt(ddx * ddx + ddy * ddy)
                length = dist if dist > 0.0 else 1.0
                nx, ny = ddx / length, ddy / length
            wx, wy = W[i, 0], W[i, 1]
            a_n = wx * nx + wy * ny
            a_t = wy * nx - wx * ny  # along the tangent (-n_y, n_x)
            if a_n <= 0.0 and abs(a_t) <= friction[i] * fmu[f] * -a_n * (1.0 + 1e-12):
                sleeping[ns] = i
                ns += 1
                continue
        if frozen.shape[0] and frozen[i]:
            continue
        # The first look: the reach (``reach``) against the bound of the body's cell
        # (``FaceGrid.cells``: clipped to the ring, then truncated).
        vx = v0[i, 0]
        vy = v0[i, 1]
        r = radius[i] * grow
        reach_i = math.sqrt(vx * vx + vy * vy) * T_grow + r + extra
        fx = (x0[i, 0] - lo_x) * inv_h
        fx = 0.0 if fx < 0.0 else fx
        fx = top_x if fx > top_x else fx
        fy = (x0[i, 1] - lo_y) * inv_h
        fy = 0.0 if fy < 0.0 else fy
        fy = top_y if fy > top_y else fy
        c = int(fx) * stride + int(fy)
        gap = ring[c]
        if outside.shape[0] and outside[c]:
            for k in range(inf_c.shape[0]):  # ``FaceGrid.plane_distance``: n.x - c
                d = x0[i, 0] * inf_n[k, 0] + x0[i, 1] * inf_n[k, 1] - inf_c[k]
                gap = d if d < gap else gap
        if not (gap <= reach_i or rest[i] >= 0):
            continue
        rows[m] = i
        cells[m] = c
        far[m] = reach_i
        m += 1
        if not (reach_i <= pad and safe[c]):
            quick = False
    if not quick or m == 0:
        none = np.zeros(0, dtype=np.intp)
        return rows[:m], none, none, quick, cells[:m], far[:m], a_bound, sleeping[:ns]
    # The narrow look (``narrow``'s quick way): each near body against its cell's faces, each
    # a capsule. A body is kept if it rests or its first path may meet a face; its pairs are
    # the faces within its reach, numbered by its place among the kept.
    g8 = 1.0 + 1e-8
    shared = 0.5 * a_bound * (dt * dt) * g8 + 1e-8
    width = table.shape[1]
    kept = np.empty(m, dtype=np.intp)
    pb = np.empty(m * width, dtype=np.intp)
    pf = np.empty(m * width, dtype=np.intp)
    q = 0
    nk = 0
    for k in range(m):
        i = rows[k]
        slack = radius[i] * g8 + shared + 1e-8 * far[k]
        busy = rest[i] >= 0
        first = q
        x = x0[i, 0]
        y = x0[i, 1]
        vx = v0[i, 0]
        vy = v0[i, 1]
        for w in range(width):
            f = np.intp(table[cells[k], w])
            if f < 0:
                continue
            if not ident:
                f = slot_face[f]
            dx = x - cap[f, 0]
            dy = y - cap[f, 1]
            abx = cap[f, 2]
            aby = cap[f, 3]
            along = dx * abx + dy * aby
            along *= cap[f, 4]  # the nearest point: a + along (b - a), clipped to [0, 1]
            along = 0.0 if along < 0.0 else along
            along = 1.0 if along > 1.0 else along
            cx = dx - abx * along
            cy = dy - aby * along
            dist = math.sqrt(cx * cx + cy * cy)
            gap = dist - cap[f, 5]
            toward = cx * vx + cy * vy
            toward = 0.0 if toward > 0.0 else toward
            if gap * dist * (1.0 - 1e-8) + toward * dt <= slack * dist:
                busy = True
            if gap <= far[k]:
                pb[q] = nk
                pf[q] = f
                q += 1
        if busy:
            kept[nk] = i
            nk += 1
        else:
            q = first  # not kept: its pairs go
    return kept[:nk], pb[:q], pf[:q], True, cells[:m], far[:m], a_bound, sleeping[:ns]
