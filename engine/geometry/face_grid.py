"""The broadphase for static faces: a uniform grid over them, built and looked up.

A body of radius r at x meets a face only if its distance from the face is at most r plus
how far it moves. The grid answers, for many bodies at once and in a few array operations,
a lower bound on that distance (``FaceGrid.gap``) and the few faces worth the exact tests
(``FaceGrid.listed``, ``pairs``, ``listed_fast``).

The cells. The finite faces (segments and discs, each a capsule: the points within rad of a
segment a-b) are covered by a square grid of side h = span / 384 over their extent grown by a
margin m = max(0.02 span, 1e-3). The distance from a face is 1-Lipschitz (it changes by at
most |x - x'| between two points), so over a cell it is at least its value at the centre
less half the diagonal, h / sqrt(2): each cell keeps that bound, least over the faces
(``FaceGridEdits.distances``), up to far = 16 h (a farther cell holds far, still a lower
bound). A cell lists the faces whose bound there is at most pad = 4 h; a body reaching at
most pad from a point of the cell is within pad + h / sqrt(2) of the centre, so every face it
can reach is listed. A ring of cells around the grid holds m: the faces are at least m from
any point outside, and a point is found in a cell by clipping to the ring, with no test of
inside (``cells``). Since pad = 4 h <= 4 (1.04 span) / 384 < m, a body out in the ring that
reaches at most pad meets no finite face, and the ring's lists are empty.

The endless faces. Lines without end (a Plane, a Box's walls) are few. The signed distance
from one, n.x - (n.p + rho), is linear, so over a cell it is at least its value at the
centre less h / sqrt(2) (less 1e-9 h more, for rounding): the bounds of ``gap`` include them,
and inside the grid one look-up is the whole lower bound. The grid is grown to a Box's
corners when that costs at most a factor 4 in extent, and then a body outside it is in a
wall (its ring holds -inf); otherwise ``gap`` adds each endless face's distance out there.

The quick lists (``_fast_lists``). On the free side of an endless face the distance from it
is the distance from its line, and over the grid from the line's piece between the
projections of the grid's corners, grown by h at each end: a capsule, listed and tested like
the finite faces. A cell wholly on the free side of every endless face is ``safe``: a body
there reaching at most pad finds every face it can reach in one row of ``table``. A floor's
line is put just under a cell's lower edge (by 1e-6 h), so a ball resting on it is in a
safe cell.

The tables and their in-place edits when colliders are added or taken out are their own
modules (engine.geometry.cell_table, engine.geometry.face_grid_edits); a step's first looks, which
use the grid, are engine.geometry.face_looks (``near``, ``narrow``, ``reach``), above this one.
"""

from __future__ import annotations

import math

import numpy as np

from .cell_table import as_table
from .face_grid_edits import FaceGridEdits, length2
from .faces import Faces, dot

__all__ = ["FaceGrid"]


class FaceGrid(FaceGridEdits):
    """The broadphase for static faces: a uniform grid over the finite faces.

    Each cell stores a lower bound on the distance from any of its points to the nearest
    finite face (the exact distance from its centre, less half its diagonal), so a body whose
    path cannot reach that far is skipped in one comparison, and the list of the faces that
    lie within ``pad`` of the cell, so a body that can reach one meets only those. Outside the
    grid every finite face is at least ``margin`` away. Lines without end (a Plane, a Box's
    walls) are few: the grid covers a Box's corners too, its cells' bounds for the first look
    (``gap``) count them as well, and the narrow pass checks them against each body near
    one directly.

    A game adds and takes out colliders between steps: ``added`` and ``removed``
    (engine.geometry.face_grid_edits) change the grid in place, in the new or old faces' windows of
    cells, and leave it as building it afresh would (the same bounds, lists in the same
    order, capsules), unless that would lay it differently (its extent or its endless faces
    change): then the caller drops it. The lists hold slots, each a face's index when it was
    listed (``_slot_face`` gives its index now), so faces renumbered by a change need no pass
    over the lists.
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
        self.gx, self.gy, self.half_diag = gx, gy, half_diag
        # What a collider added or taken out (``added``, ``removed``) needs: the extent the
        # grid was laid over, and each face's capsule and window of cells. The lists hold
        # slots, each a face's place when it was listed; ``_slot_face`` gives its index now.
        self._ext = (np.minimum(A, Bq).min(axis=0), np.maximum(A, Bq).max(axis=0), rad.max())
        self._slot_face = np.arange(F, dtype=np.intp)
        self._face_slot = np.arange(F, dtype=np.intp)
        self._slot_inf = np.concatenate([faces.infinite, np.zeros(len(faces.c), dtype=bool)])
        # Each finite face's capsule: a, b, rad, and |b - a|^2 as ``distances`` takes it.
        self._seg = np.full((F, 6), np.nan)
        self._win = np.zeros((F, 4), dtype=np.intp)  # its window of cells: i0, i1, j0, j1
        # Whether every slot is its face's index (true until a face is added or taken out).
        bound = np.full((nx, ny), self.far)
        cell_parts: list[np.ndarray] = []
        face_parts: list[np.ndarray] = []
        for k in range(self.n_finite):
            a, b, rr = A[k], Bq[k], rad[k]
            f = int(self.finite[k])
            i0, i1, j0, j1 = win = self.window(a, b, rr)
            dist = self.distances(a, b, rr, win)
            np.minimum(bound[i0:i1, j0:j1], dist, out=bound[i0:i1, j0:j1])
            di, dj = np.nonzero(dist <= self.pad)
            cell_parts.append((i0 + di) * ny + (j0 + dj))
            face_parts.append(np.full(len(di), f, dtype=np.intp))
            self._seg[f] = (a[0], a[1], b[0], b[1], rr, length2(a, b))
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
        self.table = as_table(cells_sorted, faces_sorted, counts)
        #: The finite faces' lists alone as a table too (``listed``), when they fit one:
        #: rows can take a face or give one up in place (``added``, ``removed``). Without it
        #: (faces crowded in a cell) ``listed`` reads the sorted lists, and a change of the
        #: colliders builds the grid afresh.
        self.fin_table = None
        if self.table is not None:
            if wall_cells:
                cells_fin = np.repeat(np.arange(len(self.count)), self.count)
                self.fin_table = as_table(cells_fin, self.faces_of, self.count)
            else:
                self.fin_table = self.table
        # Each face's capsule numbers in one table (a row per face) for ``narrow``.
        self.cap = np.column_stack([self.cap_a, self.cap_ab, self.cap_inv, self.cap_rad])

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
