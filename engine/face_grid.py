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
        bound = np.full((nx, ny), self.far)
        cell_parts: list[np.ndarray] = []
        face_parts: list[np.ndarray] = []
        for k in range(self.n_finite):
            a, b, rr = A[k], Bq[k], rad[k]
            # Only cells within `far` of the face (its box, grown) can hold a nearer bound.
            grow = rr + self.far + h
            i0 = max(int((min(a[0], b[0]) - grow - self.lo[0]) / h), 0)
            i1 = min(int((max(a[0], b[0]) + grow - self.lo[0]) / h) + 1, nx)
            j0 = max(int((min(a[1], b[1]) - grow - self.lo[1]) / h), 0)
            j1 = min(int((max(a[1], b[1]) + grow - self.lo[1]) / h) + 1, ny)
            cx, cy = np.meshgrid(gx[i0:i1], gy[j0:j1], indexing="ij")
            ab = b - a
            ab2 = float(ab @ ab)
            u = ((cx - a[0]) * ab[0] + (cy - a[1]) * ab[1]) / ab2 if ab2 > 0 else cx * 0.0
            u = np.clip(u, 0.0, 1.0)
            # No point of a cell is nearer the face than its centre less half its diagonal.
            dist = np.hypot(cx - a[0] - u * ab[0], cy - a[1] - u * ab[1]) - rr - half_diag
            np.minimum(bound[i0:i1, j0:j1], dist, out=bound[i0:i1, j0:j1])
            di, dj = np.nonzero(dist <= self.pad)
            cell_parts.append((i0 + di) * ny + (j0 + dj))
            face_parts.append(np.full(len(di), self.finite[k], dtype=np.intp))
        self.bound = bound
        # The bounds with a ring of cells around them holding the margin: any point outside
        # the grid is looked up in the ring (clipped), so a lookup needs no inside test.
        ring = np.full((nx + 2, ny + 2), self.margin)
        ring[1:-1, 1:-1] = bound
        self._ring = ring.reshape(-1)
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
        self.boxed = faces.boxed and covers
        if self.n_inf:
            both = bound.copy()
            for k in range(self.n_inf):
                (pnx, pny), c = self.inf_n[k], self.inf_c[k]
                at = np.add.outer(gx * pnx, gy * pny)  # cx n_x + cy n_y, cell by cell
                at -= c
                at -= half_diag + 1e-9 * h
                np.minimum(both, at, out=both)
            ring = np.full((nx + 2, ny + 2), -np.inf if self.boxed else self.margin)
            ring[1:-1, 1:-1] = both
            self._gap_ring = ring.reshape(-1)
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
        width = max(int(counts.max()), 1)
        self.table: np.ndarray | None = None
        if len(counts) * width <= 4_000_000:  # else (faces crowded in a cell) the other way
            start = np.cumsum(counts) - counts
            table = np.full((len(counts), width), -1, dtype=np.int32)
            table[cells_sorted, np.arange(len(cells_sorted)) - start[cells_sorted]] = faces_sorted
            self.table = table
        # Each face's capsule numbers in one table (a row per face) for ``narrow``.
        self.cap = np.column_stack([self.cap_a, self.cap_ab, self.cap_inv, self.cap_rad])

    def listed_fast(self, cell: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(body, face) pairs from ``table`` for bodies in safe cells reaching at most pad:
        each body's listed faces, bodies in order, each body's faces in list order."""
        assert self.table is not None
        rows = self.table.take(cell, axis=0)
        has = rows >= 0
        fb, _ = np.nonzero(has)
        return fb, rows[has].astype(np.intp)

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
