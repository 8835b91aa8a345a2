"""The broadphase for static faces: a grid over the faces, and a step's first two looks.

A step's contacts (engine.contacts) are solved cheapest test first, since in a typical scene
few bodies meet anything:

1. ``near``, over every body in about twenty array operations: a lower bound on its distance
   to every face (one look-up in the grid, whose cells' bounds hold the endless lines too)
   against how far it can reach (``reach``).
2. ``narrow``, over those near a face: the faces each can reach, and whether its path, not
   yet turned by any bounce, can meet one at all (a tangent-line bound; see there). Bodies
   that cannot, and do not rest on a face, keep the state their method reached. Usually every
   body it looks at is in a cell clear of the endless lines' backs, and then each body's
   faces, endless or not, come from one row of a table and are tested alike
   (``FaceGrid._fast_lists``).

The rest are swept impact by impact (engine.sweep, engine.sweep_one).

At a thousand bodies the cost is the count of array operations, each a microsecond or two
whatever its length, and the Python of the few impacts, not the arithmetic per body. A
clearance budget carried from step to step (a body's distance to the faces when last
looked at, less how far it has moved since) was measured and does not pay here: in the
benchmark's box balls move 0.1 to 0.2 m a step and the nearest face is a metre or two away,
so 110 to 140 of 1,000 need a fresh bound every step even with exact distances, and an
operation on 140 rows costs nearly what one on 1,000 does.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .faces import Faces, dot
from .impact import TOUCH

__all__ = ["FaceGrid", "narrow", "near", "reach"]


def reach(speed: np.ndarray, a: float, T: float, r: np.ndarray) -> np.ndarray:
    """How far from its start a ball can reach within T, bounces and all (length units), from
    its speed |V| (the array, turned into the answer in place) and a bound a on the sizes of
    its path's B and W.

    On each piece of its path x = x_k + V_k t + B t^2 / 2, and a bounce never raises the speed
    (e <= 1), so |V_k| <= |V| + |W| t: the distance covered is at most
    |V| T + |W| T^2 / 2 + |B| T^2, and the ball reaches r beyond its centre. (Sliding on a
    face, friction only slows it: its speed along the face is at most |V| + |W| t too.)
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


class FaceGrid:
    """The broadphase for static faces: a uniform grid over the finite faces.

    Each cell stores a lower bound on the distance from any of its points to the nearest
    finite face (the exact distance from its centre, less half its diagonal), so a body whose
    path cannot reach that far is skipped in one comparison, and the list of the faces that
    lie within ``pad`` of the cell, so a body that can reach one meets only those. Outside the
    grid every finite face is at least ``margin`` away. Lines without end (a Plane, a Box's
    walls) are few: the grid covers a Box's corners too, its cells' bounds for the first look
    (``gap``) count them as well, and the narrow pass checks them against each body near
    one directly.

    A game adds and takes out colliders between steps: ``added`` and ``removed`` change the
    grid in place, in the new or old faces' windows of cells, and leave it as building it
    afresh would (the same bounds, lists in the same order, capsules), unless that would lay
    it differently (its extent or its endless faces change): then the caller drops it. The
    lists hold slots, each a face's index when it was listed (``_slot_face`` gives its index
    now), so faces renumbered by a change need no pass over the lists.
    """

    def __init__(self, faces: Faces) -> None:
        L = len(faces.p)
        inf_lines = np.flatnonzero(faces.infinite)
        self.n_inf = len(inf_lines)
        self.inf_ids = inf_lines
        self.inf_n = faces.n[inf_lines]
        self.inf_p = faces.p[inf_lines]
        self.inf_rho = faces.rho[inf_lines]
        self.inf_rho_up = self.inf_rho * (1.0 + 1e-8)
        # The columns p_x, p_y, n_x, n_y, each a row to broadcast against a column of bodies.
        self.inf_cols = tuple(np.ascontiguousarray(a) for a in (*self.inf_p.T, *self.inf_n.T))
        # n.x - (n.p + rho): the distance of x from each endless face.
        self.inf_c = dot(self.inf_p, self.inf_n) + self.inf_rho
        fin_lines = np.flatnonzero(~faces.infinite)
        self.finite = np.concatenate([fin_lines, L + np.arange(len(faces.c))]).astype(np.intp)
        self.n_finite = len(self.finite)
        self.table: np.ndarray | None = None
        self.fin_table: np.ndarray | None = None
        self._ident = True
        if not self.n_finite:
            return
        # Each finite face as a capsule: segment a-b, radius rad.
        tang = np.stack([-faces.n[:, 1], faces.n[:, 0]], axis=1)
        A = np.concatenate(
            [faces.p[fin_lines] + tang[fin_lines] * faces.lo[fin_lines, None], faces.c]
        )
        Bq = np.concatenate(
            [faces.p[fin_lines] + tang[fin_lines] * faces.hi[fin_lines, None], faces.c]
        )
        rad = np.concatenate([faces.rho[fin_lines], faces.r])
        # The capsules by face index (an endless face's is nan: it passes no test), for the
        # tests of ``narrow``: a, b - a, 1 / |b - a|^2 (0 for a point), and rad grown
        # by 1e-8 and by more than the rounding of distances along a long face.
        F = L + len(faces.c)
        self.cap_a = np.full((F, 2), np.nan)
        self.cap_ab = np.full((F, 2), np.nan)
        self.cap_inv = np.full(F, np.nan)
        self.cap_rad = np.full(F, np.nan)
        seg = Bq - A
        seg2 = dot(seg, seg)
        self.cap_a[self.finite] = A
        self.cap_ab[self.finite] = seg
        self.cap_inv[self.finite] = np.where(seg2 > 0.0, 1.0 / np.where(seg2 > 0.0, seg2, 1.0), 0.0)
        self.cap_rad[self.finite] = rad * (1.0 + 1e-8) + 1e-10 * (1.0 + np.sqrt(seg2))
        lo = np.minimum(A, Bq).min(axis=0) - rad.max()
        hi = np.maximum(A, Bq).max(axis=0) + rad.max()
        covers = False  # whether the grid covers every endless face's point
        if self.n_inf:
            # The grid also covers the endless faces' points (a Box's corners) when that does
            # not coarsen it much (a box at most 4 times the finite faces' extent), so a body
            # in the box is looked up inside it, where the endless faces are in the bounds
            # (below); outside, ``gap`` measures them.
            lo2 = np.minimum(lo, self.inf_p.min(axis=0))
            hi2 = np.maximum(hi, self.inf_p.max(axis=0))
            if float((hi2 - lo2).max()) <= 4.0 * float((hi - lo).max()):
                lo, hi = lo2, hi2
                covers = True
        size = max(float((hi - lo).max()), 1e-6)
        self.margin = max(0.02 * size, 1e-3)
        self.lo = lo - self.margin
        span = (hi - lo) + 2.0 * self.margin
        cells = 384
        self.h = h = float(span.max()) / cells
        if self.n_inf:
            # A floor's (or a left wall's) line just below a cell's lower edge (by 1e-6 h):
            # a body resting on it is then in a cell wholly above it (``_fast_lists``).
            lo_grid = self.lo.copy()
            for axis in (0, 1):
                for k in range(self.n_inf):
                    if self.inf_n[k, axis] == 1.0 and self.inf_n[k, 1 - axis] == 0.0:
                        edge = float(self.inf_p[k, axis]) + 1e-6 * h
                        lo_grid[axis] = edge - math.ceil((edge - self.lo[axis]) / h) * h
                        break
            span += self.lo - lo_grid  # less than h more: the extra cell below covers it
            self.lo = lo_grid
        self.pad = 4.0 * h  # a body reaching at most this far meets only its cell's list
        #: Bounds are kept up to this distance; farther cells hold this (still a lower bound).
        self.far = 16.0 * h
        nx, ny = (np.ceil(span / h).astype(int) + 1).tolist()
        self.shape = (nx, ny)
        gx = self.lo[0] + (np.arange(nx) + 0.5) * h
        gy = self.lo[1] + (np.arange(ny) + 0.5) * h
        half_diag = h * math.sqrt(0.5)
        self._gx, self._gy, self._half_diag = gx, gy, half_diag
        # What a collider added or taken out (``added``, ``removed``) needs: the extent the
        # grid was laid over, and each face's capsule and window of cells. The lists hold
        # slots, each a face's place when it was listed; ``_slot_face`` gives its index now.
        self._ext = (np.minimum(A, Bq).min(axis=0), np.maximum(A, Bq).max(axis=0), rad.max())
        self._slot_face = np.arange(F, dtype=np.intp)
        self._face_slot = np.arange(F, dtype=np.intp)
        self._slot_inf = np.concatenate([faces.infinite, np.zeros(len(faces.c), dtype=bool)])
        # Each finite face's capsule: a, b, rad, and |b - a|^2 as ``_distances`` takes it.
        self._seg = np.full((F, 6), np.nan)
        self._win = np.zeros((F, 4), dtype=np.intp)  # its window of cells: i0, i1, j0, j1
        # Whether every slot is its face's index (true until a face is added or taken out).
        bound = np.full((nx, ny), self.far)
        cell_parts: list[np.ndarray] = []
        face_parts: list[np.ndarray] = []
        for k in range(self.n_finite):
            a, b, rr = A[k], Bq[k], rad[k]
            f = int(self.finite[k])
            i0, i1, j0, j1 = win = self._window(a, b, rr)
            dist = self._distances(a, b, rr, win)
            np.minimum(bound[i0:i1, j0:j1], dist, out=bound[i0:i1, j0:j1])
            di, dj = np.nonzero(dist <= self.pad)
            cell_parts.append((i0 + di) * ny + (j0 + dj))
            face_parts.append(np.full(len(di), f, dtype=np.intp))
            self._seg[f] = (a[0], a[1], b[0], b[1], rr, _length2(a, b))
            self._win[f] = win
        # The bounds with a ring of cells around them holding the margin: any point outside
        # the grid is looked up in the ring (clipped), so a lookup needs no inside test.
        ring = np.full((nx + 2, ny + 2), self.margin)
        ring[1:-1, 1:-1] = bound
        self._ring = ring.reshape(-1)
        self.bound = ring[1:-1, 1:-1]  # a view: the same numbers
        # ``gap``'s bounds: the same with the endless faces in them, so inside the grid a
        # lookup is the whole lower bound. The signed distance from a face, n.x - c, changes
        # by at most |x - x'| between two points, so over a cell it is at least its value at
        # the centre less half the diagonal (less 1e-9 h more, far beyond the rounding of
        # these few operations: the reach compared with it is widened by 1e-9 of itself and
        # TOUCH). In the ring (outside the grid) an endless face may be anywhere near: there
        # ``gap`` adds the distances from them (``_outside`` marks those cells), or when they
        # are all a Box's walls and the grid covers its corners, the ring holds -inf: a body
        # outside the grid is outside the box, in the wall, and is always looked at.
        self._gap_ring = self._ring
        self._gap_inner = self.bound
        self.boxed = faces.boxed and covers
        self._inf_bound: np.ndarray | None = None
        if self.n_inf:
            endless = np.full((nx, ny), np.inf)
            for k in range(self.n_inf):
                (pnx, pny), c = self.inf_n[k], self.inf_c[k]
                at = np.add.outer(gx * pnx, gy * pny)  # cx n_x + cy n_y, cell by cell
                at -= c
                at -= half_diag + 1e-9 * h
                np.minimum(endless, at, out=endless)
            self._inf_bound = endless  # the endless faces' part of the bounds, kept
            ring = np.full((nx + 2, ny + 2), -np.inf if self.boxed else self.margin)
            np.minimum(bound, endless, out=ring[1:-1, 1:-1])
            self._gap_ring = ring.reshape(-1)
            self._gap_inner = ring[1:-1, 1:-1]
            outside = np.ones((nx + 2, ny + 2), dtype=bool)
            outside[1:-1, 1:-1] = False
            self.outside = outside.reshape(-1)
        self._ring_lo = self.lo - h  # the ring's lower-left corner
        self._tiles = (np.zeros(0), np.zeros(0))  # for ``cells``, grown as needed
        # The lists are kept by ring cell too; the ring's are empty. A body out in the ring
        # that reaches at most pad meets nothing finite: pad (4 h, at most 0.0108 of the
        # faces' extent plus margins) is less than the margin (0.02 of it, or 1e-3).
        ii, jj = np.divmod(np.concatenate(cell_parts).astype(np.intp), ny)
        cells_all = (ii + 1) * (ny + 2) + (jj + 1)
        order = np.argsort(cells_all, kind="stable")
        self.faces_of = np.concatenate(face_parts)[order]
        counts = np.bincount(cells_all, minlength=(nx + 2) * (ny + 2)).astype(np.intp)
        self.count = counts
        self.start = (np.cumsum(counts) - counts).astype(np.intp)
        self._fast_lists(faces, A, Bq, rad, cell_parts, face_parts, gx, gy, half_diag)

    def _fast_lists(
        self,
        faces: Faces,
        A: np.ndarray,
        Bq: np.ndarray,
        rad: np.ndarray,
        cell_parts: list[np.ndarray],
        face_parts: list[np.ndarray],
        gx: np.ndarray,
        gy: np.ndarray,
        half_diag: float,
    ) -> None:
        """The lists for ``narrow``'s quick way, ``table``: each cell's faces with
        the endless ones among them, as rows of a table (-1 past the end).

        An endless face is a half-plane: on its free side, n.(x - p) >= 0, the distance from
        it is the distance from its line, which over the grid is the distance from the
        line's piece between the projections of the grid's corners (the projection of a
        point of the grid lies between those of the corners), grown by h at each end: a
        capsule, listed and tested as the finite faces are. ``safe`` marks the cells wholly
        on the free side of every endless line (every corner beyond it, with a margin for
        rounding); the ring's are not safe, since the lists
        hold nothing there. A body in a safe cell that reaches at most pad finds in its
        cell's list every face it can reach, endless or not (a face within pad of the body is
        within pad plus half the diagonal of the cell's centre, what the lists hold). The
        endless faces come first in each list, in their order, then the finite ones: each
        body's faces in the order the other way gives them (endless, then listed).
        """
        nx, ny = self.shape
        h, pad = self.h, self.pad
        safe = np.ones((nx + 2, ny + 2), dtype=bool)
        wall_cells: list[np.ndarray] = []
        wall_faces: list[np.ndarray] = []
        if self.n_inf:
            safe[:] = False
            inner = np.ones((nx, ny), dtype=bool)
            top = self.lo + np.array([nx, ny], dtype=float) * h
            corners = np.array(
                [[self.lo[0], self.lo[1]], [top[0], self.lo[1]], [self.lo[0], top[1]], top]
            )
            # A point is found in a cell (``cells``) up to the rounding of its coordinates
            # less the grid's corner, a few ulps of the largest: the cells clear the lines
            # by 1e-9 h and 1e-14 of that more.
            slack = 1e-9 * h + 1e-14 * (1.0 + float(np.abs(corners).max()))
            for k in range(self.n_inf):
                p, n, rr = self.inf_p[k], self.inf_n[k], float(self.inf_rho[k])
                t = np.array([-n[1], n[0]])
                along = (corners - p) @ t
                a = p + t * (float(along.min()) - h)
                seg = t * (float(along.max()) - float(along.min()) + 2.0 * h)
                seg2 = float(seg @ seg)
                fid = int(self.inf_ids[k])
                self.cap_a[fid] = a
                self.cap_ab[fid] = seg
                self.cap_inv[fid] = 1.0 / seg2
                self.cap_rad[fid] = rr * (1.0 + 1e-8) + 1e-10 * (1.0 + math.sqrt(seg2))
                # n.(x - p) at each cell's centre; every centre projects onto the capsule's
                # segment, so its distance from the capsule is |n.(x - p)| - rr.
                side = np.add.outer((gx - p[0]) * n[0], (gy - p[1]) * n[1])
                di, dj = np.nonzero(np.abs(side) - (rr + half_diag) <= pad)
                wall_cells.append(di * ny + dj)
                wall_faces.append(np.full(len(di), fid, dtype=np.intp))
                # n.(x - p) is linear: over the cell, least at a corner, by (|n_x| + |n_y|) h / 2
                # below the centre's value.
                inner &= side - (0.5 * h * (abs(n[0]) + abs(n[1])) + slack) >= 0.0
            safe[1:-1, 1:-1] = inner
        self.safe = safe.reshape(-1)
        if wall_cells:
            ii, jj = np.divmod(np.concatenate(wall_cells + cell_parts).astype(np.intp), ny)
            cells_all = (ii + 1) * (ny + 2) + (jj + 1)
            order = np.argsort(cells_all, kind="stable")
            faces_sorted = np.concatenate(wall_faces + face_parts)[order]
            cells_sorted = cells_all[order]
            counts = np.bincount(cells_all, minlength=(nx + 2) * (ny + 2))
        else:  # no endless faces: the lists are the finite ones, already sorted
            faces_sorted, counts = self.faces_of, self.count
            cells_sorted = np.repeat(np.arange(len(counts)), counts)
        self.table = _as_table(cells_sorted, faces_sorted, counts)
        #: The finite faces' lists alone as a table too (``listed``), when they fit one:
        #: rows can take a face or give one up in place (``added``, ``removed``). Without it
        #: (faces crowded in a cell) ``listed`` reads the sorted lists, and a change of the
        #: colliders builds the grid afresh.
        self.fin_table = None
        if self.table is not None:
            if wall_cells:
                cells_fin = np.repeat(np.arange(len(self.count)), self.count)
                self.fin_table = _as_table(cells_fin, self.faces_of, self.count)
            else:
                self.fin_table = self.table
        # Each face's capsule numbers in one table (a row per face) for ``narrow``.
        self.cap = np.column_stack([self.cap_a, self.cap_ab, self.cap_inv, self.cap_rad])

    def _window(self, a: np.ndarray, b: np.ndarray, rr: float) -> tuple[int, int, int, int]:
        """The cells (i0:i1, j0:j1) that can hold a bound from the capsule a-b of radius rr:
        those within ``far`` of it (its box, grown)."""
        h, (nx, ny) = self.h, self.shape
        grow = rr + self.far + h
        i0 = max(int((min(a[0], b[0]) - grow - self.lo[0]) / h), 0)
        i1 = min(int((max(a[0], b[0]) + grow - self.lo[0]) / h) + 1, nx)
        j0 = max(int((min(a[1], b[1]) - grow - self.lo[1]) / h), 0)
        j1 = min(int((max(a[1], b[1]) + grow - self.lo[1]) / h) + 1, ny)
        return i0, i1, j0, j1

    def _distances(
        self, a: np.ndarray, b: np.ndarray, rr: float, win: tuple[int, int, int, int]
    ) -> np.ndarray:
        """The lower bound the capsule a-b of radius rr gives the cells of ``win``: the
        distance from each cell's centre less half its diagonal (no point of a cell is
        nearer). Cell by cell the same numbers whatever the window."""
        i0, i1, j0, j1 = win
        # The cells' centres as a column of x and a row of y, broadcast: each cell's numbers
        # come from the same operations on the same two coordinates as over a full mesh.
        dx = self._gx[i0:i1, None] - a[0]
        dy = self._gy[None, j0:j1] - a[1]
        ab = b - a
        ab2 = _length2(a, b)
        if ab2 > 0:
            u = (dx * ab[0] + dy * ab[1]) / ab2
            np.clip(u, 0.0, 1.0, out=u)
            dist = np.hypot(dx - u * ab[0], dy - u * ab[1])
        else:  # a point: u = 0, and x - 0 * 0 is x
            dist = np.hypot(dx, dy)
        dist -= rr
        dist -= self._half_diag
        return dist

    def added(self, faces: Faces, first: int, flat: int, round_: int) -> bool:
        """Take in the faces of a collider just added (``engine.faces.faces_added``: its
        ``flat`` flat faces are ``first``..., its ``round_`` round ones the last), in place:
        its lists, bounds and capsules, the same as building the grid afresh. False (and
        nothing changed) when the grid must be built afresh instead: it has no finite faces
        or no tables, the collider has an endless face, or it reaches past the extent the
        grid was laid over."""
        if not self.n_finite or self.fin_table is None or self.table is None:
            return False
        if flat and bool(faces.infinite[first : first + flat].any()):
            return False
        F, D = len(faces.owner), len(faces.c)
        # Each new face's capsule a-b of radius rad, as __init__ takes it.
        A: list[np.ndarray] = []
        Bq: list[np.ndarray] = []
        rad: list[float] = []
        if flat:
            fl = slice(first, first + flat)
            n = faces.n[fl]
            tang = np.stack([-n[:, 1], n[:, 0]], axis=1)
            A += list(faces.p[fl] + tang * faces.lo[fl, None])
            Bq += list(faces.p[fl] + tang * faces.hi[fl, None])
            rad += faces.rho[fl].tolist()
        A += list(faces.c[D - round_ :])
        Bq += A[flat:]
        rad += faces.r[D - round_ :].tolist()
        lo, hi, rmax = self._ext
        for a, b, rr in zip(A, Bq, rad, strict=True):
            if (
                rr > rmax
                or min(a[0], b[0]) < lo[0]
                or min(a[1], b[1]) < lo[1]
                or max(a[0], b[0]) > hi[0]
                or max(a[1], b[1]) > hi[1]
            ):
                return False  # a grid laid afresh would be laid differently
        count = flat + round_
        ids = list(range(first, first + flat)) + list(range(F - round_, F))
        S = len(self._slot_face)
        slots = list(range(S, S + count))
        sf = self._slot_face
        shifted = flat and D > round_  # round faces before it move up past its flat ones
        if shifted:
            sf[sf >= first] += flat
        self._slot_face = np.concatenate([sf, ids])
        fs = self._face_slot
        if flat:
            self._face_slot = np.concatenate([fs[:first], slots[:flat], fs[first:], slots[flat:]])
        else:
            self._face_slot = np.concatenate([fs, slots])
        self._slot_inf = np.concatenate([self._slot_inf, np.zeros(count, dtype=bool)])
        # Capsule rows, as __init__ makes them (the same operations, in floats).
        seg, rows, wins = [], [], []
        for a, b, rr in zip(A, Bq, rad, strict=True):
            abx, aby = float(b[0] - a[0]), float(b[1] - a[1])
            ab2 = abx * abx + aby * aby
            inv = 1.0 / ab2 if ab2 > 0.0 else 0.0
            rows.append(
                (a[0], a[1], abx, aby, inv, rr * (1.0 + 1e-8) + 1e-10 * (1.0 + math.sqrt(ab2)))
            )
            seg.append((a[0], a[1], b[0], b[1], rr, _length2(a, b)))
            wins.append(self._window(a, b, rr))
        self._seg = np.concatenate([self._seg, seg])
        self._win = np.concatenate([self._win, wins])
        cap, new_rows = self.cap, np.array(rows)
        if flat:
            self.cap = np.concatenate([cap[:first], new_rows[:flat], cap[first:], new_rows[flat:]])
        else:
            self.cap = np.concatenate([cap, new_rows])
        self._ident = self._ident and not shifted
        if flat:
            self._renumbered(faces)
        else:
            self.finite = np.concatenate([self.finite, ids])
            self.n_finite = len(self.finite)
        key = self._keys() if shifted else None
        ny = self.shape[1]
        for k in range(count):
            s, f = slots[k], ids[k]
            i0, i1, j0, j1 = win = wins[k]
            dist = self._distances(A[k], Bq[k], rad[k], win)
            np.minimum(self.bound[i0:i1, j0:j1], dist, out=self.bound[i0:i1, j0:j1])
            self._bounds_changed(win)
            di, dj = np.nonzero(dist <= self.pad)
            cells = (i0 + di + 1) * (ny + 2) + (j0 + dj + 1)
            for which in ("table", "fin_table"):
                if which == "fin_table" and self.fin_table is self.table:
                    continue
                table = getattr(self, which)
                # The face goes last in each list unless it is flat and round faces are
                # listed after it (then by ``key``).
                grown = _insert(table, cells, s, f, key)
                if grown is None:
                    return False  # the caller drops this grid
                if grown is not table:
                    if self.fin_table is table:
                        self.fin_table = grown
                    setattr(self, which, grown)
        return True

    def removed(self, faces: Faces, index: np.ndarray, gone: np.ndarray) -> bool:
        """Let go of the faces ``gone`` of a collider just taken out (old indices;
        ``index``: each old face's new index, ``engine.faces.faces_removed``), in place: the
        same lists, bounds and capsules as building the grid afresh. False when it must be
        built afresh instead (as for ``added``, or when the extent the grid was laid over
        shrinks)."""
        if not self.n_finite or self.fin_table is None or self.table is None:
            return False
        slots = self._face_slot[gone]
        if bool(self._slot_inf[slots].any()):
            return False
        live = (self._slot_face >= 0) & ~self._slot_inf
        live[slots] = False
        if not live.any():
            return False
        lo, hi, rmax = self._ext
        inner = all(
            rr < rmax
            and min(a0, b0) > lo[0]
            and min(a1, b1) > lo[1]
            and max(a0, b0) < hi[0]
            and max(a1, b1) < hi[1]
            for a0, a1, b0, b1, rr, _ in self._seg[slots].tolist()
        )
        if not inner:
            # It touches the extent the grid was laid over: is that extent still the same?
            seg = self._seg[live]
            A, Bq, rad = seg[:, :2], seg[:, 2:4], seg[:, 4]
            if not (
                np.array_equal(np.minimum(A, Bq).min(axis=0), lo)
                and np.array_equal(np.maximum(A, Bq).max(axis=0), hi)
                and float(rad.max()) == rmax
            ):
                return False
        tables = [self.table] if self.fin_table is self.table else [self.table, self.fin_table]
        sf = self._slot_face
        self._slot_face = np.where(sf >= 0, index[np.maximum(sf, 0)], -1)
        kept = index >= 0
        self._face_slot = self._face_slot[kept]
        self.cap = self.cap[kept]
        self._renumbered(faces)
        ny = self.shape[1]
        for s in slots.tolist():
            sg = self._seg[s]
            i0, i1, j0, j1 = w = tuple(self._win[s].tolist())
            dist = self._distances(sg[:2], sg[2:4], sg[4], w)
            di, dj = np.nonzero(dist <= self.pad)
            cells = (i0 + di + 1) * (ny + 2) + (j0 + dj + 1)
            for table in tables:
                _take_out(table, cells, s)
            # The cells it was the least bound of (or tied): only there the bound changes,
            # to the least of the faces left whose windows hold the cell, or ``far``.
            di, dj = np.nonzero(dist <= self.bound[i0:i1, j0:j1])
            if len(di):
                self.bound[i0 + di, j0 + dj] = self._least(live, i0 + di, j0 + dj)
                self._bounds_changed(w)
            self._seg[s] = np.nan
        if 2 * int(live.sum()) + 64 < len(self._slot_face):
            self._compact()
        return True

    def _least(self, live: np.ndarray, ci: np.ndarray, cj: np.ndarray) -> np.ndarray:
        """The bounds of cells (ci, cj) from the ``live`` faces (by slot) whose windows hold
        them, at most ``far``: what building afresh gives them, by the same operations as
        ``_distances`` on each face's numbers, all faces at once."""
        win = self._win
        # Windows (i0, i1, j0, j1) that meet the cells' box: i0 <= i_max, -i1 <= -i_min - 1,
        # j0 <= j_max and -j1 <= -j_min - 1, all at once.
        i_lo, i_hi, j_lo, j_hi = int(ci.min()), int(ci.max()), int(cj.min()), int(cj.max())
        meets = (win * _FLIP <= (i_hi, -i_lo - 1, j_hi, -j_lo - 1)).all(axis=1)
        near = np.flatnonzero(meets & live)
        least = np.full(len(ci), self.far)
        if not len(near):
            return least
        sg, w = self._seg[near], win[near]
        a0, a1, b0, b1 = (sg[:, k : k + 1] for k in range(4))
        rr, ab2 = sg[:, 4:5], sg[:, 5:6]
        held = (ci >= w[:, 0:1]) & (ci < w[:, 1:2]) & (cj >= w[:, 2:3]) & (cj < w[:, 3:4])
        dx = self._gx[ci] - a0  # (faces, cells)
        dy = self._gy[cj] - a1
        abx, aby = b0 - a0, b1 - a1
        point = ab2 <= 0.0
        u = (dx * abx + dy * aby) / np.where(point, 1.0, ab2)
        np.clip(u, 0.0, 1.0, out=u)
        u[np.broadcast_to(point, u.shape)] = 0.0  # a point: x - 0 * 0 is x
        dist = np.hypot(dx - u * abx, dy - u * aby)
        dist -= rr
        dist -= self._half_diag
        dist[~held] = np.inf
        np.minimum(least, dist.min(axis=0), out=least)
        return least

    def _renumbered(self, faces: Faces) -> None:
        """After faces were added or taken out: the endless and finite faces' indices, and
        whether every slot is its face's index."""
        L = len(faces.p)
        self.inf_ids = np.flatnonzero(faces.infinite)
        self.finite = np.concatenate([np.flatnonzero(~faces.infinite), L + np.arange(len(faces.c))])
        self.finite = self.finite.astype(np.intp)
        self.n_finite = len(self.finite)
        sf = self._slot_face
        self._ident = len(sf) == len(faces.owner) and bool(np.array_equal(sf, np.arange(len(sf))))

    def _keys(self) -> np.ndarray:
        """Each slot's place in a table's rows: the endless faces first (-1), then by index."""
        return np.where(self._slot_inf, -1, self._slot_face)

    def _bounds_changed(self, win: tuple[int, int, int, int]) -> None:
        """``gap``'s bounds over ``win`` from ``bound`` (the ring's share the same numbers)."""
        i0, i1, j0, j1 = win
        if self._inf_bound is not None:
            np.minimum(
                self.bound[i0:i1, j0:j1],
                self._inf_bound[i0:i1, j0:j1],
                out=self._gap_inner[i0:i1, j0:j1],
            )

    def _compact(self) -> None:
        """Slots renumbered as the faces' indices (many faces were taken out)."""
        sf = self._slot_face
        live = sf >= 0
        order = sf[live]  # the faces of the live slots, slot order
        for name in ("table", "fin_table"):
            table = getattr(self, name)
            if table is None or (name == "fin_table" and table is self.table):
                continue
            ok = table >= 0
            table[ok] = sf[table[ok]]
        F = len(self._face_slot)
        seg = np.full((F, 6), np.nan)
        win = np.zeros((F, 4), dtype=np.intp)
        inf = np.zeros(F, dtype=bool)
        seg[order] = self._seg[live]
        win[order] = self._win[live]
        inf[order] = self._slot_inf[live]
        self._seg, self._win, self._slot_inf = seg, win, inf
        self._slot_face = np.arange(F, dtype=np.intp)
        self._face_slot = np.arange(F, dtype=np.intp)
        self._ident = True

    def listed_fast(self, cell: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(body, face) pairs from ``table`` for bodies in safe cells reaching at most pad:
        each body's listed faces, bodies in order, each body's faces in list order."""
        assert self.table is not None
        rows = self.table.take(cell, axis=0)
        has = rows >= 0
        fb, _ = np.nonzero(has)
        ff = rows[has].astype(np.intp)
        return fb, ff if self._ident else self._slot_face.take(ff)

    def cells(self, x: np.ndarray) -> np.ndarray:
        """Each point's cell (with the ring; a point outside the grid takes the ring cell
        nearest it): an index into the bounds (``gap``) and the lists (``listed``)."""
        nx, ny = self.shape
        # The (N, 2) points as one flat array against the corner and the top repeated
        # (x, y, x, y, ...): an (N, 2) array with a (2,) one costs ~3x more than two columns,
        # and two columns twice the calls. Clipped to the ring first, so truncation toward
        # zero is the floor. The same operations on each coordinate as column by column.
        m = 2 * len(x)
        if len(self._tiles[0]) < m:
            k = max(len(x), len(self._tiles[0]))  # points: at least twice the last
            self._tiles = (np.tile(self._ring_lo, k), np.tile([nx + 1.0, ny + 1.0], k))
        ij = x.reshape(-1) - self._tiles[0][:m]
        ij *= 1.0 / self.h
        np.maximum(ij, 0.0, out=ij)
        np.minimum(ij, self._tiles[1][:m], out=ij)
        k_ij = ij.astype(np.intp)
        cell = k_ij[0::2] * (ny + 2)
        cell += k_ij[1::2]
        return cell

    def plane_distance(self, x: np.ndarray, k: int) -> np.ndarray:
        """Distance of each point from the k-th endless face (a wall of a Box is one column)."""
        nx, ny = self.inf_n[k]
        c = self.inf_c[k]
        for col, n_col, other in ((0, nx, ny), (1, ny, nx)):
            if other == 0.0 and n_col == 1.0:
                return x[:, col] - c
            if other == 0.0 and n_col == -1.0:
                return -c - x[:, col]  # -x - c, exactly
        return x[:, 0] * nx + x[:, 1] * ny - c

    def gap(self, x: np.ndarray, cell: np.ndarray | None) -> np.ndarray:
        """A lower bound (length units) on each point's distance to every face: its cell's
        bound, which holds the endless faces too, or outside the grid the ring's clearance
        from the finite faces and its distance from each endless one."""
        if cell is not None:
            d = self._gap_ring[cell]  # inside the grid, the endless faces are in its bounds
            if self.n_inf and not self.boxed:
                out = self.outside[cell]
                if out.any():
                    far = np.flatnonzero(out)
                    xf = x.take(far, axis=0)
                    for k in range(self.n_inf):
                        d[far] = np.minimum(d[far], self.plane_distance(xf, k))
            return d
        d = np.full(len(x), np.inf)
        for k in range(self.n_inf):
            np.minimum(d, self.plane_distance(x, k), out=d)
        return d

    def pairs(self, X: np.ndarray, reach: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(body, face) pairs to test: the endless faces within reach, and the finite ones
        ``listed`` for each body."""
        parts_b: list[np.ndarray] = []
        parts_f: list[np.ndarray] = []
        if self.n_inf:
            d = X @ self.inf_n.T - self.inf_c
            bi, fi = np.nonzero(d <= reach[:, None])
            parts_b.append(bi)
            parts_f.append(self.inf_ids[fi])
        if self.n_finite:
            fb, ff = self.listed(reach, self.cells(X))
            parts_b.append(fb)
            parts_f.append(ff)
        if not parts_b:
            return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
        return np.concatenate(parts_b), np.concatenate(parts_f)

    def listed(self, reach: np.ndarray, cell: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(body, finite face) pairs to test: the faces the body's cell lists, or all of them
        for a body reaching farther than pad (if it can reach one at all). ``cell``: the
        bodies' cells (``cells``)."""
        parts_b: list[np.ndarray] = []
        parts_f: list[np.ndarray] = []
        listed = reach <= self.pad
        every = bool(listed.all())  # the usual case: no body reaches past its cell's list
        table = self.fin_table
        if table is not None:
            # Each listed body's row of the table: its cell's faces in order.
            some = None if every else np.flatnonzero(listed)
            rows = table.take(cell if some is None else cell.take(some), axis=0)
            has = rows >= 0
            fb, _ = np.nonzero(has)
            if len(fb):
                ff = rows[has].astype(np.intp)
                parts_b.append(fb if some is None else some.take(fb))
                parts_f.append(ff if self._ident else self._slot_face.take(ff))
            total = 0
        else:
            cnt = self.count.take(cell) if every else np.where(listed, self.count[cell], 0)
            total = int(cnt.sum())
        if total:
            # Body b's k-th pair is the k-th face of its cell's list:
            # faces_of[start[cell_b] + k], with k = (pair index) - (b's first pair index).
            first = np.cumsum(cnt)
            first -= cnt
            parts_b.append(np.repeat(np.arange(len(reach)), cnt))
            shift = self.start.take(cell)
            shift -= first
            shift = np.repeat(shift, cnt)
            shift += np.arange(total)
            parts_f.append(self.faces_of.take(shift))
        if not every:
            far = np.flatnonzero(~listed & (self._ring[cell] <= reach))
        if not every and len(far):
            parts_b.append(np.repeat(far, self.n_finite))
            parts_f.append(np.tile(self.finite, len(far)))
        if not parts_b:
            return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
        if len(parts_b) == 1:
            return parts_b[0], parts_f[0]
        return np.concatenate(parts_b), np.concatenate(parts_f)


_FLIP = np.array([1, -1, 1, -1], dtype=np.intp)  # for ``FaceGrid._least``'s test of windows

#: The most entries a cell table (``FaceGrid.table``) may hold: beyond it (faces crowded in a
#: cell) the lists are read from their sorted form.
TABLE_SIZE = 4_000_000


def _as_table(
    cells_sorted: np.ndarray, faces_sorted: np.ndarray, counts: np.ndarray
) -> np.ndarray | None:
    """Lists sorted by cell (each cell's faces in order, ``counts`` of them) as the rows of a
    table, -1 past each list's end; None when it would hold more than TABLE_SIZE entries."""
    width = max(int(counts.max()), 1)
    if len(counts) * width > TABLE_SIZE:
        return None
    start = np.cumsum(counts) - counts
    table = np.full((len(counts), width), -1, dtype=np.int32)
    table[cells_sorted, np.arange(len(cells_sorted)) - start[cells_sorted]] = faces_sorted
    return table


def _length2(a: np.ndarray, b: np.ndarray) -> float:
    """|b - a|^2 of two points (2,), as ``FaceGrid._distances`` has always taken it."""
    ab = b - a
    return float(ab @ ab)


def _insert(
    table: np.ndarray, cells: np.ndarray, slot: int, face: int, key: np.ndarray | None
) -> np.ndarray | None:
    """Put ``slot`` (face index ``face``) into the lists of ``cells``, each in its place by
    ``key`` (the slots' order: ``FaceGrid._keys``; None: last, after every face listed), in
    place; a wider table when a list is full (the old one otherwise), None when a wider one
    would hold more than TABLE_SIZE."""
    if not len(cells):
        return table
    rows = table.take(cells, axis=0)
    has = rows >= 0
    count = has.sum(axis=1)
    width = table.shape[1]
    if int(count.max()) >= width:
        wider = width + max(2, width // 2)
        if len(table) * wider > TABLE_SIZE:
            return None
        grown = np.full((len(table), wider), -1, dtype=table.dtype)
        grown[:, :width] = table
        table = grown
        rows = table.take(cells, axis=0)
        has = rows >= 0
        width = wider
    if key is None:  # it goes last
        table[cells, count] = slot
        return table
    before = has & (key.take(np.where(has, rows, 0)) < face)
    pos = before.sum(axis=1)[:, None]
    col = np.arange(width)
    shifted = np.empty_like(rows)
    shifted[:, 0] = -1
    shifted[:, 1:] = rows[:, :-1]
    table[cells] = np.where(col < pos, rows, np.where(col == pos, slot, shifted))
    return table


def _take_out(table: np.ndarray, cells: np.ndarray, slot: int) -> None:
    """Take ``slot`` out of the lists of ``cells`` (each holds it), in place."""
    if not len(cells):
        return
    rows = table.take(cells, axis=0)
    pos = np.argmax(rows == slot, axis=1)[:, None]
    shifted = np.empty_like(rows)
    shifted[:, -1] = -1
    shifted[:, :-1] = rows[:, 1:]
    table[cells] = np.where(np.arange(rows.shape[1]) < pos, rows, shifted)
